// Where a body on a circular orbit is, in inertial axes: for the torques that depend on the orbit
// (gravity gradient, a planet's dipole field).
#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <string>

#include "gyrostat/body.hpp"
#include "gyrostat/numeric/unit_vector.hpp"

namespace gyrostat::torque {

/// A circular orbit of rate n (rad/s) in the plane normal to the unit vector N (inertial axes):
///   ĉ(t) = cos(n t + φ0) e1 + sin(n t + φ0) e2,     the unit vector from the planet to the body,
///   e1 = ẑ × N / |ẑ × N|  (the ascending node; x̂ when N ∥ ẑ),   e2 = N × e1,
/// so that the default N = ẑ, φ0 = 0 is the inertial x-y plane with ĉ(0) = x̂, and ĉ turns
/// about N (prograde). N need not be given with unit length.
struct CircularOrbit {
    double rate = 0.0;
    Vec3 normal = Vec3::UnitZ();
    double phase = 0.0;
    Vec3 node = Vec3::UnitX();     ///< e1
    Vec3 quadrant = Vec3::UnitY(); ///< e2

    /// Throws std::invalid_argument "<torque>: orbit_normal = [...] must not be zero" for N = 0
    /// (or "must be finite" for a NaN or infinite component); N of any length is normalised
    /// without overflow or underflow (numeric/unit_vector.hpp).
    CircularOrbit(double n, const Vec3& orbit_normal, double phi0, const char* torque)
        : rate(n),
          normal(unit_direction(orbit_normal, std::string(torque) + ": orbit_normal", "it is the orbit plane's normal")),
          phase(phi0) {
        const Vec3 ascending = Vec3::UnitZ().cross(normal);  // |ẑ × N| ≤ 1, and > 1e-12 when used: safe to normalise
        node = ascending.norm() > 1e-12 ? Vec3(ascending.normalized()) : Vec3::UnitX();
        quadrant = normal.cross(node);
    }

    /// ĉ(t) in inertial axes.
    Vec3 position(double t) const {
        const double u = rate * t + phase;
        return std::cos(u) * node + std::sin(u) * quadrant;
    }
};

}  // namespace gyrostat::torque
