// States in the user's body frame, runs in the principal axes: the conversions at the engine's
// edges for a body given by its inertia tensor (Body::from_inertia).
#pragma once

#include <Eigen/Core>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "gyrostat/attitude.hpp"
#include "gyrostat/body.hpp"
#include "gyrostat/model/system.hpp"

namespace gyrostat::model::frame {

/// A model declares beside its states which of them are vectors in body axes:
///   static constexpr std::array<int, n> body_vectors;   the first index of each 3-vector
/// (ω at 0; the moving mass's u and v), and with carries_attitude its quaternion body → inertial
/// at y[3..7). A state free of the body frame (an averaged model's slow variables) declares an
/// empty list. A model that declares nothing takes only bodies given in principal axes.
///
/// With R = body.principal_axes() (v_user = R v_p) and q_R its quaternion:
///   v_user = R v_p,   q_user = q_p ⊗ q_R*   (R(q_user) R = R(q_p): x_inertial = R(q_p) x_p),
/// and back v_p = Rᵀ v_user, q_p = q_user ⊗ q_R. Both are linear in the state.
template <class S, class = void>
struct declares_body_vectors : std::false_type {};
template <class S>
struct declares_body_vectors<S, std::void_t<decltype(S::body_vectors)>> : std::true_type {};

enum class To { User, Principal };

/// The body's rotation applied to one vector in place.
inline void rotate_vector(const Body& body, double* v, To to) {
    Eigen::Map<Vec3> x(v);
    x = to == To::User ? Vec3(body.principal_axes() * x) : Vec3(body.principal_axes().transpose() * x);
}

/// The body's rotation applied to an attitude quaternion (w, x, y, z) in place.
inline void rotate_quaternion(const Body& body, double* q, To to) {
    const Eigen::Vector4d& r = body.principal_quaternion();
    Eigen::Map<Eigen::Vector4d> x(q);
    x = quaternion_product(x, to == To::User ? Eigen::Vector4d(r[0], -r[1], -r[2], -r[3]) : r);
}

/// A state of the models whose state starts with ω (then, from 7 components on, the quaternion):
/// what a short initial state and an averaged model's lifted state are.
inline void convert_rate_state(const Body& body, double* y, Eigen::Index size, To to) {
    if (body.principal() || size < 3) return;
    rotate_vector(body, y, to);
    if (size >= 7) rotate_quaternion(body, y + 3, to);
}

/// Whether the model's states need converting.
template <class S>
bool rotated(const S& model) {
    return !model.body().principal();
}

/// Throws std::invalid_argument when the model cannot take the body it has in a rotated frame.
template <class S>
void require_frame(const S& model) {
    if constexpr (!declares_body_vectors<S>::value) {
        if (rotated(model))
            throw std::invalid_argument(std::string("the '") + S::family +
                                        "' model takes only a body given by its principal moments, not by an inertia "
                                        "tensor with products of inertia");
    } else {
        (void)model;
    }
}

/// A full state of a model of type S on `body` converted in place (what a dense output keeps: the
/// body, not the model, which may be gone when it is evaluated).
template <class S>
void convert_state(const Body& body, double* y, To to) {
    if constexpr (declares_body_vectors<S>::value) {
        if (body.principal()) return;
        for (int start : S::body_vectors) rotate_vector(body, y + start, to);
        if constexpr (system::carries_attitude<S>::value) rotate_quaternion(body, y + 3, to);
    } else {
        (void)body, (void)y, (void)to;
    }
}

/// A full state (S::dim components) converted in place.
template <class S>
void convert(const S& model, double* y, To to) {
    if (!rotated(model)) return;
    require_frame(model);
    convert_state<S>(model.body(), y, to);
}

/// The model's initial state in principal axes from a state given in the user's frame: a full
/// state is converted; a short one (ω alone, ω and the quaternion) is completed in the user's
/// frame first (the identity attitude is the user's axes) when the model's state has body
/// vectors, and is converted first when it has none (an averaged model's (a, r) from ω).
template <class S>
typename S::State initial_state(const S& model, const Eigen::VectorXd& given) {
    if (!rotated(model)) return system::initial_state(model, given);
    require_frame(model);
    if constexpr (declares_body_vectors<S>::value) {
        if (S::body_vectors.size() == 0 && given.size() != S::dim) {
            Eigen::VectorXd principal = given;
            convert_rate_state(model.body(), principal.data(), principal.size(), To::Principal);
            return system::initial_state(model, principal);
        }
    }
    typename S::State y = system::initial_state(model, given);
    convert(model, y.data(), To::Principal);
    return y;
}

/// A state (or a rate: the map is linear and constant) of model `from`'s principal axes written
/// in the principal axes of `to`, a model of the same type on another body (a parameter of the
/// body moved: its axes turn with it), through the user's frame: y_to = U_to⁻¹ U_from y.
template <class S>
void reframe(const S& from, const S& to, double* y) {
    if (!rotated(from) && !rotated(to)) return;
    convert(from, y, To::User);
    convert(to, y, To::Principal);
}

}  // namespace gyrostat::model::frame
