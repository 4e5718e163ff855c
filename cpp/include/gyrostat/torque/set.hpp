// A set of perturbation torques acting on one body: composition without virtual calls.
#pragma once

#include <algorithm>
#include <Eigen/Core>
#include <limits>
#include <optional>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <string>
#include <variant>
#include <vector>

#include "gyrostat/body.hpp"
#include "gyrostat/euler_poinsot.hpp"
#include "gyrostat/torque/constant.hpp"
#include "gyrostat/torque/custom.hpp"
#include "gyrostat/torque/dipole_field.hpp"
#include "gyrostat/torque/gravity_gradient.hpp"
#include "gyrostat/torque/inertial.hpp"
#include "gyrostat/torque/linear_damping.hpp"
#include "gyrostat/torque/magnetic.hpp"
#include "gyrostat/torque/moving_mass_damper.hpp"
#include "gyrostat/torque/resistive_medium.hpp"
#include "gyrostat/torque/viscous_cavity.hpp"

namespace gyrostat {

/// Every torque the library knows: adding a torque is its header and its line here. Each is a
/// small value type. It must give
///   Vec3 operator()(t, ω, J)                       the torque in body axes (J: principal moments);
///   void add_jacobian(t, ω, J, Mat3& dM_dω)        its derivative with respect to ω (an attitude
///                                                  torque's ∂M/∂q is the set's central difference:
///                                                  TorqueSet::add_attitude_jacobian);
///   bool axisymmetric()                            it commutes with rotations about body z;
/// and declare beside its equations (torque/parameter.hpp)
///   static name, python_name, description          its scene type, its Python class, one line,
///   static std::array<Parameter, n> parameters     name, shape, unit, axes, description, constraint,
///   static T from(const Values&)                   itself from named values (a scene table),
///   Values values() const                          the parameters it keeps.
/// The Python classes, the scene schema and every list of torques are generated from these.
/// It declares each capability it has; the models and integrators read the declarations (the
/// traits below), never its type:
///   static constexpr bool needs_attitude = true    it reads the attitude: operator()(t, ω, J, q)
///                                                  instead (q: the unit quaternion body → inertial;
///                                                  models without q refuse it: require_no_attitude);
///   static constexpr bool optional_attitude = true decided per instance: bool uses_attitude(), and
///                                                  operator()/add_jacobian take q as a pointer;
///   Vector2d averaged(t, a, r, A, C)               its (ȧ, ṙ) over the symmetric Euler–Poinsot
///                                                  motion (without it the averaged model refuses it);
///   Vec3 averaged_power(t, EulerPoinsot, J)        its ⟨ω_i M_i⟩ over the triaxial free motion in
///                                                  closed form (without it: quadrature);
///   AffineForm affine_form()                       M = M0 − Σ t^k D_k ω (torque/affine.hpp; the
///                                                  nutation-averaged top takes only these), and
///   static constexpr bool constant_coefficients    at most D_0: folded into one M0 − D ω, which the
///                                                  Taylor recursion and the SIMD lanes take;
///   VectorForm vector_form(), std::string label    a compiled function the SIMD lanes call for W
///                                                  members at once (DOP853 batches), and its name;
///   const TorqueFunction& user_function()          it calls the user's function (reset before a
///                                                  run; a serialised one keeps an ensemble on one thread);
///   static constexpr bool on_orbit = true          it reads the body's place on a circular orbit:
///                                                  a member `orbit`, T with_orbit(const CircularOrbit&);
///   T in_principal_axes(const Body&)               it moves itself to the principal axes (others are
///                                                  moved by their parameters' declared axes);
///   T prepared(const Vec3& moments)                what it computes once for the body's moments;
///   std::vector<Assumption> assumptions(const Motion&)   its validity numbers;
///   static constexpr bool keeps_momentum_norm = true     Jω·M ≡ 0;
///   static constexpr std::array<const char*, n> affine_in   the stored parameters M is affine in
///                                                  (the sensitivities' one-sided difference);
///   static constexpr std::array<const char*, n> inverse_in  those M is inversely proportional to
///                                                  (as 1/p: the same difference between p and 2p
///                                                  is −p/2 times ∂M/∂p, exact to rounding as well).
using AnyTorque = std::variant<torque::Constant, torque::LinearDamping, torque::ResistiveMedium,
                               torque::ViscousCavity, torque::MovingMassDamper, torque::GravityGradient,
                               torque::MagneticTorque, torque::DipoleFieldTorque, torque::InertialTorque,
                               torque::Custom>;

template <class T, class = void>
struct keeps_momentum_norm : std::false_type {};
template <class T>
struct keeps_momentum_norm<T, std::enable_if_t<T::keeps_momentum_norm>> : std::true_type {};

/// The stored parameters a torque declares M affine in (`affine_in`; none without it).
template <class T, class = void>
struct declares_affine_in : std::false_type {};
template <class T>
struct declares_affine_in<T, std::void_t<decltype(T::affine_in)>> : std::true_type {};
template <class T>
std::vector<std::string> affine_in() {
    if constexpr (declares_affine_in<T>::value)
        return std::vector<std::string>(T::affine_in.begin(), T::affine_in.end());
    else
        return {};
}

/// The stored parameters a torque declares M inversely proportional to (`inverse_in`; none without it).
template <class T, class = void>
struct declares_inverse_in : std::false_type {};
template <class T>
struct declares_inverse_in<T, std::void_t<decltype(T::inverse_in)>> : std::true_type {};
template <class T>
std::vector<std::string> inverse_in() {
    if constexpr (declares_inverse_in<T>::value)
        return std::vector<std::string>(T::inverse_in.begin(), T::inverse_in.end());
    else
        return {};
}

template <class T, class = void>
struct needs_attitude : std::false_type {};
template <class T>
struct needs_attitude<T, std::enable_if_t<T::needs_attitude>> : std::true_type {};

/// A torque whose dependence on the attitude is decided per instance (a user's torque): it
/// declares `optional_attitude = true`, `bool uses_attitude() const` and takes the attitude as a
/// pointer (nullptr: none), in operator() and add_jacobian.
template <class T, class = void>
struct optional_attitude : std::false_type {};
template <class T>
struct optional_attitude<T, std::enable_if_t<T::optional_attitude>> : std::true_type {};

/// Whether this torque reads the attitude.
template <class T>
bool uses_attitude(const T& x) {
    if constexpr (optional_attitude<T>::value)
        return x.uses_attitude();
    else
        return needs_attitude<T>::value;
}

/// A torque that reads the body's place on a circular orbit (`static constexpr bool on_orbit =
/// true`, a member `orbit` (torque::OrbitOfTorque: its own orbit or none) and `T
/// with_orbit(const CircularOrbit&) const`): the model gives it its orbit (TorqueSet::on_orbit).
template <class T, class = void>
struct on_orbit : std::false_type {};
template <class T>
struct on_orbit<T, std::enable_if_t<T::on_orbit>> : std::true_type {};

template <class T, class = void>
struct has_averaged : std::false_type {};
template <class T>
struct has_averaged<T, std::void_t<decltype(std::declval<const T&>().averaged(0.0, 0.0, 0.0, 1.0, 1.0))>>
    : std::true_type {};

/// A torque that gives its averaged power over the triaxial Euler–Poinsot motion in closed form
/// (`Vec3 averaged_power(t, const EulerPoinsot&, J)`: ⟨ω_i M_i⟩ per axis); the others are averaged
/// by quadrature (TorqueSet::averaged_power).
template <class T, class = void>
struct has_averaged_power : std::false_type {};
template <class T>
struct has_averaged_power<T, std::void_t<decltype(std::declval<const T&>().averaged_power(
                                 0.0, std::declval<const EulerPoinsot&>(), Vec3()))>> : std::true_type {};

/// A torque affine in ω with coefficients polynomial in t (torque/affine.hpp).
template <class T, class = void>
struct has_affine_form : std::false_type {};
template <class T>
struct has_affine_form<T, std::void_t<decltype(std::declval<const T&>().affine_form())>> : std::true_type {};

/// ... whose form is constant in t: folded into the set's one M0 − D ω.
template <class T, class = void>
struct folded : std::false_type {};
template <class T>
struct folded<T, std::enable_if_t<T::constant_coefficients>> : std::true_type {};

/// A torque the SIMD lanes may call for W members at once (`VectorForm vector_form() const`).
template <class T, class = void>
struct has_vector_form : std::false_type {};
template <class T>
struct has_vector_form<T, std::void_t<decltype(std::declval<const T&>().vector_form())>> : std::true_type {};

/// A torque that calls the user's function (`const TorqueFunction& user_function() const`).
template <class T, class = void>
struct calls_user_function : std::false_type {};
template <class T>
struct calls_user_function<T, std::void_t<decltype(std::declval<const T&>().user_function())>> : std::true_type {};

/// The user's function a torque calls (nullptr: none).
template <class T>
const torque::TorqueFunction* user_function_of(const T& x) {
    if constexpr (calls_user_function<T>::value)
        return &x.user_function();
    else
        return nullptr;
}

template <class T, class = void>
struct has_assumptions : std::false_type {};
template <class T>
struct has_assumptions<T, std::void_t<decltype(std::declval<const T&>().assumptions(std::declval<const torque::Motion&>()))>>
    : std::true_type {};

/// A torque's validity numbers over a motion (none for a torque that assumes nothing).
template <class T>
std::vector<torque::Assumption> assumptions_of(const T& x, const torque::Motion& motion) {
    if constexpr (has_assumptions<T>::value)
        return x.assumptions(motion);
    else
        return {};
}

/// A torque that moves itself to the principal axes (a user's function: Custom) declares
/// `T in_principal_axes(const Body&) const`; every other torque is moved by its declaration.
template <class T, class = void>
struct rotates_itself : std::false_type {};
template <class T>
struct rotates_itself<T, std::void_t<decltype(std::declval<const T&>().in_principal_axes(std::declval<const Body&>()))>>
    : std::true_type {};

/// A torque that computes something once for the moments of the body it acts on
/// (`T prepared(const Vec3& moments) const`: TorqueSet::in_principal_axes).
template <class T, class = void>
struct has_prepared : std::false_type {};
template <class T>
struct has_prepared<T, std::void_t<decltype(std::declval<const T&>().prepared(std::declval<const Vec3&>()))>>
    : std::true_type {};

/// x with its body-axes parameters (torque/parameter.hpp: Axes::Body) written in the principal
/// axes of `body`: v_p = Rᵀ v, D_p = Rᵀ D R (R = body.principal_axes(): v = R v_p); scalars and
/// inertial-axes parameters as they are. Rebuilt with T::from, so its checks run again.
template <class T>
T in_principal_axes(const T& x, const Body& body) {
    if constexpr (rotates_itself<T>::value) {
        return x.in_principal_axes(body);
    } else {
        if (body.principal()) return x;
        const Mat3& R = body.principal_axes();
        torque::Values values = x.values();
        for (const torque::Parameter& p : T::parameters) {
            if (p.axes != torque::Axes::Body || !values.has(p.name)) continue;
            if (p.shape == torque::Shape::Vector3) {
                values.set(p.name, Vec3(R.transpose() * values.vector(p.name)));
            } else if (p.shape == torque::Shape::Matrix3) {
                values.set(p.name, Mat3(R.transpose() * values.matrix(p.name) * R));
            } else if (p.shape == torque::Shape::Matrices) {
                std::vector<Mat3> rotated = values.matrices(p.name);
                for (Mat3& m : rotated) m = R.transpose() * m * R;
                values.set(p.name, std::move(rotated));
            }
        }
        return T::from(values);
    }
}

namespace detail {
template <class... Torques>
std::string python_names(std::variant<Torques...>*) {
    std::string names;
    ((names += (names.empty() ? "" : ", ") + std::string(Torques::python_name)), ...);
    return names;
}
}  // namespace detail

/// "ConstantTorque, LinearDamping, …": the Python names of every torque, for error messages.
inline std::string torque_python_names() { return detail::python_names(static_cast<AnyTorque*>(nullptr)); }

inline const char* torque_name(const AnyTorque& t) {
    return std::visit([](const auto& x) { return std::decay_t<decltype(x)>::name; }, t);
}

/// The torques on a body. Torques affine in ω with constant coefficients (constant, linear
/// damping) are folded at construction into one M0 − D ω, so the hot path costs one 3×3 product
/// whatever their number; the others are evaluated one by one. First-order averaging is linear
/// in the torques: the averaged right-hand side is the sum of each part's contribution.
class TorqueSet {
public:
    TorqueSet() = default;
    explicit TorqueSet(std::vector<AnyTorque> parts) : parts_(std::move(parts)) {
        for (const auto& part : parts_) fold(part);
    }

    const std::vector<AnyTorque>& parts() const { return parts_; }
    /// The same torques on the principal axes of `body` (in_principal_axes above), each with
    /// `T prepared(const Vec3& moments) const` given the body's principal moments (what it can
    /// compute once for the body it acts on: the moving-mass damper's coefficients). Every model
    /// applies it to the torques it is given.
    TorqueSet in_principal_axes(const Body& body) const {
        require_orbits();
        const bool any_prepared = std::any_of(parts_.begin(), parts_.end(), [](const AnyTorque& part) {
            return std::visit([](const auto& x) { return has_prepared<std::decay_t<decltype(x)>>::value; }, part);
        });
        if (body.principal() && !any_prepared) return *this;
        std::vector<AnyTorque> rotated;
        for (const auto& part : parts_)
            rotated.push_back(std::visit([&](const auto& x) -> AnyTorque {
                using T = std::decay_t<decltype(x)>;
                if constexpr (has_prepared<T>::value)
                    return gyrostat::in_principal_axes(x, body).prepared(body.moments());
                else
                    return gyrostat::in_principal_axes(x, body);
            }, part));
        return TorqueSet(std::move(rotated));
    }
    bool empty() const { return parts_.empty(); }
    bool has_damping() const { return has_damping_; }
    /// Only folded torques (constant affine coefficients): the right-hand side is a quadratic polynomial.
    bool is_affine() const { return others_.empty(); }
    /// Every torque keeps |Jω| (Jω·M ≡ 0; none at all counts).
    bool keeps_momentum_norm() const {
        for (const auto& part : parts_)
            if (!std::visit([](const auto& x) { return gyrostat::keeps_momentum_norm<std::decay_t<decltype(x)>>::value; }, part))
                return false;
        return true;
    }

    /// The first torque that needs the attitude (nullptr: none does).
    const char* needs_attitude() const {
        for (const auto& part : parts_) {
            const char* name = std::visit([](const auto& x) -> const char* {
                using T = std::decay_t<decltype(x)>;
                return gyrostat::uses_attitude(x) ? T::python_name : nullptr;
            }, part);
            if (name) return name;
        }
        return nullptr;
    }
    /// Throws std::invalid_argument naming the torque when one needs the attitude and the model
    /// (`model`, e.g. "Model(attitude=False)") does not carry it.
    void require_no_attitude(const std::string& model) const {
        if (const char* name = needs_attitude())
            throw std::invalid_argument(std::string(name) + " depends on the attitude, which " + model +
                                        " does not carry: use a model with the attitude quaternion (attitude=True)");
    }
    /// Some torque runs one call at a time (a user's Python function, which holds the GIL): an
    /// ensemble of such members runs on one thread, since more only hand the GIL back and forth.
    bool serialised() const {
        for (const auto& part : parts_)
            if (const torque::TorqueFunction* f = std::visit([](const auto& x) { return user_function_of(x); }, part);
                f && f->serialised())
                return true;
        return false;
    }
    /// The one orbit of a model with these torques: `model_orbit` when given, else the orbit the
    /// orbit torques were given (none: no orbit at all). Throws std::invalid_argument naming both
    /// when a torque's own orbit differs from the model's or from another torque's: one body is
    /// in one place.
    std::optional<torque::CircularOrbit> common_orbit(const std::optional<torque::CircularOrbit>& model_orbit) const {
        std::optional<torque::CircularOrbit> found = model_orbit;
        std::string owner = "the model's orbit";
        for (const auto& part : parts_)
            std::visit([&](const auto& x) {
                using T = std::decay_t<decltype(x)>;
                if constexpr (gyrostat::on_orbit<T>::value) {
                    if (!x.orbit.given()) return;
                    if (!found) {
                        found = *x.orbit, owner = std::string(T::python_name) + "'s orbit";
                    } else if (!found->same_as(*x.orbit)) {
                        throw std::invalid_argument(std::string(T::python_name) + " has its own orbit " + x.orbit->text() +
                                                    ", which differs from " + owner + " " + found->text() +
                                                    ": one body is on one orbit; give it once, to the model (orbit=...), "
                                                    "and leave it out of the torques");
                    }
                }
            }, part);
        return found;
    }
    /// The same torques, each orbit torque on `orbit` (after common_orbit: those with an orbit of
    /// their own have this one).
    TorqueSet on_orbit(const torque::CircularOrbit& orbit) const {
        std::vector<AnyTorque> placed;
        for (const auto& part : parts_)
            placed.push_back(std::visit([&](const auto& x) -> AnyTorque {
                if constexpr (gyrostat::on_orbit<std::decay_t<decltype(x)>>::value)
                    return x.with_orbit(orbit);
                else
                    return x;
            }, part));
        return TorqueSet(std::move(placed));
    }
    /// Throws std::invalid_argument naming the first orbit torque that has no orbit (neither its
    /// own nor the model's).
    void require_orbits() const {
        for (const auto& part : parts_)
            std::visit([](const auto& x) {
                if constexpr (gyrostat::on_orbit<std::decay_t<decltype(x)>>::value) (void)x.orbit.required(x.python_name);
            }, part);
    }

    /// The first torque without an averaged contribution (nullptr: every one has it).
    const char* without_averaged() const {
        for (const auto& part : parts_) {
            const char* name = std::visit([](const auto& x) -> const char* {
                using T = std::decay_t<decltype(x)>;
                return has_averaged<T>::value ? nullptr : T::python_name;
            }, part);
            if (name) return name;
        }
        return nullptr;
    }

    /// Every torque commutes with rotations about body z (none at all counts).
    bool axisymmetric() const {
        for (const auto& part : parts_)
            if (!std::visit([](const auto& x) { return x.axisymmetric(); }, part)) return false;
        return true;
    }

    /// Σ M_i(t, ω) (q: the attitude, for the torques that need it; a model without the attitude
    /// refused them at construction with require_no_attitude).
    Vec3 total(double t, const Vec3& omega, const Vec3& moments, const Eigen::Vector4d* attitude = nullptr) const {
        Vec3 m = folded_total(omega);
        for (const auto& part : others_) m += evaluate(part, t, omega, moments, attitude);
        return m;
    }
    /// The folded torques' M0 − D ω: total()'s first term, and all of it where is_affine().
    Vec3 folded_total(const Vec3& omega) const { return has_damping_ ? Vec3(constant_ - damping_ * omega) : constant_; }
    /// Σ ∂M_i/∂ω (at the attitude, for the torques that read it).
    Mat3 jacobian(double t, const Vec3& omega, const Vec3& moments, const Eigen::Vector4d* attitude = nullptr) const {
        Mat3 d = -damping_;
        for (const auto& part : others_)
            std::visit([&](const auto& x) {
                if constexpr (gyrostat::optional_attitude<std::decay_t<decltype(x)>>::value)
                    x.add_jacobian(t, omega, moments, attitude, d);
                else
                    x.add_jacobian(t, omega, moments, d);
            }, part);
        return d;
    }
    /// Σ ∂M_i/∂q of the torques that read the attitude, added to `d` (3 × 4, q = (w, x, y, z)):
    /// central differences in each component of q, step ε^{1/3} (|q| = 1: truncation and rounding
    /// both ~4e-11 relative; a torque normalises q, so the radial column is its formula's, which a
    /// tangent direction never weighs). The variational equations need it (model/variational.hpp:
    /// without it the sensitivities under an attitude torque were wrong by their own size); false,
    /// `d` untouched, where no torque reads the attitude.
    bool add_attitude_jacobian(double t, const Vec3& omega, const Vec3& moments, const Eigen::Vector4d& attitude,
                               Eigen::Matrix<double, 3, 4>& d) const {
        constexpr double step = 6.0554544523933395e-06;  // ε^{1/3}
        bool any = false;
        for (const auto& part : others_) {
            if (!std::visit([](const auto& x) { return gyrostat::uses_attitude(x); }, part)) continue;
            any = true;
            for (int k = 0; k < 4; ++k) {
                Eigen::Vector4d plus = attitude, minus = attitude;
                plus[k] += step;
                minus[k] -= step;
                d.col(k) += (evaluate(part, t, omega, moments, &plus) - evaluate(part, t, omega, moments, &minus)) / (2.0 * step);
            }
        }
        return any;
    }
    /// The torques outside the folded affine part, evaluated one by one.
    const std::vector<AnyTorque>& others() const { return others_; }
    /// The folded affine part: M = M0 − D ω (for the Taylor recursion).
    const Vec3& constant_part() const { return constant_; }
    const Mat3& damping_part() const { return damping_; }

    /// Σ (ȧ, ṙ)_i over the symmetric Euler–Poinsot motion with moments (A, A, C).
    Eigen::Vector2d averaged(double t, double a, double r, double A, double C) const {
        Eigen::Vector2d rates = Eigen::Vector2d::Zero();
        for (const auto& part : parts_)
            rates += std::visit([&](const auto& x) -> Eigen::Vector2d {
                if constexpr (has_averaged<std::decay_t<decltype(x)>>::value)
                    return x.averaged(t, a, r, A, C);
                else
                    throw std::logic_error(std::string(x.python_name) + ": no averaged contribution");
            }, part);
        return rates;
    }

    /// The averaged power per axis, P_i = ⟨ω_i M_i⟩ over one period of the triaxial Euler–Poinsot
    /// motion (the triaxial averaged model: d|G|²/dt = 2 Σ A_i P_i, dT/dt = Σ P_i; model/
    /// averaged_triaxial.hpp). Closed forms where they exist (docs/papers/triaxial_averaging.md §2):
    /// the folded M0 − D ω gives P_i = M0_i ⟨ω_i⟩ − D_ii ⟨ω_i²⟩ (⟨ω_i ω_j⟩ = 0 for i ≠ j; only the
    /// component of M0 along the axis circulated about acts), a torque with `averaged_power` its own;
    /// every other torque (a user's included) by the trapezoidal rule in the phase,
    ///   P_i ≈ (1/n) Σ_j ω_i(φ_j) M_i(t, ω(φ_j)),  φ_j = 2πj/n,  n = motion.nodes(tolerance)
    /// (EulerPoinsot::for_each_node: the elliptic functions on a quarter period),
    /// which converges geometrically for these periodic analytic integrands. Torques that need the
    /// attitude are refused by the model before (require_no_attitude).
    Vec3 averaged_power(double t, const EulerPoinsot& motion, const Vec3& moments, double tolerance) const {
        Vec3 power = Vec3::Zero();
        if (constant_.squaredNorm() != 0.0) power += constant_.cwiseProduct(motion.mean_omega());
        if (has_damping_) power -= damping_.diagonal().cwiseProduct(motion.mean_square());
        bool quadrature = false;
        for (const auto& part : others_)
            std::visit([&](const auto& x) {
                if constexpr (has_averaged_power<std::decay_t<decltype(x)>>::value)
                    power += x.averaged_power(t, motion, moments);
                else
                    quadrature = true;
            }, part);
        if (!quadrature) return power;
        const int n = motion.nodes(tolerance);
        Vec3 sum = Vec3::Zero();
        motion.for_each_node(n, [&](const Vec3& omega) {
            Vec3 m = Vec3::Zero();
            for (const auto& part : others_)
                if (!std::visit([](const auto& x) { return has_averaged_power<std::decay_t<decltype(x)>>::value; }, part))
                    m += evaluate(part, t, omega, moments, nullptr);
            sum += omega.cwiseProduct(m);
        });
        return power + sum / n;
    }

private:
    /// One torque M_i(t, ω) (with the attitude for the torques that read it).
    static Vec3 evaluate(const AnyTorque& part, double t, const Vec3& omega, const Vec3& moments,
                         const Eigen::Vector4d* attitude) {
        return std::visit([&](const auto& x) -> Vec3 {
            using T = std::decay_t<decltype(x)>;
            if constexpr (gyrostat::optional_attitude<T>::value) {
                return x(t, omega, moments, attitude);
            } else if constexpr (gyrostat::needs_attitude<T>::value) {
                if (!attitude) throw std::logic_error(std::string(x.python_name) + ": evaluated without the attitude");
                // A quaternion that became non-finite in a trial step (ω overflowed and q̇ with it)
                // is no rotation the user gave: its torque is not finite either, and the integrator
                // reports the non-finite state (status NonFiniteState), as for any other torque.
                if (!attitude->allFinite()) return Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
                return x(t, omega, moments, *attitude);
            } else {
                return x(t, omega, moments);
            }
        }, part);
    }

    /// A torque with constant affine coefficients joins M0 − D ω; every other is kept apart.
    void fold(const AnyTorque& part) {
        std::visit([&](const auto& x) {
            if constexpr (folded<std::decay_t<decltype(x)>>::value) {
                const torque::AffineForm form = x.affine_form();
                constant_ += form.constant;
                if (!form.damping.empty()) damping_ += form.damping.front(), has_damping_ = true;
            } else {
                others_.push_back(part);
            }
        }, part);
    }

    std::vector<AnyTorque> parts_;
    std::vector<AnyTorque> others_;
    Vec3 constant_ = Vec3::Zero();
    Mat3 damping_ = Mat3::Zero();
    bool has_damping_ = false;
};

}  // namespace gyrostat
