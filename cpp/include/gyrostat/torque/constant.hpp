// A constant torque fixed in body axes.
#pragma once

#include <Eigen/Core>
#include <array>

#include "gyrostat/body.hpp"
#include "gyrostat/torque/affine.hpp"
#include "gyrostat/torque/parameter.hpp"

namespace gyrostat::torque {

/// M = (M1, M2, M3), constant in body axes (paper 000: ε(M1, M2, M3)).
/// Assumptions: none; it does not need the attitude.
///
/// Averaged over the symmetric Euler–Poinsot motion p = a cos φ, q = a sin φ
/// (φ̇ = (C − A) r / A):  ȧ = 0,  ṙ = M3 / C.  M1, M2 average out; in the full motion they shift
/// the (p, q) circle by |M⊥|/(A |ν|), ν = (C − A) r / A, so the averaging fails as r → 0.
struct Constant {
    static constexpr const char* name = "constant";
    static constexpr const char* python_name = "ConstantTorque";
    static constexpr const char* description = "a constant torque in body axes";
    static constexpr std::array<Parameter, 1> parameters{{
        {"moment", "moment", Shape::Vector3, "N m", "M in body axes"},
    }};
    /// M is affine in these (a sensitivity's ∂f/∂p is then a one-sided difference, exact).
    static constexpr std::array<const char*, 1> affine_in{{"moment"}};

    Vec3 moment = Vec3::Zero();

    explicit Constant(const Vec3& m) : moment(m) { require(python_name, parameters[0], m); }
    static Constant from(const Values& v) { return Constant(v.vector("moment")); }
    Values values() const {
        Values v;
        v.set("moment", moment);
        return v;
    }

    Vec3 operator()(double /*t*/, const Vec3& /*omega*/, const Vec3& /*moments*/) const { return moment; }
    /// M0 = moment, no ω term (torque/affine.hpp).
    AffineForm affine_form() const { return {moment, {}}; }
    static constexpr bool constant_coefficients = true;
    /// ∂M/∂ω = 0.
    void add_jacobian(double /*t*/, const Vec3& /*omega*/, const Vec3& /*moments*/, Mat3& /*dM_domega*/) const {}
    /// (ȧ, ṙ) of the averaged symmetric motion.
    Eigen::Vector2d averaged(double /*t*/, double /*a*/, double /*r*/, double /*A*/, double C) const {
        return {0.0, moment.z() / C};
    }
    /// Commutes with rotations about body z (then the (a, r) reduction is exact): M1 = M2 = 0.
    bool axisymmetric() const { return moment.x() == 0.0 && moment.y() == 0.0; }
};

}  // namespace gyrostat::torque
