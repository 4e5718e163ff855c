// A circular orbit and its orbit frame (LVLH): where the body is, in inertial axes, for the
// torques that depend on the orbit (gravity gradient, a planet's dipole field) and for the
// attitude relative to the orbit (model/orbiting.hpp). docs/orbit_frame.md draws the convention.
#pragma once

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include "gyrostat/body.hpp"
#include "gyrostat/numeric/unit_vector.hpp"
#include "gyrostat/torque/parameter.hpp"

namespace gyrostat::torque {

/// A circular orbit of rate n (rad/s) in the plane normal to the unit vector N (inertial axes):
///   ĉ(t) = cos u e1 + sin u e2,   u = n t + φ0 (the argument of latitude),
///   e1 = ẑ × N / |ẑ × N|  (the ascending node on the inertial x-y plane; x̂ when N is along ±ẑ),
///   e2 = N × e1,
/// ĉ the unit vector from the planet to the body. So the default N = ẑ, φ0 = 0 is the inertial
/// x-y plane with the body at ĉ(0) = x̂ moving towards ŷ: ĉ turns about N (prograde), its
/// velocity is n N × ĉ. N need not be given with unit length.
///
/// The orbit frame (LVLH, local vertical local horizontal; Hughes, Spacecraft Attitude Dynamics,
/// §8.3; Wertz §16.2):
///   x_o = N × ĉ   along track (the velocity's direction; roll axis),
///   y_o = −N      minus the orbit normal (pitch axis),
///   z_o = −ĉ      nadir, towards the planet (yaw axis),
/// right-handed (x_o × y_o = z_o). It turns at ω_o = n N = −n y_o. Hill's frame (radial ĉ,
/// along track N × ĉ, normal N; Basilisk's hillPoint) is (x_H, y_H, z_H) = (−z_o, x_o, −y_o).
struct CircularOrbit {
    static constexpr const char* python_name = "Orbit";
    static constexpr const char* description =
        "a circular orbit: its rate, its plane's normal and the body's angle on it at t = 0 (docs/orbit_frame.md)";
    static constexpr std::array<Parameter, 3> parameters{{
        {"rate", "orbit rate n", Shape::Scalar, "rad/s", "the orbit's mean motion n = sqrt(mu / r^3)", Constraint::Positive},
        {"normal", "orbit normal N", Shape::Vector3, "1", "the orbit plane's normal in inertial axes (the sense of motion)",
         Constraint::Finite, 0, true, "[0, 0, 1]", Axes::Inertial},
        {"phase", "orbit phase", Shape::Scalar, "rad",
         "the body's angle u(0) on the orbit at t = 0 from e1 = z x N / |z x N| (x when N is along z)",
         Constraint::Finite, 0, true, "0"},
    }};

    double rate = 0.0;
    Vec3 normal = Vec3::UnitZ();
    double phase = 0.0;
    Vec3 node = Vec3::UnitX();     ///< e1
    Vec3 quadrant = Vec3::UnitY(); ///< e2

    /// Throws std::invalid_argument "<owner>: orbit rate n = ... must be finite and positive", or
    /// "<owner>: orbit_normal = [...] must not be zero" (or "must be finite"); N of any length is
    /// normalised without overflow or underflow (numeric/unit_vector.hpp).
    CircularOrbit(double n, const Vec3& orbit_normal, double phi0, const char* owner, const char* normal_name = "orbit_normal")
        : rate(n),
          normal(unit_direction(orbit_normal, std::string(owner) + ": " + normal_name, "it is the orbit plane's normal")),
          phase(phi0) {
        require(owner, parameters[0], n);
        require(owner, parameters[2], phi0);
        const Vec3 ascending = Vec3::UnitZ().cross(normal);  // |ẑ × N| ≤ 1, and > 1e-12 when used: safe to normalise
        node = ascending.norm() > 1e-12 ? Vec3(ascending.normalized()) : Vec3::UnitX();
        quadrant = normal.cross(node);
    }
    static CircularOrbit from(const Values& v) {
        return CircularOrbit(v.scalar("rate"), v.vector_or("normal", Vec3::UnitZ()), v.scalar_or("phase", 0.0), python_name,
                             "normal");
    }
    Values values() const {
        Values v;
        v.set("rate", rate);
        v.set("normal", normal);
        v.set("phase", phase);
        return v;
    }

    /// u(t) = n t + φ0, the body's angle on the orbit from e1.
    double argument(double t) const { return rate * t + phase; }
    /// ĉ(t) in inertial axes.
    Vec3 position(double t) const {
        const double u = argument(t);
        return std::cos(u) * node + std::sin(u) * quadrant;
    }
    /// The orbit frame's axes in inertial axes, as columns (x_o, y_o, z_o) = (N × ĉ, −N, −ĉ): the
    /// rotation orbit frame → inertial.
    Mat3 frame(double t) const {
        const Vec3 c = position(t);
        Mat3 R;
        R.col(0) = normal.cross(c);
        R.col(1) = Vec3::Zero() - normal;  // 0 − x, not −x: no −0 in a printed frame
        R.col(2) = Vec3::Zero() - c;
        return R;
    }
    /// The orbit frame's angular velocity n N, in inertial axes.
    Vec3 angular_velocity() const { return rate * normal; }

    /// The same orbit to rounding (the normals compared after normalisation).
    bool same_as(const CircularOrbit& o) const {
        auto close = [](double a, double b) { return std::abs(a - b) <= 1e-12 * std::max({1.0, std::abs(a), std::abs(b)}); };
        return close(rate, o.rate) && close(phase, o.phase) && (normal - o.normal).cwiseAbs().maxCoeff() <= 1e-12;
    }
    /// "Orbit(rate=0.001, normal=[0, 0, 1], phase=0)".
    std::string text() const {
        return std::string(python_name) + "(rate=" + format_value(rate) + ", normal=" + format_vector(normal) +
               ", phase=" + format_value(phase) + ")";
    }
};

/// The part of an orbit torque that says where the body is (GravityGradient, DipoleFieldTorque):
/// its own orbit, given with its parameters orbit_rate, orbit_normal and phase, or none, when the
/// model's orbit is to be used (TorqueSet::on_orbit gives it). A torque declares
/// `static constexpr bool on_orbit = true` and holds one of these as `orbit`.
class OrbitOfTorque {
public:
    OrbitOfTorque() = default;
    explicit OrbitOfTorque(const CircularOrbit& o) : orbit_(o) {}
    /// From a torque's named values: its own orbit when orbit_rate is given; orbit_normal or phase
    /// without orbit_rate throws std::invalid_argument naming the torque.
    static OrbitOfTorque from(const Values& v, const char* torque) {
        if (!v.has("orbit_rate")) {
            if (v.has("orbit_normal") || v.has("phase"))
                throw std::invalid_argument(std::string(torque) + ": orbit_normal and phase need orbit_rate (or give no "
                                            "orbit at all and give the model its orbit: Model(..., orbit=gyrostat.Orbit(...)))");
            return {};
        }
        return OrbitOfTorque(CircularOrbit(v.scalar("orbit_rate"), v.vector_or("orbit_normal", Vec3::UnitZ()),
                                           v.scalar_or("phase", 0.0), torque));
    }
    /// orbit_rate, orbit_normal, phase into v (nothing without an orbit of its own).
    void add_to(Values& v) const {
        if (!orbit_) return;
        v.set("orbit_rate", orbit_->rate);
        v.set("orbit_normal", orbit_->normal);
        v.set("phase", orbit_->phase);
    }
    bool given() const { return orbit_.has_value(); }
    const std::optional<CircularOrbit>& get() const { return orbit_; }
    /// The orbit; throws std::logic_error naming the torque when it has none (a model gives it one
    /// before any evaluation: TorqueSet::in_principal_axes refuses an orbit torque without orbit).
    const CircularOrbit& operator*() const { return *orbit_; }
    const CircularOrbit* operator->() const { return &*orbit_; }
    const CircularOrbit& required(const char* torque) const {
        if (!orbit_)
            throw std::invalid_argument(std::string(torque) + " has no orbit: give it orbit_rate, or give the model "
                                        "its orbit (Model(..., orbit=gyrostat.Orbit(rate=...)), a scene's [orbit] table)");
        return *orbit_;
    }

private:
    std::optional<CircularOrbit> orbit_;
};

/// The three declared parameters every orbit torque shares (optional: without them the torque
/// takes the model's orbit).
inline constexpr Parameter orbit_rate_parameter{"orbit_rate", "orbit rate n", Shape::Scalar, "rad/s",
                                                "the orbit's mean motion n = sqrt(mu / r^3); leave out the three orbit "
                                                "parameters to use the model's orbit",
                                                Constraint::Positive, 0, true, "the model's orbit"};
inline constexpr Parameter orbit_normal_parameter{"orbit_normal", "orbit normal N", Shape::Vector3, "1",
                                                  "the orbit plane's normal in inertial axes (needs orbit_rate)",
                                                  Constraint::Finite, 0, true, "[0, 0, 1]", Axes::Inertial};
inline constexpr Parameter orbit_phase_parameter{"phase", "orbit phase", Shape::Scalar, "rad",
                                                 "the body's angle on the orbit at t = 0 from e1 = z x N / |z x N| "
                                                 "(needs orbit_rate; docs/orbit_frame.md)",
                                                 Constraint::Finite, 0, true, "0"};

}  // namespace gyrostat::torque
