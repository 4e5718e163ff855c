// The averaged (slow-variable) system over the triaxial Euler–Poinsot motion.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "gyrostat/body.hpp"
#include "gyrostat/euler_poinsot.hpp"
#include "gyrostat/model/system.hpp"
#include "gyrostat/torque/set.hpp"

namespace gyrostat::model {

/// A rigid body of any moments (no rotor) under small torques fixed in the body, averaged over
/// its torque-free motion (euler_poinsot.hpp; derivation docs/papers/triaxial_averaging.md). With
/// M small, d(G²)/dt = 2 Jω·M and dT/dt = ω·M exactly; first-order averaging over one period of
/// the free motion at fixed (|G|², p_b, s) gives, with the averaged power per axis
/// P_i = ⟨ω_i M_i⟩ (TorqueSet::averaged_power: closed forms in K and E for the constant and linear
/// torques, the resistive medium and the viscous cavity, the trapezoidal rule in the phase for any
/// other torque fixed in the body, a user's included),
///
///   d|G|²/dt = 2 Σ A_i P_i,   dp_b/dt = 2 Σ (A_i − A_b) P_i,   ds/dt = 0,   dφ/dt = πλ/(2K(k)),
///
/// p_b = G² − 2T A_b the distance to the separatrix carried as a state (T = (G² − p_b)/(2A_b)), so
/// that k'² ∝ p_b keeps its digits next to the separatrix; s = ±1 the branch (the sign of ω about
/// the axis circulated about: odd torques such as a constant one need it); φ the fast phase,
/// unwrapped, whose rate is a function of the slow variables: ω(t) along a run is the free motion
/// at (|G|², p_b, s, φ), to O(ε) in the slow variables and to O(1) in φ by t ~ 1/ε (the phase's
/// own first-order correction is not averaged).
///
/// The averaged rates stay finite at the separatrix p_b = 0, but the period P = 4K/λ diverges like
/// ln(1/k') there and the averaging stops holding where the slow drift over one period is no
/// longer small against p_b: `slow_to_fast` = max(|d ln G²/dt|, |d ln |p_b|/dt|)/φ̇ must stay ≪ 1
/// (the model ladder switches up to the full model before it and back down after the crossing).
/// A symmetric body is the limit k² = 0, where the rates equal those of AveragedSymmetric's (a, r).
class AveragedTriaxial {
public:
    static constexpr int dim = 4;
    using State = Eigen::Vector4d;
    static constexpr const char* family = "averaged_triaxial";
    static constexpr std::array<Quantity, dim> states{
        {{"G2", "kg^2 m^4/s^2", "|G|^2, the squared norm of the angular momentum"},
         {"pb", "kg^2 m^4/s^2", "p_b = |G|^2 - 2 T A_mid, the distance to the separatrix (> 0: rotation about the axis of the largest moment, < 0: of the smallest)"},
         {"branch", "1", "s = +1 or -1, the sign of omega about the axis the body rotates about (constant between separatrix crossings)", nullptr, true},
         {"phase", "rad", "the fast phase phi of the free motion (u = 2 K phi / pi; 0 where omega_mid = 0), unwrapped"}}};

    /// (|G|², p_b, s, φ) do not depend on the body frame (model/frame.hpp); the ω they are lifted
    /// from and to does.
    static constexpr std::array<int, 0> body_vectors{};
    /// φ̇ is a function of the slow variables and feeds back into none of them (system.hpp).
    static constexpr std::array<int, 1> quadratures{{3}};
    /// The relative accuracy of the averages taken by quadrature (EulerPoinsot::nodes).
    static constexpr double quadrature_tolerance = 1e-13;

    AveragedTriaxial(Body body, TorqueSet torques) : body_(std::move(body)), torques_(torques.in_principal_axes(body)) {
        if (body_.rotor().squaredNorm() != 0.0)
            throw std::invalid_argument("AveragedTriaxial: averaging over the Euler–Poinsot motion is for a rigid body "
                                        "(rotor k = 0); this body has |k| = " + format_value(body_.rotor().norm()));
        const Vec3& J = body_.moments();
        if (J.maxCoeff() == J.minCoeff())
            throw std::invalid_argument("AveragedTriaxial: A1 = A2 = A3 = " + format_value(J[0]) +
                                        ": a spherical body has no fast motion to average over");
        torques_.require_no_attitude("AveragedTriaxial (the averaged model carries no attitude; use the full model)");
        middle_ = J[EulerPoinsot::sorted_axes(J)[1]];
    }

    const Body& body() const { return body_; }
    const TorqueSet& torques() const { return torques_; }
    /// A_b, the middle principal moment.
    double middle_moment() const { return middle_; }

    /// The free motion the state stands for (throws on the separatrix and off the body's level sets;
    /// `on_the_way`: a state of a run, a T rounded past the permanent rotation taken as it).
    EulerPoinsot motion(const State& y, bool on_the_way = true) const {
        return EulerPoinsot(body_.moments(), y[0], y[1], y[2], on_the_way);
    }

    /// At |G|² ≤ 0 (a damped body brought to rest, |G|² rounded or stepped past 0 by the
    /// integrator) every rate is 0: rest (the outputs' slow_to_fast = ∞ there, which the validity
    /// check reports: the averaging has no fast motion left).
    void rhs(double t, const State& y, State& dy) const {
        if (!(y[0] > 0.0)) {
            dy.setZero();
            return;
        }
        const EulerPoinsot free = motion(y);
        const Vec3& J = body_.moments();
        const Vec3 power = torques_.averaged_power(t, free, J, quadrature_tolerance);
        dy[0] = 2.0 * J.dot(power);
        dy[1] = 2.0 * (J.array() - middle_).matrix().dot(power);
        dy[2] = 0.0;
        dy[3] = free.phase_rate();
    }

    /// (|G|², p_b, s, φ) of a full state (ω alone, or followed by the quaternion or the moving mass's u, v):
    /// |G|² = Σ A_i² ω_i², p_b = Σ A_i (A_i − A_b) ω_i², s the sign of ω about the axis circulated
    /// about, φ where the free motion passes through ω.
    State initial_state(const Eigen::VectorXd& given) const {
        if (given.size() != 3 && given.size() != 7 && given.size() != 9)
            throw std::invalid_argument("initial state has " + std::to_string(given.size()) +
                                        " components; AveragedTriaxial needs (G2, pb, branch, phase), or omega = (p, q, r) "
                                        "of the full model (optionally followed by the attitude quaternion, or by the "
                                        "moving mass's u and v)");
        const Vec3 w = given.head<3>();
        const Vec3& J = body_.moments();
        const double G2 = (J.cwiseProduct(w)).squaredNorm();
        const double pb = EulerPoinsot::separatrix_distance(J, w);
        if (pb == 0.0 || !(G2 > 0.0))
            return {G2, pb, 1.0, 0.0};  // at rest or on the separatrix: check_state names it
        const std::array<int, 3> order = EulerPoinsot::sorted_axes(J);
        const double branch = w[pb > 0.0 ? order[2] : order[0]] < 0.0 ? -1.0 : 1.0;
        const EulerPoinsot free(J, G2, pb, branch, true);
        return {G2, pb, branch, free.phase_of(w)};
    }

    /// The free motion at its phase plus `phase`: ω (the full model's state where the averaging
    /// stops holding; the model ladder's switch up). `y` is a state of a run: at |G|² ≤ 0 the body
    /// is at rest (ω = 0, as the right-hand side takes it), and a T rounded past the permanent
    /// rotation is that rotation; the separatrix, a bad branch or phase are refused by name.
    Eigen::VectorXd full_state(const State& y, double phase) const {
        check_branch_and_phase(y);
        if (!(y[0] > 0.0) && std::isfinite(y[0]) && std::isfinite(y[1])) return Eigen::VectorXd::Zero(3);
        return motion(y).omega(y[3] + phase);
    }

    /// Refuses a state no motion of this body has, naming it: |G|² ≤ 0, p_b = 0 (the separatrix),
    /// a branch other than ±1, (|G|², p_b) outside the body's level sets, a non-finite phase.
    void check_state(const State& y) const {
        check_branch_and_phase(y);
        (void)motion(y, false);
    }

    static constexpr std::array<OutputInfo, 11> outputs_info{
        {{"angular_momentum_norm", "kg m^2/s", "|G| = |J omega|, the norm of the angular momentum", true, true},
         {"kinetic_energy", "J", "T = omega . J omega / 2 = (|G|^2 - p_b)/(2 A_mid), the kinetic energy of the rotation", true, true},
         {"modulus_squared", "1", "k^2 of the free motion (0: a permanent rotation or a symmetric body, 1: the separatrix)", false},
         {"complementary_modulus_squared", "1", "k'^2 = 1 - k^2, from p_b (every digit next to the separatrix)", false},
         {"period", "s", "P = 4 K(k) / lambda, the period of omega(t) of the free motion", false},
         {"fast_frequency", "rad/s", "dphi/dt = pi lambda / (2 K(k)), the frequency of the averaged-out motion", false},
         {"slow_to_fast", "1", "max(|d ln |G|^2/dt|, |d ln |p_b|/dt|) over the fast frequency (averaging needs it << 1; it grows without bound at the separatrix)", false},
         {"p", "rad/s", "omega_1 of the free motion at the carried phase", false},
         {"q", "rad/s", "omega_2 of the free motion at the carried phase", false},
         {"r", "rad/s", "omega_3 of the free motion at the carried phase", false},
         nutation_angle_info}};
    /// |G| and T alone (the outputs a run's error is measured on), the others NaN: a window
    /// estimate's companion does not pay for the free motion's K(k), phase and atan2.
    void measured_outputs(double /*t*/, const State& y, double* out) const {
        out[0] = std::sqrt(std::max(y[0], 0.0));
        out[1] = 0.5 * (y[0] - y[1]) / middle_;
        std::fill(out + 2, out + outputs_info.size(), std::numeric_limits<double>::quiet_NaN());
    }
    void outputs(double t, const State& y, double* out) const {
        measured_outputs(t, y, out);
        if (y[1] == 0.0 || !(y[0] > 0.0)) {  // on the separatrix (or at rest): no period, no phase
            constexpr double nan = std::numeric_limits<double>::quiet_NaN();
            out[2] = 1.0, out[3] = 0.0, out[4] = std::numeric_limits<double>::infinity(), out[5] = 0.0;
            out[6] = std::numeric_limits<double>::infinity();
            out[7] = out[8] = out[9] = out[10] = nan;
            return;
        }
        const EulerPoinsot free = motion(y);
        out[2] = free.m();
        out[3] = free.m1();
        out[4] = free.period();
        out[5] = free.phase_rate();
        State dy;
        rhs(t, y, dy);
        const double slow = std::max(std::abs(dy[0] / y[0]), std::abs(dy[1] / y[1]));
        out[6] = slow / out[5];
        const Vec3 w = free.omega(y[3]);
        out[7] = w[0], out[8] = w[1], out[9] = w[2];
        out[10] = nutation_angle(body_.moments().cwiseProduct(w));
    }
    bool keeps(std::size_t /*output*/) const { return torques_.empty(); }

private:
    static void check_branch_and_phase(const State& y) {
        if (y[2] != 1.0 && y[2] != -1.0)
            throw std::invalid_argument("AveragedTriaxial: the branch must be +1 or -1; got " + format_value(y[2]));
        if (!std::isfinite(y[3]))
            throw std::invalid_argument("AveragedTriaxial: the phase must be finite; got " + format_value(y[3]));
    }

    Body body_;
    TorqueSet torques_;
    double middle_ = 0.0;
};

}  // namespace gyrostat::model
