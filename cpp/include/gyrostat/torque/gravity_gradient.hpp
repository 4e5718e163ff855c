// The gravity-gradient torque on a body in a circular orbit.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <utility>

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
/// J = diag(A1, A2, A3), R(q) body → inertial, ĉ_I(t) on the orbit (torque/orbit.hpp): its own
/// (orbit_rate, orbit_normal, phase) or, given none, the model's (TorqueSet::on_orbit). It needs
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
    static constexpr std::array<Parameter, 3> parameters{{orbit_rate_parameter, orbit_normal_parameter, orbit_phase_parameter}};
    static constexpr bool needs_attitude = true;
    /// Reads the orbit: its own, or the model's (TorqueSet::on_orbit).
    static constexpr bool on_orbit = true;

    OrbitOfTorque orbit;

    explicit GravityGradient(OrbitOfTorque o) : orbit(std::move(o)) {}
    GravityGradient(double n, const Vec3& normal, double phase) : orbit(CircularOrbit(n, normal, phase, python_name)) {
        require(python_name, parameters[1], normal);
    }
    static GravityGradient from(const Values& v) { return GravityGradient(OrbitOfTorque::from(v, python_name)); }
    Values values() const {
        Values v;
        orbit.add_to(v);
        return v;
    }
    /// The same torque on the orbit o (the model's).
    GravityGradient with_orbit(const CircularOrbit& o) const { return GravityGradient(OrbitOfTorque(o)); }

    /// M = 3 n² ĉ × (J ĉ).
    Vec3 operator()(double t, const Vec3& /*omega*/, const Vec3& moments, const Eigen::Vector4d& quaternion) const {
        const Vec3 c = rotation_matrix(quaternion).transpose() * orbit->position(t);
        return 3.0 * orbit->rate * orbit->rate * c.cross(moments.cwiseProduct(c));
    }
    /// ∂M/∂ω = 0.
    void add_jacobian(double, const Vec3&, const Vec3&, Mat3&) const {}
    bool axisymmetric() const { return false; }

    /// Ω (rad/s, about the orbit normal) of the averaged precession of G, above, for a symmetric
    /// body (A, A, C) with angular velocity ω (body axes) and attitude q, on the torque's own orbit.
    double precession_rate(const Vec3& moments, const Vec3& omega, const Eigen::Vector4d& quaternion) const {
        return precession_rate(moments, omega, quaternion, orbit.required("GravityGradient.precession_rate: the torque"));
    }
    /// The same on the orbit o (the model's).
    static double precession_rate(const Vec3& moments, const Vec3& omega, const Eigen::Vector4d& quaternion,
                                  const CircularOrbit& orbit) {
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
