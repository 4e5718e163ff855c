// The averaged (slow-variable) system over the symmetric Euler–Poinsot motion.
#pragma once

#include <array>
#include <cmath>
#include <stdexcept>

#include "gyrostat/body.hpp"
#include "gyrostat/torque/set.hpp"

namespace gyrostat::model {

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
/// Invariants reported: |G| = √(A²a² + C²r²) (kept by internal torques: cavity, damper) and
/// T = ½(A a² + C r²).
class AveragedSymmetric {
public:
    static constexpr int dim = 2;
    static constexpr bool has_jacobian = false;
    static constexpr bool has_projection = false;
    static constexpr bool has_taylor = false;
    static constexpr int max_taylor_order = 0;
    static constexpr int n_invariants = 2;
    using State = Eigen::Vector2d;
    using Jacobian = Eigen::Matrix2d;

    AveragedSymmetric(Body body, TorqueSet torques) : body_(std::move(body)), torques_(std::move(torques)) {
        if (body_.rotor().squaredNorm() != 0.0)
            throw std::invalid_argument("AveragedSymmetric: averaging over the Euler–Poinsot motion is for a rigid body "
                                        "(rotor k = 0); this body has |k| = " + format_value(body_.rotor().norm()));
        A_ = body_.moments()[0];
        C_ = body_.moments()[2];
        if (A_ == C_)
            throw std::invalid_argument("AveragedSymmetric: A = C = " + format_value(A_) +
                                        ": a spherical body has no fast rotation of (p, q) to average over");
    }

    const Body& body() const { return body_; }
    const TorqueSet& torques() const { return torques_; }
    double A() const { return A_; }
    double C() const { return C_; }
    /// (B − A)/A: the near-symmetry parameter χε of paper 002.
    double asymmetry() const { return (body_.moments()[1] - A_) / A_; }
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
    void jacobian(double, const State&, Jacobian&) const {}
    void project(State&) const {}
    template <int Order>
    void taylor_coefficients(double, const State&, State*) const {}
    bool supports_taylor() const { return false; }

    static constexpr std::array<const char*, n_invariants> invariant_names{"angular_momentum_norm", "kinetic_energy"};
    void invariants(double, const State& y, double* out) const {
        out[0] = std::sqrt(A_ * A_ * y[0] * y[0] + C_ * C_ * y[1] * y[1]);
        out[1] = 0.5 * (A_ * y[0] * y[0] + C_ * y[1] * y[1]);
    }

private:
    Body body_;
    TorqueSet torques_;
    double A_ = 0.0, C_ = 0.0;
};

}  // namespace gyrostat::model
