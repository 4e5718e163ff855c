// A constant torque fixed in body axes.
#pragma once

#include <Eigen/Core>

#include "gyrostat/body.hpp"

namespace gyrostat::torque {

/// M = (M1, M2, M3), constant in body axes (paper 000: ε(M1, M2, M3)).
/// Assumptions: none; it does not need the attitude.
///
/// Averaged over the symmetric Euler–Poinsot motion p = a cos φ, q = a sin φ
/// (φ̇ = (C − A) r / A):  ȧ = 0,  ṙ = M3 / C.  M1, M2 average out; in the full motion they shift
/// the (p, q) circle by |M⊥|/(A |ν|), ν = (C − A) r / A, so the averaging fails as r → 0.
struct Constant {
    Vec3 moment = Vec3::Zero();

    explicit Constant(const Vec3& m) : moment(m) { require_finite(m, "ConstantTorque: moment"); }

    Vec3 operator()(double /*t*/, const Vec3& /*omega*/, const Vec3& /*moments*/) const { return moment; }
    /// ∂M/∂ω = 0.
    void add_jacobian(double /*t*/, const Vec3& /*omega*/, const Vec3& /*moments*/, Mat3& /*dM_domega*/) const {}
    /// (ȧ, ṙ) of the averaged symmetric motion.
    Eigen::Vector2d averaged(double /*t*/, double /*a*/, double /*r*/, double /*A*/, double C) const {
        return {0.0, moment.z() / C};
    }
    static constexpr const char* name = "constant";
};

}  // namespace gyrostat::torque
