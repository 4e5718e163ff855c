// A constant torque fixed in body axes.
#pragma once

#include "gyrostat/body.hpp"

namespace gyrostat::torque {

/// M = (M1, M2, M3), constant in body axes (paper 000: ε(M1, M2, M3)).
/// Assumptions: none; it does not need the attitude.
struct Constant {
    Vec3 moment = Vec3::Zero();

    explicit Constant(const Vec3& m) : moment(m) { require_finite(m, "ConstantTorque: moment"); }

    Vec3 operator()(double /*t*/, const Vec3& /*omega*/) const { return moment; }
    /// ∂M/∂ω = 0.
    void add_jacobian(double /*t*/, const Vec3& /*omega*/, Mat3& /*dM_domega*/) const {}
    static constexpr const char* name = "constant";
};

}  // namespace gyrostat::torque
