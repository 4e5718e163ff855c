// A constant torque fixed in inertial space.
#pragma once

#include <Eigen/Core>
#include <array>

#include "gyrostat/attitude.hpp"
#include "gyrostat/body.hpp"
#include "gyrostat/torque/parameter.hpp"

namespace gyrostat::torque {

/// A torque constant in inertial space (a thruster held on an inertial target, a constant
/// external couple):
///
///   M = R(q)ᵀ M_I        (M_I inertial, N m; R(q) body → inertial),
///
/// so that the inertial angular momentum grows linearly: G_I(t) = G_I(0) + M_I t (the test's
/// closed form). Needs the attitude; ∂M/∂ω = 0; no averaged contribution (|G| changes through
/// G's direction, which the averaged model does not carry: it refuses this torque).
struct InertialTorque {
    static constexpr const char* name = "inertial";
    static constexpr const char* python_name = "InertialTorque";
    static constexpr const char* description = "a constant torque fixed in inertial space (needs the attitude)";
    static constexpr std::array<Parameter, 1> parameters{{
        {"moment", "moment", Shape::Vector3, "N m", "M_I in inertial axes", Constraint::Finite, 0, true, nullptr, Axes::Inertial},
    }};
    /// M is affine in these (a sensitivity's ∂f/∂p is then a one-sided difference, exact).
    static constexpr std::array<const char*, 1> affine_in{{"moment"}};
    static constexpr bool needs_attitude = true;

    Vec3 moment = Vec3::Zero();

    explicit InertialTorque(const Vec3& m) : moment(m) { require(python_name, parameters[0], m); }
    static InertialTorque from(const Values& v) { return InertialTorque(v.vector("moment")); }
    Values values() const {
        Values v;
        v.set("moment", moment);
        return v;
    }

    /// M = R(q)ᵀ M_I.
    Vec3 operator()(double /*t*/, const Vec3& /*omega*/, const Vec3& /*moments*/, const Eigen::Vector4d& quaternion) const {
        return rotation_matrix(quaternion).transpose() * moment;
    }
    void add_jacobian(double, const Vec3&, const Vec3&, Mat3&) const {}
    bool axisymmetric() const { return false; }
};

}  // namespace gyrostat::torque
