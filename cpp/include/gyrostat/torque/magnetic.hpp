// The torque on a magnetic dipole fixed in the body, in a field given in inertial axes.
#pragma once

#include <Eigen/Core>
#include <array>

#include "gyrostat/attitude.hpp"
#include "gyrostat/body.hpp"
#include "gyrostat/torque/parameter.hpp"

namespace gyrostat::torque {

/// A magnetic dipole m fixed in the body in a field B constant in inertial space:
///
///   M = m × R(q)ᵀ B        (m in body axes, A m²; B inertial, T; R(q) body → inertial).
///
/// Needs the attitude; ∂M/∂ω = 0. No averaged contribution (the averaged model carries no
/// attitude and refuses it).
struct MagneticTorque {
    static constexpr const char* name = "magnetic";
    static constexpr const char* python_name = "MagneticTorque";
    static constexpr const char* description =
        "a magnetic dipole fixed in the body in a field constant in inertial space (needs the attitude)";
    static constexpr std::array<Parameter, 2> parameters{{
        {"dipole", "dipole m", Shape::Vector3, "A m^2", "the body's magnetic dipole moment m in body axes"},
        {"field", "field B", Shape::Vector3, "T", "the magnetic field B in inertial axes", Constraint::Finite, 0, true, nullptr,
         Axes::Inertial},
    }};
    /// M is affine in these (a sensitivity's ∂f/∂p is then a one-sided difference, exact).
    static constexpr std::array<const char*, 2> affine_in{{"dipole", "field"}};
    static constexpr bool needs_attitude = true;

    Vec3 dipole = Vec3::Zero();
    Vec3 field = Vec3::Zero();

    MagneticTorque(const Vec3& m, const Vec3& b) : dipole(m), field(b) {
        require(python_name, parameters[0], m);
        require(python_name, parameters[1], b);
    }
    static MagneticTorque from(const Values& v) { return MagneticTorque(v.vector("dipole"), v.vector("field")); }
    Values values() const {
        Values v;
        v.set("dipole", dipole);
        v.set("field", field);
        return v;
    }

    /// M = m × R(q)ᵀ B.
    Vec3 operator()(double /*t*/, const Vec3& /*omega*/, const Vec3& /*moments*/, const Eigen::Vector4d& quaternion) const {
        return dipole.cross(rotation_matrix(quaternion).transpose() * field);
    }
    void add_jacobian(double, const Vec3&, const Vec3&, Mat3&) const {}
    bool axisymmetric() const { return false; }
};

}  // namespace gyrostat::torque
