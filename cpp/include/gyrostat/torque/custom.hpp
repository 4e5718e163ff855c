// A torque the user writes: a function the core calls, compiled or given by the bindings.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include "gyrostat/attitude.hpp"
#include "gyrostat/body.hpp"
#include "gyrostat/torque/parameter.hpp"

namespace gyrostat::torque {

/// The C signature of a compiled torque function (SciPy's LowLevelCallable convention: the last
/// argument is the callable's user_data):
///
///   int torque(double t, const double* omega, const double* quaternion, double* moment, void* user_data)
///
/// omega: ω (3 numbers, body axes); quaternion: q = (w, x, y, z), body → inertial (4 numbers), or
/// NULL for a torque declared without the attitude; moment: M (3 numbers, body axes) to write.
/// It returns 0, or a non-zero code that stops the run with an error naming the torque. It is
/// called from any thread at once (ensembles), so it must not keep state between calls.
using TorqueFunctionPointer = int (*)(double, const double*, const double*, double*, void*);
/// The optional Jacobian, same arguments: writes ∂M/∂ω, 9 numbers row-major (d[3 i + j] = ∂M_i/∂ω_j).
/// A vectorised torque (below) keeps this scalar Jacobian.
using JacobianFunctionPointer = TorqueFunctionPointer;

/// The vectorised signature: n members at once, structure of arrays (member l = 0..n−1):
///
///   int torque(int n, const double* t, const double* omega, const double* quaternion, double* moment, void* user_data)
///
/// t[l]: member l's time (each member of a SIMD batch has its own); omega[i n + l]: ω_i of member l
/// (3n numbers, body axes); quaternion[i n + l]: q_i of member l, i = w, x, y, z (4n numbers), or
/// NULL without the attitude; moment[i n + l]: M_i of member l (3n numbers) to write. Same return
/// code and thread rules as above; besides, member l's M must depend on member l's numbers only,
/// computed the same whatever n (then a member's result does not depend on the batch it ran in).
/// The SIMD batches of an ensemble (integrate/batch.hpp) call it once per DOP853 stage for their W
/// lanes (n = W, the lanes' arrays passed as they are); every other path calls it with n = 1.
using VectorTorqueFunctionPointer = int (*)(int, const double*, const double*, const double*, double*, void*);

/// A compiled vectorised torque function and its user_data (null function: none).
struct VectorForm {
    VectorTorqueFunctionPointer function = nullptr;
    void* user_data = nullptr;
    bool operator==(const VectorForm& o) const { return function == o.function && user_data == o.user_data; }
};

/// "CustomTorque 'label': the compiled function returned <status> at t = <t>" (`where`: the time,
/// or the times of a batch's members).
inline std::string compiled_failure(const std::string& label, const char* what, int status, const std::string& where) {
    return "CustomTorque '" + label + "': the compiled " + what + " returned " + std::to_string(status) + " at " + where;
}

/// What the core calls for a user's torque: a compiled function (below) or what the bindings make
/// of a Python callable (which takes the GIL).
class TorqueFunction {
public:
    virtual ~TorqueFunction() = default;
    /// M(t, ω[, q]) in body axes; throws (naming the torque) when the function fails.
    virtual Vec3 torque(double t, const Vec3& omega, const Eigen::Vector4d* quaternion) const = 0;
    /// ∂M/∂ω into d and true, or false when the user gave no Jacobian.
    virtual bool jacobian(double t, const Vec3& omega, const Eigen::Vector4d* quaternion, Mat3& d) const = 0;
    /// One call at a time, whatever the threads (a Python callable: it holds the GIL).
    virtual bool serialised() const { return true; }
    /// The compiled vectorised form, which the SIMD batches call for W members at once (none:
    /// a scalar or Python function).
    virtual VectorForm vector_form() const { return {}; }
};

/// A compiled torque function, scalar or vectorised (C signatures above; the vectorised one is
/// called with n = 1 here), and its optional Jacobian.
class CompiledTorqueFunction final : public TorqueFunction {
public:
    CompiledTorqueFunction(std::string label, TorqueFunctionPointer torque, void* user_data,
                           JacobianFunctionPointer jacobian = nullptr, void* jacobian_data = nullptr)
        : label_(std::move(label)), torque_(torque), data_(user_data), jacobian_(jacobian), jacobian_data_(jacobian_data) {
        if (!torque_) throw std::invalid_argument("CustomTorque '" + label_ + "': the function pointer is null");
    }
    CompiledTorqueFunction(std::string label, VectorForm vector, JacobianFunctionPointer jacobian = nullptr,
                           void* jacobian_data = nullptr)
        : label_(std::move(label)), vector_(vector), jacobian_(jacobian), jacobian_data_(jacobian_data) {
        if (!vector_.function) throw std::invalid_argument("CustomTorque '" + label_ + "': the function pointer is null");
    }
    bool serialised() const override { return false; }  ///< called from every thread at once
    VectorForm vector_form() const override { return vector_; }
    Vec3 torque(double t, const Vec3& omega, const Eigen::Vector4d* quaternion) const override {
        Vec3 m = Vec3::Zero();
        const double* q = quaternion ? quaternion->data() : nullptr;
        const int status = vector_.function ? vector_.function(1, &t, omega.data(), q, m.data(), vector_.user_data)
                                            : torque_(t, omega.data(), q, m.data(), data_);
        if (status != 0) throw std::runtime_error(compiled_failure(label_, "function", status, "t = " + format_value(t)));
        return m;
    }
    bool jacobian(double t, const Vec3& omega, const Eigen::Vector4d* quaternion, Mat3& d) const override {
        if (!jacobian_) return false;
        double rows[9] = {};
        const int status = jacobian_(t, omega.data(), quaternion ? quaternion->data() : nullptr, rows, jacobian_data_);
        if (status != 0) throw std::runtime_error(compiled_failure(label_, "Jacobian", status, "t = " + format_value(t)));
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) d(i, j) = rows[3 * i + j];
        return true;
    }

private:
    std::string label_;
    TorqueFunctionPointer torque_ = nullptr;
    void* data_ = nullptr;
    VectorForm vector_;
    JacobianFunctionPointer jacobian_ = nullptr;
    void* jacobian_data_ = nullptr;
};

/// A torque the user writes, M = f(t, ω) or f(t, ω, q) in body axes (`attitude`: f takes q; only
/// models that carry the attitude take such a torque). Its Jacobian ∂M/∂ω is the user's, or
/// central difference quotients with steps h_j = 1e-6 max(1, |ω_j|) (error O(h²) relative, ~1e-12;
/// 6 calls). It has no averaged contribution and no Taylor coefficients (the models refuse it
/// there), and is never folded into the affine part. A compiled vectorised function (above) runs
/// in the SIMD batches of an ensemble (DOP853), called once per stage for the batch's W members
/// (model/gyrostat.hpp: GyrostatLanes); any other runs its members one at a time.
///
/// On a body given by its inertia tensor (Body::from_inertia) f still sees the user's frame: the
/// model's principal-axes ω_p and q_p become ω = R ω_p and q = q_p ⊗ q_R* before the call, and
/// M_p = Rᵀ M, ∂M_p/∂ω_p = Rᵀ (∂M/∂ω) R after it (in_principal_axes).
struct Custom {
    static constexpr const char* name = "custom";
    static constexpr const char* python_name = "CustomTorque";
    static constexpr const char* description =
        "a torque the user writes: M = f(t, omega) or f(t, omega, quaternion) in body axes, a Python callable or a "
        "compiled function";
    static constexpr bool optional_attitude = true;

    std::shared_ptr<const TorqueFunction> function;
    std::string label;      ///< the function's name, for messages and the repr
    bool attitude = false;  ///< f takes the quaternion
    /// What the front end made `function` from, opaque here (the bindings keep the user's objects:
    /// the factory and the keyword arguments it was called with, which sensitivities move).
    std::shared_ptr<const void> origin;

    Custom(std::shared_ptr<const TorqueFunction> f, std::string name, bool with_attitude)
        : function(std::move(f)), label(std::move(name)), attitude(with_attitude) {
        if (!function) throw std::invalid_argument("CustomTorque '" + label + "': no function");
    }

    bool uses_attitude() const { return attitude; }
    /// The user's function (torque/set.hpp: a torque that calls one; the front end resets a Python
    /// function's state before a run, an ensemble of serialised ones runs on one thread).
    const TorqueFunction& user_function() const { return *function; }
    /// The compiled vectorised function the SIMD batches call (none: a scalar or Python function,
    /// or a body given by its inertia tensor, whose frame the batches do not rotate).
    VectorForm vector_form() const { return rotated_ ? VectorForm{} : function->vector_form(); }

    /// The same function on the principal axes of `body` (the comment above the class).
    Custom in_principal_axes(const Body& body) const {
        Custom rotated = *this;
        rotated.rotated_ = !body.principal();
        rotated.axes_ = body.principal_axes();
        const Eigen::Vector4d& q = body.principal_quaternion();
        rotated.axes_conjugate_ = Eigen::Vector4d(q[0], -q[1], -q[2], -q[3]);
        return rotated;
    }

    /// M = f(t, ω[, q]).
    Vec3 operator()(double t, const Vec3& omega, const Vec3& /*moments*/, const Eigen::Vector4d* quaternion) const {
        const Eigen::Vector4d* q = attitude ? quaternion : nullptr;
        if (!rotated_) return function->torque(t, omega, q);
        const Eigen::Vector4d q_user = q ? quaternion_product(*q, axes_conjugate_) : Eigen::Vector4d::Zero();
        return axes_.transpose() * function->torque(t, axes_ * omega, q ? &q_user : nullptr);
    }
    /// The user's ∂M/∂ω, or central difference quotients.
    void add_jacobian(double t, const Vec3& omega, const Vec3& moments, const Eigen::Vector4d* quaternion, Mat3& d) const {
        const Eigen::Vector4d* q = attitude ? quaternion : nullptr;
        Mat3 user;
        const Eigen::Vector4d q_user = q && rotated_ ? quaternion_product(*q, axes_conjugate_) : Eigen::Vector4d::Zero();
        if (function->jacobian(t, rotated_ ? Vec3(axes_ * omega) : omega, q && rotated_ ? &q_user : q, user)) {
            d += rotated_ ? Mat3(axes_.transpose() * user * axes_) : user;
            return;
        }
        for (int j = 0; j < 3; ++j) {
            const double h = 1e-6 * std::max(1.0, std::abs(omega[j]));
            Vec3 up = omega, down = omega;
            up[j] += h, down[j] -= h;
            d.col(j) += ((*this)(t, up, moments, q) - (*this)(t, down, moments, q)) / (up[j] - down[j]);
        }
    }
    bool axisymmetric() const { return false; }

private:
    bool rotated_ = false;
    Mat3 axes_ = Mat3::Identity();
    Eigen::Vector4d axes_conjugate_ = Eigen::Vector4d(1.0, 0.0, 0.0, 0.0);
};

}  // namespace gyrostat::torque
