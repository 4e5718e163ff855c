// The gravity-gradient torque on a body in a circular orbit.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>

#include "gyrostat/attitude.hpp"
#include "gyrostat/body.hpp"
#include "gyrostat/numeric/unit_vector.hpp"
#include "gyrostat/torque/orbit.hpp"
#include "gyrostat/torque/parameter.hpp"

namespace gyrostat::torque {

/// The gravity-gradient torque of a point-mass planet on a body in a circular orbit of rate
/// n = √(μ / r³), to first order in (body size / r):
///
///   M = 3 n² ĉ × (J ĉ),    ĉ = R(q)ᵀ ĉ_I(t)  the unit vector planet → body in body axes,
///
/// J = diag(A1, A2, A3), R(q) body → inertial, ĉ_I(t) on the orbit (torque/orbit.hpp). It needs
/// the attitude (models with the quaternion), and does not depend on ω (∂M/∂ω = 0).
///
/// Averaged over the orbit (⟨ĉ ĉᵀ⟩ = (I − N Nᵀ)/2) and over the free motion of a symmetric body
/// (A, A, C) (the symmetry axis e3 cones about g = G/|G| at the nutation angle ϑ:
/// ⟨e3 e3ᵀ⟩ = cos²ϑ g gᵀ + ½ sin²ϑ (I − g gᵀ)):
///   ⟨M⟩ = −¾ n² (C − A)(3 cos²ϑ − 1)(N·g) N × g,
/// perpendicular to G: |G| and T keep their values at first order (the averaged (a, r) system
/// gets no contribution), and G precesses about the orbit normal N at the rate
///   Ω = −3 n² (C − A)(3 cos²ϑ − 1) cos i / (4 |G|),   cos i = N·g
/// (for a body spinning about its axis, ϑ = 0, |G| = C ω3: Ω = −(3/2)(n²/ω3)((C − A)/C) cos i,
/// the classical result). The averaged model carries no attitude and refuses this torque
/// (AveragedSymmetric); `precession_rate` gives Ω.
struct GravityGradient {
    static constexpr const char* name = "gravity_gradient";
    static constexpr const char* python_name = "GravityGradient";
    static constexpr const char* description = "the gravity-gradient torque on a circular orbit (needs the attitude)";
    static constexpr std::array<Parameter, 3> parameters{{
        {"orbit_rate", "orbit rate n", Shape::Scalar, "rad/s", "the orbit's mean motion n = sqrt(mu / r^3)",
         Constraint::Positive},
        {"orbit_normal", "orbit normal N", Shape::Vector3, "1", "the orbit plane's normal in inertial axes",
         Constraint::Finite, 0, true, "[0, 0, 1]", Axes::Inertial},
        {"phase", "orbit phase", Shape::Scalar, "rad", "the body's angle on the orbit from the ascending node at t = 0",
         Constraint::Finite, 0, true, "0"},
    }};
    static constexpr bool needs_attitude = true;

    CircularOrbit orbit;

    GravityGradient(double n, const Vec3& normal, double phase) : orbit(n, normal, phase, python_name) {
        require(python_name, parameters[0], n);
        require(python_name, parameters[1], normal);
        require(python_name, parameters[2], phase);
    }
    static GravityGradient from(const Values& v) {
        return GravityGradient(v.scalar("orbit_rate"), v.vector_or("orbit_normal", Vec3::UnitZ()), v.scalar_or("phase", 0.0));
    }
    Values values() const {
        Values v;
        v.set("orbit_rate", orbit.rate);
        v.set("orbit_normal", orbit.normal);
        v.set("phase", orbit.phase);
        return v;
    }

    /// M = 3 n² ĉ × (J ĉ).
    Vec3 operator()(double t, const Vec3& /*omega*/, const Vec3& moments, const Eigen::Vector4d& quaternion) const {
        const Vec3 c = rotation_matrix(quaternion).transpose() * orbit.position(t);
        return 3.0 * orbit.rate * orbit.rate * c.cross(moments.cwiseProduct(c));
    }
    /// ∂M/∂ω = 0.
    void add_jacobian(double, const Vec3&, const Vec3&, Mat3&) const {}
    bool axisymmetric() const { return false; }

    /// Ω (rad/s, about the orbit normal) of the averaged precession of G, above, for a symmetric
    /// body (A, A, C) with angular velocity ω (body axes) and attitude q.
    double precession_rate(const Vec3& moments, const Vec3& omega, const Eigen::Vector4d& quaternion) const {
        const Vec3 G = moments.cwiseProduct(omega);
        const Vec3 g = scaled_unit(G);  // G/|G| and |G| without overflow or underflow (numeric/unit_vector.hpp)
        const double cos_nutation = g.z();
        const double cos_inclination = orbit.normal.dot(rotation_matrix(quaternion) * g);
        const double A = 0.5 * (moments.x() + moments.y()), C = moments.z();
        return -3.0 * orbit.rate * orbit.rate * (C - A) * (3.0 * cos_nutation * cos_nutation - 1.0) * cos_inclination /
               (4.0 * G.stableNorm());
    }
};

}  // namespace gyrostat::torque
