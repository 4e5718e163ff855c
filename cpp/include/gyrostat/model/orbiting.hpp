// A gyrostat on a circular orbit: the full model with the attitude, its torques on the model's
// one orbit, and its attitude reported relative to the orbit frame (LVLH).
#pragma once

#include <array>
#include <cmath>
#include <optional>
#include <utility>

#include "gyrostat/attitude.hpp"
#include "gyrostat/model/gyrostat.hpp"
#include "gyrostat/model/system.hpp"
#include "gyrostat/torque/orbit.hpp"

namespace gyrostat::model {

/// The gyrostat with the attitude (model/gyrostat.hpp: the same state (ω, q) and right-hand side)
/// on one circular orbit (torque/orbit.hpp), which every orbit torque of the model reads
/// (TorqueSet::on_orbit; a torque's own orbit must be the same: TorqueSet::common_orbit).
///
/// Besides the gyrostat's outputs it records the attitude relative to the orbit frame
/// O = (x_o, y_o, z_o) = (N × ĉ, −N, −ĉ) (along track, minus the orbit normal, nadir), whose axes
/// in inertial axes are the columns of R_IO(t) (CircularOrbit::frame) and which turns at
/// ω_O = n N (inertial axes):
///   R_OB = R_IO(t)ᵀ R(q),   q_OB its unit quaternion (w ≥ 0)      body → orbit frame,
///   R_OB = R_z(yaw) R_y(pitch) R_x(roll)                          the 3-2-1 sequence (roll about
///                                                                  x_o along track, pitch about
///                                                                  y_o, yaw about z_o nadir),
///                                                                  singular at pitch = ±π/2,
///   ω_rel = ω − n R(q)ᵀ N                                        ω relative to O, body axes,
///   G_I = R(q) (J ω + k):   azimuth λ = atan2(G_I·e2, G_I·e1),   inclination i = ∠(G_I, N)
///                                                                  (the precession of G about N).
/// A body at rest in O (roll = pitch = yaw = 0, ω_rel = 0) has ω = n R(q)ᵀ N = (0, −n, 0).
class OrbitingGyrostat : public RateAttitude<OrbitingGyrostat, 7, true> {
public:
    using Inner = Gyrostat<true>;
    static constexpr int dim = 7;
    static constexpr const char* model_name = "Gyrostat";
    using State = Inner::State;
    using Jacobian = Inner::Jacobian;
    static constexpr const char* family = "gyrostat";
    static constexpr auto states = rate_states<true>();

    /// The torques' orbit torques are put on `orbit` (each one's own orbit, if given, must be it).
    OrbitingGyrostat(const Body& body, const TorqueSet& torques, const torque::CircularOrbit& orbit)
        : orbit_(*torques.common_orbit(orbit)), inner_(body, torques.on_orbit(orbit_)) {}

    const torque::CircularOrbit& orbit() const { return orbit_; }
    const Body& body() const { return inner_.body(); }
    const TorqueSet& torques() const { return inner_.torques(); }
    bool supports_taylor() const { return inner_.supports_taylor(); }

    /// The gyrostat's: ω̇ = J⁻¹ (ΣM − ω × (Jω + k)),  q̇ = ½ q ⊗ (0, ω).
    void rhs(double t, const State& y, State& dy) const { inner_.rhs(t, y, dy); }
    /// The gyrostat's Jacobian.
    void jacobian(double t, const State& y, Jacobian& jac) const { inner_.jacobian(t, y, jac); }
    /// The gyrostat's f and products with the variational equations' columns (system::has_rate_with_products).
    bool rate_with_products(double t, const State& y, const double* columns, std::size_t count, State& f,
                            double* products) const {
        return inner_.rate_with_products(t, y, columns, count, f, products);
    }
    static constexpr int max_taylor_order = Inner::max_taylor_order;
    template <int order>
    void taylor_coefficients(double t, const State& y, State* coefficients) const {
        inner_.template taylor_coefficients<order>(t, y, coefficients);
    }
    State taylor_rate_error(const State& y, const State& y_low, const State& c1) const {
        return inner_.taylor_rate_error(y, y_low, c1);
    }
    /// The gyrostat's affine Euler coefficients (the variational Taylor run's: integrate/variational_taylor.hpp).
    const AffineEuler<double>& affine_euler() const { return inner_.affine_euler(); }
    void require_splitting() const { inner_.require_splitting(); }
    void free_flow(double h, State& y) const { inner_.free_flow(h, y); }
    bool keeps_momentum_norm() const { return inner_.keeps_momentum_norm(); }
    double separatrix(const State& y) const { return inner_.separatrix(y); }

    static constexpr std::array<OutputInfo, 12> orbit_outputs{{
        {"q_orbit_w", "1", "attitude quaternion body to orbit frame (LVLH: x along track, y minus the orbit normal, z nadir), scalar part (>= 0)", false},
        {"q_orbit_x", "1", "attitude quaternion body to orbit frame, x", false},
        {"q_orbit_y", "1", "attitude quaternion body to orbit frame, y", false},
        {"q_orbit_z", "1", "attitude quaternion body to orbit frame, z", false},
        {"roll", "rad", "roll: the 3-2-1 (yaw, pitch, roll) angle about x (along track) of the body to the orbit frame; singular at pitch = +-pi/2", false},
        {"pitch", "rad", "pitch: the 3-2-1 angle about y (minus the orbit normal), in [-pi/2, pi/2]; roll and yaw are singular at +-pi/2", false},
        {"yaw", "rad", "yaw: the 3-2-1 angle about z (nadir) of the body to the orbit frame; singular at pitch = +-pi/2", false},
        {"omega_rel_x", "rad/s", "angular velocity relative to the orbit frame, omega - n R^T N, body x", false},
        {"omega_rel_y", "rad/s", "angular velocity relative to the orbit frame, body y", false},
        {"omega_rel_z", "rad/s", "angular velocity relative to the orbit frame, body z", false},
        {"momentum_azimuth", "rad", "the azimuth of the angular momentum G about the orbit normal N, from e1 (the precession of G)", false},
        {"momentum_inclination", "rad", "the angle between the angular momentum G and the orbit normal N", false},
    }};
    static constexpr auto outputs_info = concat(Inner::outputs_info, orbit_outputs);

    /// The gyrostat's outputs, then those relative to the orbit frame (above).
    void outputs(double t, const State& y, double* out) const {
        inner_.outputs(t, y, out);
        out += Inner::outputs_info.size();
        const Eigen::Vector4d q = y.template segment<4>(3);
        const Mat3 R = rotation_matrix(q);
        const Eigen::Vector4d q_ob = quaternion_from_matrix(orbit_.frame(t).transpose() * R);
        for (int i = 0; i < 4; ++i) out[i] = q_ob[i];
        const Vec3 yaw_pitch_roll = euler_angles(q_ob, EulerConvention::ZYX);
        out[4] = yaw_pitch_roll[2], out[5] = yaw_pitch_roll[1], out[6] = yaw_pitch_roll[0];
        const Vec3 omega = y.template head<3>();
        const Vec3 relative = omega - orbit_.rate * (R.transpose() * orbit_.normal);
        for (int i = 0; i < 3; ++i) out[7 + i] = relative[i];
        const Vec3 G = R * body().angular_momentum(omega);
        out[10] = std::atan2(G.dot(orbit_.quadrant), G.dot(orbit_.node));
        out[11] = std::atan2(G.cross(orbit_.normal).norm(), G.dot(orbit_.normal));
    }
    /// The gyrostat's conserved outputs; none relative to the orbit.
    bool keeps(std::size_t output) const { return output < Inner::outputs_info.size() && inner_.keeps(output); }

    /// The state (ω, q) at t of a body whose attitude relative to the orbit frame is q_OB (body →
    /// orbit frame, any scale) and whose angular velocity relative to it is ω_rel (body axes):
    ///   R(q) = R_IO(t) R(q_OB),   ω = ω_rel + n R(q)ᵀ N.
    /// At rest in the orbit frame: q_OB = (1, 0, 0, 0), ω_rel = 0.
    State from_orbit_frame(double t, const Eigen::Vector4d& q_ob, const Vec3& omega_rel) const {
        const Mat3 R = orbit_.frame(t) * rotation_matrix(unit_quaternion(q_ob));
        State y;
        y.template head<3>() = omega_rel + orbit_.rate * (R.transpose() * orbit_.normal);
        y.template segment<4>(3) = quaternion_from_matrix(R);
        return y;
    }

private:
    torque::CircularOrbit orbit_;
    Inner inner_;
};

}  // namespace gyrostat::model
