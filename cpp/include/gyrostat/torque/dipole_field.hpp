// The torque on a magnetic dipole fixed in the body, on a circular orbit in a planet's tilted dipole field.
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>
#include <utility>

#include "gyrostat/attitude.hpp"
#include "gyrostat/body.hpp"
#include "gyrostat/numeric/unit_vector.hpp"
#include "gyrostat/torque/orbit.hpp"
#include "gyrostat/torque/parameter.hpp"

namespace gyrostat::torque {

/// A magnetic dipole m fixed in the body, on a circular orbit in a planet's tilted dipole field:
///
///   B_I(t) = B0 [3 (d·ĉ) ĉ − d],     M = m × R(q)ᵀ B_I(t),
///
/// d the unit direction of the planet's dipole moment (inertial axes, fixed: the planet's own
/// rotation is left out), ĉ(t) the unit vector planet → body on the orbit (torque/orbit.hpp: its
/// own, or the model's when it is given none),
/// B0 = μ0 |m_planet| / (4π r³) the field's magnitude at the magnetic equator at the orbit's
/// radius (about 2.4e-5 T in a low Earth orbit; the Earth's d is near −ẑ, tilted by about 10°).
/// Needs the attitude; ∂M/∂ω = 0; no averaged contribution.
struct DipoleFieldTorque {
    static constexpr const char* name = "dipole_field";
    static constexpr const char* python_name = "DipoleFieldTorque";
    static constexpr const char* description =
        "a magnetic dipole fixed in the body on a circular orbit in a planet's tilted dipole field (needs the attitude)";
    static constexpr std::array<Parameter, 6> parameters{{
        {"dipole", "dipole m", Shape::Vector3, "A m^2", "the body's magnetic dipole moment m in body axes"},
        {"field_strength", "field strength B0", Shape::Scalar, "T",
         "B0 = mu0 |m_planet| / (4 pi r^3), the field at the magnetic equator at the orbit's radius", Constraint::Positive},
        orbit_rate_parameter,
        {"dipole_axis", "dipole axis d", Shape::Vector3, "1",
         "the direction of the planet's dipole moment in inertial axes (tilted from -z for a tilted dipole)",
         Constraint::Finite, 0, true, "[0, 0, -1]", Axes::Inertial},
        orbit_normal_parameter,
        orbit_phase_parameter,
    }};
    /// M is affine in these (a sensitivity's ∂f/∂p is then a one-sided difference, exact).
    static constexpr std::array<const char*, 2> affine_in{{"dipole", "field_strength"}};
    static constexpr bool needs_attitude = true;
    /// Reads the orbit: its own, or the model's (TorqueSet::on_orbit).
    static constexpr bool on_orbit = true;

    Vec3 dipole = Vec3::Zero();
    double field_strength = 0.0;
    Vec3 axis = -Vec3::UnitZ();
    OrbitOfTorque orbit;

    DipoleFieldTorque(const Vec3& m, double b0, const Vec3& d, OrbitOfTorque o)
        : dipole(m), field_strength(b0), orbit(std::move(o)) {
        require(python_name, parameters[0], m);
        require(python_name, parameters[1], b0);
        require(python_name, parameters[3], d);
        axis = unit_direction(d, std::string(python_name) + ": dipole_axis", "the direction of the planet's dipole moment");
    }
    DipoleFieldTorque(const Vec3& m, double b0, double n, const Vec3& d, const Vec3& normal, double phase)
        : DipoleFieldTorque(m, b0, d, OrbitOfTorque(CircularOrbit(n, normal, phase, python_name))) {
        require(python_name, parameters[4], normal);
    }
    static DipoleFieldTorque from(const Values& v) {
        return DipoleFieldTorque(v.vector("dipole"), v.scalar("field_strength"), v.vector_or("dipole_axis", -Vec3::UnitZ()),
                                 OrbitOfTorque::from(v, python_name));
    }
    Values values() const {
        Values v;
        v.set("dipole", dipole);
        v.set("field_strength", field_strength);
        v.set("dipole_axis", axis);
        orbit.add_to(v);
        return v;
    }
    /// The same torque on the orbit o (the model's).
    DipoleFieldTorque with_orbit(const CircularOrbit& o) const { return DipoleFieldTorque(dipole, field_strength, axis, OrbitOfTorque(o)); }

    /// B_I(t) = B0 [3 (d·ĉ) ĉ − d] in inertial axes.
    Vec3 field(double t) const {
        const Vec3 c = orbit->position(t);
        return field_strength * (3.0 * axis.dot(c) * c - axis);
    }
    /// M = m × R(q)ᵀ B_I(t).
    Vec3 operator()(double t, const Vec3& /*omega*/, const Vec3& /*moments*/, const Eigen::Vector4d& quaternion) const {
        return dipole.cross(rotation_matrix(quaternion).transpose() * field(t));
    }
    void add_jacobian(double, const Vec3&, const Vec3&, Mat3&) const {}
    bool axisymmetric() const { return false; }
};

}  // namespace gyrostat::torque
