// The averaged (slow-variable) system over the symmetric Euler–Poinsot motion.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "gyrostat/body.hpp"
#include "gyrostat/model/system.hpp"
#include "gyrostat/numeric/lanes.hpp"
#include "gyrostat/torque/set.hpp"

namespace gyrostat::model {

struct AveragedLanes;

/// Slow variables (a, r) of a nearly symmetric body (A1 ≈ A2 = A, A3 = C) under small torques.
/// The generating motion is p = a cos φ, q = a sin φ, r = const, φ̇ = (C − A) r / A; averaging
/// the perturbed Euler equations over φ gives
///
///   ȧ = Σ_i ⟨M_i · e_a⟩ contributions,   ṙ = Σ_i ⟨M_i,3⟩ / C,
///
/// one (ȧ, ṙ) pair per torque (TorqueSet::averaged; each torque's header gives its formula).
/// r is signed and may pass through zero; the averaging then stops being valid (the fast
/// frequency |(C − A) r / A| must stay large against the slow rates: fast_frequency(),
/// slow_rate()). A near-symmetric body B = A(1 + χε) contributes nothing to (ȧ, ṙ) at first
/// order: the asymmetry only shifts the phase.
///
/// Outputs recorded: |G| = √(A²a² + C²r²) (kept by internal torques: cavity, damper),
/// T = ½(A a² + C r²), the papers' x = a² and y = r², the fast frequency |(C − A) r / A| and
/// the ratio slow rate / fast frequency that must stay ≪ 1 for the averaging to hold.
class AveragedSymmetric {
public:
    static constexpr int dim = 2;
    using State = Eigen::Vector2d;
    static constexpr const char* family = "averaged_symmetric";
    static constexpr std::array<Quantity, dim> states{{{"a", "rad/s", "a = sqrt(p^2 + q^2), the transverse amplitude"}, {"r", "rad/s", "angular velocity about body z"}}};

    /// (a, r) do not depend on the body frame (model/frame.hpp); the ω they are lifted from and to
    /// does.
    static constexpr std::array<int, 0> body_vectors{};

    AveragedSymmetric(Body body, TorqueSet torques) : body_(std::move(body)), torques_(torques.in_principal_axes(body)) {
        if (body_.rotor().squaredNorm() != 0.0)
            throw std::invalid_argument("AveragedSymmetric: averaging over the Euler–Poinsot motion is for a rigid body "
                                        "(rotor k = 0); this body has |k| = " + format_value(body_.rotor().norm()));
        A_ = body_.moments()[0];
        C_ = body_.moments()[2];
        if (A_ == C_)
            throw std::invalid_argument("AveragedSymmetric: A = C = " + format_value(A_) +
                                        ": a spherical body has no fast rotation of (p, q) to average over");
        if (const char* name = torques_.without_averaged())
            throw std::invalid_argument(std::string("AveragedSymmetric: ") + name +
                                        " has no contribution to the (a, r) system (a torque that depends on the "
                                        "attitude, which the averaged model does not carry, or a user's torque): use "
                                        "the full model");
    }

    const Body& body() const { return body_; }
    const TorqueSet& torques() const { return torques_; }
    double A() const { return A_; }
    double C() const { return C_; }
    /// Whether the (a, r) system is exact rather than averaged: a symmetric body (A = B) without
    /// rotor under torques that commute with rotations about z; then r = 0 is no limit.
    bool exact_reduction() const {
        return body_.moments()[0] == body_.moments()[1] && body_.rotor().squaredNorm() == 0.0 && torques_.axisymmetric();
    }
    /// |φ̇| = |(C − A) r / A|.
    double fast_frequency(double r) const { return std::abs((C_ - A_) * r / A_); }
    /// max(|ȧ/a|, |ṙ/r|): the rate at which the slow variables change.
    double slow_rate(double t, const State& y) const {
        State dy;
        rhs(t, y, dy);
        const double a_rate = y[0] != 0.0 ? std::abs(dy[0] / y[0]) : std::abs(dy[0]);
        const double r_rate = y[1] != 0.0 ? std::abs(dy[1] / y[1]) : std::abs(dy[1]);
        return std::max(a_rate, r_rate);
    }

    /// (ȧ, ṙ) = Σ_i averaged contribution of torque i at (a, r), moments (A, A, C).
    void rhs(double t, const State& y, State& dy) const { dy = torques_.averaged(t, y[0], y[1], A_, C_); }
    /// W members in SIMD lanes (below), for the ensembles' DOP853 batches (integrate/batch.hpp).
    using LaneModel = AveragedLanes;

    /// (a, r) of a full state: a = √(p² + q²), r = ω3 (ω alone, or followed by the quaternion or the moving mass's u, v).
    State initial_state(const Eigen::VectorXd& given) const {
        if (given.size() != 3 && given.size() != 7 && given.size() != 9)
            throw std::invalid_argument("initial state has " + std::to_string(given.size()) +
                                        " components; AveragedSymmetric needs (a, r), or ω = (p, q, r) of the full model "
                                        "(optionally followed by the attitude quaternion, or by the moving mass's u and v)");
        return {std::hypot(given[0], given[1]), given[2]};
    }

    /// The generating motion at phase φ: ω = (a cos φ, a sin φ, r) (the full model's state when
    /// the averaging stops holding; a near-symmetric body's (p, q) is a circle to first order).
    Eigen::VectorXd full_state(const State& y, double phase) const {
        check_state(y);
        return Eigen::Vector3d(y[0] * std::cos(phase), y[0] * std::sin(phase), y[1]);
    }

    /// a = √(p² + q²) is an amplitude: a < 0 is not a state of the generating motion.
    void check_state(const State& y) const {
        if (!(y[0] >= 0.0))
            throw std::invalid_argument("AveragedSymmetric: the amplitude a = sqrt(p^2 + q^2) must be >= 0; got a = " +
                                        format_value(y[0]));
    }

    static constexpr std::array<OutputInfo, 7> outputs_info{{{"angular_momentum_norm", "kg m^2/s", "|G| = |J omega + k|, the norm of the angular momentum", true, true},
                                                             {"kinetic_energy", "J", "T = omega . J omega / 2, the kinetic energy of the rotation", true, true},
                                                             {"x", "rad^2/s^2", "x = a^2 (papers 000/001; paper 002 calls it y)", false},
                                                             {"y", "rad^2/s^2", "y = r^2 (papers 000/001; paper 002 calls it x)", false},
                                                             {"fast_frequency", "rad/s", "|(C - A) r / A|, the frequency of the averaged-out motion", false},
                                                             {"slow_to_fast", "1", "the slow variables' relative rate over the fast frequency (averaging needs it << 1)", false},
                                                             nutation_angle_info}};
    /// |G| and T alone (the outputs a run's error is measured on), the others NaN: a window
    /// estimate's companion does not pay for slow_to_fast's right-hand side and ϑ's atan2.
    void measured_outputs(double /*t*/, const State& y, double* out) const {
        out[0] = std::sqrt(A_ * A_ * y[0] * y[0] + C_ * C_ * y[1] * y[1]);
        out[1] = 0.5 * (A_ * y[0] * y[0] + C_ * y[1] * y[1]);
        std::fill(out + 2, out + outputs_info.size(), std::numeric_limits<double>::quiet_NaN());
    }
    void outputs(double t, const State& y, double* out) const {
        measured_outputs(t, y, out);
        out[2] = y[0] * y[0];
        out[3] = y[1] * y[1];
        out[4] = fast_frequency(y[1]);
        out[5] = out[4] > 0.0 ? slow_rate(t, y) / out[4] : std::numeric_limits<double>::infinity();
        // The nutation angle from the slow variables: on the generating motion
        // ω = (a cos φ, a sin φ, r) of a symmetric body (A = B, no rotor), G = (A a cos φ, A a sin φ, C r)
        // in body axes, so √(G_x² + G_y²) = A a and G_z = C r for every phase φ: ϑ does not depend on
        // the averaged-out phase, and tan ϑ = A a / (C r), ϑ = atan2(A a, C r) (model/system.hpp).
        out[6] = nutation_angle(Vec3(A_ * y[0], 0.0, C_ * y[1]));
    }
    bool keeps(std::size_t /*output*/) const { return torques_.empty(); }

private:
    Body body_;
    TorqueSet torques_;
    double A_ = 0.0, C_ = 0.0;
};

/// W averaged systems side by side in SIMD lanes: the right-hand side lane by lane (each
/// member's torques are a list of formulas), the rest of DOP853 vectorised; no Taylor method.
struct AveragedLanes {
    using System = AveragedSymmetric;
    using Lanes = lanes::Lanes;
    static constexpr int W = lanes::width;
    static constexpr int dim = System::dim;
    const System* members[W];

    static bool accepts(const System& /*system*/, bool /*taylor*/) { return true; }
    explicit AveragedLanes(const System* const* given) { std::copy(given, given + W, members); }
    void rhs(const Lanes& t, const Lanes* y, Lanes* dy) const {
        for (int l = 0; l < W; ++l) {
            System::State rate;
            members[l]->rhs(t[l], System::State(y[0][l], y[1][l]), rate);
            dy[0][l] = rate[0];
            dy[1][l] = rate[1];
        }
    }
    void project(Lanes* /*y*/) const {}
};

}  // namespace gyrostat::model
