// Stiffness measured along a run: when the explicit path (DOP853) is held by its stability limit,
// and when the stiff path (CVODE BDF) no longer needs to be. Method 'auto' (auto_switch.hpp)
// hands the run from one to the other on these verdicts.
#pragma once

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>

#include "gyrostat/integrate/diagnose.hpp"

namespace gyrostat::integrate {

/// The thresholds, and why (ρ: the spectral radius of ∂f/∂y where it matters, h: the step):
///
/// * kBoundary = 6.1: DOP853's stability region meets the negative real axis near hλ = −6.1
///   (the value Hairer's dop853.f tests against). An explicit step with h·ρ above it is unstable,
///   so a controller that keeps h·ρ near it is held by stability, not accuracy.
/// * Explicit side, Hairer's test (HNW I §IV.2, dop853.f `nstiff`), free: after each accepted
///   step, ρ ≈ ‖f(t+h, y_new) − f(t+h, g₁₂)‖ / ‖y_new − g₁₂‖ with g₁₂ the argument of the 12th
///   stage (both at c = 1: a secant of f along the error direction, which the dominant mode
///   dominates). h·ρ > 6.1 is a positive test; 15 positives (reset by 6 negatives in a row,
///   as in dop853.f) make the step suspect. It is then confirmed with the Jacobian's dominant
///   eigenvalue λ (diagnose.hpp) before the run switches to BDF: λ decaying (an oscillatory
///   mode would limit BDF too), h·|λ| ≥ kBoundary/2 (the secant was not a nonlinear fluke:
///   the step really sits at the boundary; the secant is ≤ ρ up to nonlinear terms, hence the
///   slack of 2), and at least kMinRemainingSteps explicit steps of this size left before t1
///   (fewer cost less than BDF's restart at order 1, which takes tens of small steps).
/// * Stiff side: every kImplicitPeriod BDF steps (the first check after as many, when BDF's
///   step reflects accuracy and no longer its start-up), h_BDF·|λ| ≤ kBackFraction·kBoundary
///   = 1.5 switches back to DOP853. DOP853's own step at the same tolerance is at least BDF's
///   (order 8 against ≤ 5), so this leaves the explicit method a factor 4 of room below its
///   boundary before it is stability-limited again: that factor between 6.1 (to go stiff)
///   and 1.5 (to come back) is the hysteresis. Each return to DOP853 halves the fraction for
///   the next BDF segment (1.5, 0.76, 0.38, …), so a problem that sits at the boundary settles
///   on BDF instead of flapping. A check costs one Jacobian and a dim×dim eigenproblem
///   (≈ 10 µs for 9 states, against ≈ 5 µs per BDF step: ≈ 4% at 50 steps).
/// * BDF must pay: a BDF step costs kPays DOP853 steps or more (measured on paper 001's moving
///   mass, 9 states: 3.2 µs against 0.67 µs per step, bench/auto_method.py's "mild" case), so at
///   each check from the second on (the first period holds BDF's start-up at order 1) BDF's mean
///   step over the period must be at least kPays times the step DOP853 would be held at there,
///   h_BDF·|λ| ≥ kPays·kBoundary = 18.3 (the mean: a single step may be one cut by an error test). Where the tolerance, not stability, keeps BDF's step
///   small (a mildly stiff problem at a loose rtol: BDF's steps 2× DOP853's there, the run 2.6×
///   slower than DOP853 alone and 100× less accurate), the run goes back to DOP853, and switches
///   to BDF again only once DOP853's held step has fallen below 1/kPays of the BDF step seen (the
///   stiffness grew): no flapping.
template <class System>
class StiffnessMonitor {
public:
    using State = typename System::State;
    static constexpr double kBoundary = 6.1;
    static constexpr int kStiffTests = 15;
    static constexpr int kNonStiffTests = 6;
    static constexpr double kMinRemainingSteps = 100.0;
    static constexpr long kImplicitPeriod = 50;
    static constexpr double kBackFraction = 0.25;
    static constexpr double kPays = 3.0;

    StiffnessMonitor(const System& system, double t1) : system_(system), t1_(t1) {}

    /// Called by DOP853 after each accepted step from t to t + h (y_new, f_new = f(t + h, y_new);
    /// stage, f_stage: the 12th stage's argument and derivative). True: hand over to BDF.
    bool explicit_step(double t, double h, const State& y_new, const State& f_new, const State& stage,
                       const State& f_stage) {
        const double den = (y_new - stage).squaredNorm();
        if (den <= 0.0) return false;
        const double h_rho = std::abs(h) * std::sqrt((f_new - f_stage).squaredNorm() / den);
        if (!(h_rho > kBoundary)) {
            if (++non_stiff_ >= kNonStiffTests) stiff_ = 0;
            return false;
        }
        non_stiff_ = 0;
        if (++stiff_ < kStiffTests) return false;
        stiff_ = 0;
        const double t_new = t + h;
        const std::complex<double> lambda = eigenvalue(t_new, y_new);
        const double h_lambda = std::abs(h) * std::abs(lambda);
        if (!decaying(lambda) || !(h_lambda >= 0.5 * kBoundary) ||
            std::abs(t1_ - t_new) < kMinRemainingSteps * std::abs(h) ||
            (bdf_step_seen_ > 0.0 && !(kPays * std::abs(h) < bdf_step_seen_)))  // BDF did not pay at this step yet
            return false;
        reason_ = "stiff: DOP853's step h = " + format_number(std::abs(h)) + " is held at its stability boundary (h·ρ > " +
                  format_number(kBoundary) + " in Hairer's test on " + std::to_string(kStiffTests) +
                  " steps); dominant eigenvalue λ = " + format_eigenvalue(lambda) + ", h·|λ| = " + format_number(h_lambda, 3);
        implicit_steps_ = 0;
        t_handed_ = t_new;
        return true;
    }

    /// Called by BDF after each step (t, y; h its last step). True: hand over to DOP853.
    bool implicit_step(double t, const State& y, double h) {
        if (implicit_steps_ == 0) last_check_ = t_handed_;
        if (++implicit_steps_ % kImplicitPeriod != 0 || t == t1_) return false;
        const double mean_step = std::abs(t - last_check_) / static_cast<double>(kImplicitPeriod);
        last_check_ = t;
        const std::complex<double> lambda = eigenvalue(t, y);
        const double h_lambda = std::abs(h) * std::abs(lambda);
        const double threshold = kBackFraction * kBoundary / static_cast<double>(1L << std::min(returns_, 20));
        if (h_lambda <= threshold) {
            reason_ = "not stiff: BDF's step h = " + format_number(std::abs(h)) + " with dominant eigenvalue λ = " +
                      format_eigenvalue(lambda) + " gives h·|λ| = " + format_number(h_lambda, 3) + " ≤ " +
                      format_number(threshold, 3) + ", well inside DOP853's stability boundary " + format_number(kBoundary);
            ++returns_;
            bdf_step_seen_ = 0.0;
        } else if (implicit_steps_ >= 2 * kImplicitPeriod && mean_step * std::abs(lambda) < kPays * kBoundary) {
            reason_ = "BDF does not pay: its mean step over the last " + std::to_string(kImplicitPeriod) + " steps, " +
                      format_number(mean_step) + ", with dominant eigenvalue λ = " + format_eigenvalue(lambda) +
                      " gives h·|λ| = " + format_number(mean_step * std::abs(lambda), 3) + " < " +
                      format_number(kPays * kBoundary, 3) + ": less than " + format_number(kPays) +
                      " times the step DOP853 is held at (h·|λ| = " + format_number(kBoundary) +
                      "), and a BDF step costs at least that many DOP853 steps";
            bdf_step_seen_ = mean_step;
        } else {
            return false;
        }
        stiff_ = non_stiff_ = 0;
        return true;
    }

    /// Why the last hand-over was asked for.
    const std::string& reason() const { return reason_; }
    /// Jacobians evaluated for the checks (for Stats::jacobian_evals).
    long evaluations() const { return evaluations_; }

private:
    std::complex<double> eigenvalue(double t, const State& y) {
        ++evaluations_;
        return dominant_eigenvalue(system_, t, y);
    }

    const System& system_;
    double t1_;
    int stiff_ = 0, non_stiff_ = 0, returns_ = 0;
    long implicit_steps_ = 0, evaluations_ = 0;
    double bdf_step_seen_ = 0.0;  ///< BDF's mean step when it last did not pay (0: never)
    double t_handed_ = 0.0;       ///< where the run was last handed to BDF
    double last_check_ = 0.0;     ///< where BDF's last check was (its mean step is measured since)
    std::string reason_;
};

/// BDF stepping over oscillations it damps away. BDF is stable for every decaying mode whatever
/// h, and it also damps an oscillatory mode with h·|Im λ| ≫ 1 that the true solution keeps (its
/// amplification at hλ = ±i·y, y ≫ 1, is O(1/y^k)): the answer is then smooth, converged in
/// BDF's own error estimate, and wrong (ω0 = (1e100, 0.5, −0.3) about a stable axis: q, r damped
/// to 1e-102 instead of oscillating at ~0.5). Watched every kPeriod steps and at the end of a
/// run: the Jacobian's dominant eigenvalue λ (diagnose.hpp) with h·|Im λ| > kStepsOver (more than
/// 1.6 periods of the mode per step) while the mode itself decays little within a step,
/// h·(−Re λ) < kOwnDecay (a mode that decays by e^-3 per step anyway may be damped: that is
/// what BDF is for). One warning per run, naming λ, h and t. Cost: one Jacobian and a dim×dim
/// eigenproblem per kPeriod steps (≈ 10 µs for 9 states, against ≈ 5 µs per BDF step).
template <class System>
class OscillationWatch {
public:
    using State = typename System::State;
    static constexpr long kPeriod = 50;
    static constexpr double kStepsOver = 10.0;
    static constexpr double kOwnDecay = 3.0;

    explicit OscillationWatch(const System& system) : system_(system) {}

    /// After each step (t, y, h its size; `last`: the run's final step): checks every kPeriod
    /// steps and at the last one; adds the warning to `result` once.
    void after_step(double t, const State& y, double h, bool last, Result& result) {
        if (warned_ || !(++steps_ % kPeriod == 0 || last) || !(h > 0.0)) return;
        const std::complex<double> lambda = dominant_eigenvalue(system_, t, y);
        const double over = h * std::abs(lambda.imag()), decay = -h * lambda.real();
        if (!(over > kStepsOver && decay < kOwnDecay)) return;
        warned_ = true;
        result.warnings.push_back(
            "cvode_bdf steps over oscillations it damps away: at t = " + format_number(t) + " the Jacobian's dominant "
            "eigenvalue λ = " + format_eigenvalue(lambda, 3) + " is oscillatory with step h = " + format_number(h, 3) +
            " (h·|Im λ| = " + format_number(over, 3) + " > " + format_number(kStepsOver, 2) +
            ", h·|Re λ| = " + format_number(std::abs(decay), 3) +
            "): the oscillation of that mode is lost; use method 'auto' or 'dop853'");
    }

private:
    const System& system_;
    long steps_ = 0;
    bool warned_ = false;
};

}  // namespace gyrostat::integrate
