// Splitting integrators: the exact flow of the free body composed with the flow of the
// perturbation (Celledoni, Fassò, Säfström & Zanna, SIAM J. Sci. Comput. 30 (2008), §5;
// McLachlan & Quispel, Acta Numerica 11 (2002) 341 for the compositions).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <vector>

#include "gyrostat/body.hpp"
#include "gyrostat/integrate/control.hpp"
#include "gyrostat/integrate/events.hpp"
#include "gyrostat/integrate/options.hpp"
#include "gyrostat/integrate/recorder.hpp"
#include "gyrostat/integrate/substep.hpp"

namespace gyrostat::integrate {

/// A System splits when it gives its free flow and its perturbation (model/system.hpp); the
/// perturbation's sub-flow is built here (substep.hpp: PerturbationFlow). Optionally
///   bool keeps_momentum_norm() const;    |G| = |Jω| (ω = y[0..2], J = body().moments()) is a
///                                        first integral of both sub-flows: projected on (below)
template <class S, class = void>
struct has_splitting : std::false_type {};
template <class S>
struct has_splitting<S, std::void_t<decltype(std::declval<const S&>().free_flow(0.0, std::declval<typename S::State&>()))>>
    : std::true_type {};
template <class S, class = void>
struct has_momentum_norm : std::false_type {};
template <class S>
struct has_momentum_norm<S, std::void_t<decltype(std::declval<const S&>().keeps_momentum_norm())>> : std::true_type {};

namespace splitting_detail {

/// The Strang sub-steps of a composition of order 2, 4 or 6, as fractions of the step:
///   2: Strang  S(h) = P(h/2) F(h) P(h/2)  (P the perturbation's flow, F the free flow);
///   4: Yoshida's (Forest–Ruth) triple jump S(γ1 h) S(γ2 h) S(γ1 h), γ1 = 1/(2 − 2^{1/3}),
///      γ2 = 1 − 2γ1 (Yoshida, Phys. Lett. A 150 (1990) 262);
///   6: the triple jump of the order-4 method, δ1 = 1/(2 − 2^{1/5}), δ2 = 1 − 2δ1 (9 Strang steps).
inline std::vector<double> strang_fractions(int order) {
    if (order == 2) return {1.0};
    const double g1 = 1.0 / (2.0 - std::cbrt(2.0)), g2 = 1.0 - 2.0 * g1;
    const std::vector<double> four{g1, g2, g1};
    if (order == 4) return four;
    const double d1 = 1.0 / (2.0 - std::pow(2.0, 0.2)), d2 = 1.0 - 2.0 * d1;
    std::vector<double> six;
    for (double d : {d1, d2, d1})
        for (double g : four) six.push_back(d * g);
    return six;
}

/// The projection on |Jω| = G0 of a rigid body whose sub-flows both keep |G| (the torque-free
/// body, the cavity, the orthogonal servo torque): ω ← ω G0/|Jω| after each step (Hairer, Lubich
/// & Wanner, Geometric Numerical Integration, IV.4). Each sub-flow keeps |G| exactly but rounds
/// it, and near a slowly changing ω the rounding repeats step after step: a secular drift of
/// ~1e-16 per step without it (2.6e-11 over 2e6 steps of the cavity, bench/long_horizon.py).
template <class System>
class MomentumNormProjection {
public:
    MomentumNormProjection(const System& system, const typename System::State& y0) {
        if constexpr (has_momentum_norm<System>::value) {
            if (!system.keeps_momentum_norm()) return;
            moments_ = system.body().moments();
            G0_ = moments_.cwiseProduct(y0.template head<3>()).norm();
            active_ = G0_ > 0.0;
        }
    }
    bool active() const { return active_; }
    void apply(typename System::State& y) const {
        if (!active_) return;
        const double G = moments_.cwiseProduct(y.template head<3>()).norm();
        if (G > 0.0) y.template head<3>() *= G0_ / G;
    }

private:
    bool active_ = false;
    Vec3 moments_ = Vec3::Ones();
    double G0_ = 0.0;
};

}  // namespace splitting_detail

/// One composite step of size h from (t, y): P(a_0 h) F(b_1 h) P(a_1 h) … F(b_s h) P(a_s h), the
/// halves of neighbouring Strang steps merged (a_0 = c_1/2, a_i = (c_i + c_{i+1})/2, a_s = c_s/2).
template <class System>
class SplittingStep {
public:
    using State = typename System::State;
    SplittingStep(const System& system, int order) : system_(system) {
        const std::vector<double> c = splitting_detail::strang_fractions(order);
        free_ = c;
        perturb_.assign(c.size() + 1, 0.0);
        for (std::size_t i = 0; i < c.size(); ++i) {
            perturb_[i] += 0.5 * c[i];
            perturb_[i + 1] += 0.5 * c[i];
        }
    }
    /// Prepares the perturbation flows of step size h (once per distinct h).
    void prepare(double h) {
        if (h == h_) return;
        h_ = h;
        prepared_.clear();
        for (double a : perturb_) prepared_.push_back(Perturbation::over(system_, a * h));
    }
    /// y ← the composite step of size h from time t; returns the number of sub-flows.
    long advance(double t, double h, State& y) {
        prepare(h);
        double time = t;
        prepared_[0].apply(system_, time, y);
        for (std::size_t i = 0; i < free_.size(); ++i) {
            system_.free_flow(free_[i] * h, y);
            time += free_[i] * h;
            prepared_[i + 1].apply(system_, time, y);
        }
        return static_cast<long>(2 * free_.size() + 1);
    }
    /// The same step of size h from (t, y) without touching the prepared flows of the main step.
    State partial(double t, double h, const State& y) const {
        State z = y;
        if (h == 0.0) return z;
        double time = t;
        Perturbation::over(system_, perturb_[0] * h).apply(system_, time, z);
        for (std::size_t i = 0; i < free_.size(); ++i) {
            system_.free_flow(free_[i] * h, z);
            time += free_[i] * h;
            Perturbation::over(system_, perturb_[i + 1] * h).apply(system_, time, z);
        }
        model::system::project(system_, z);
        return z;
    }

private:
    const System& system_;
    std::vector<double> free_, perturb_;
    using Perturbation = PerturbationFlow<System>;
    std::vector<Perturbation> prepared_;
    double h_ = std::numeric_limits<double>::quiet_NaN();
};

namespace splitting_detail {

/// Evenly spaced steps of a run at which the splitting probes its local error (ErrorProbe): 32,
/// but at most one step in three, so that the three composite steps of each probe at most double
/// a short run and cost 1 % of one of 10⁴ steps. (One in ten was too sparse: the local error is
/// peaked along an orbit, and the orthogonal servo's estimate at h = 0.04 over t = 6 fell to a
/// third of the error.)
constexpr double kProbes = 32.0;
inline double probe_stride(double n_steps) { return std::max(3.0, std::floor(n_steps / kProbes)); }

/// The splitting's own error estimate (Richardson; HNW I §II.4): from (t, y), one composite step
/// of h against two of h/2. With the local error C h^(p+1) of a method of order p, their
/// difference is C h^(p+1) (1 − 2^-p), so the local error of the step of h is
///   le = |y_h − y_{h/2,h/2}|∞ / (1 − 2^-p),
/// taken relative to max|y_i|. Over n = span/h steps the local errors add up at most linearly
/// (the phase error of a conservative flow does): the global estimate is n·le = span·C·h^p. A
/// difference at the level of rounding (le ≤ kRounding = 32ε: a composite step rounds a few
/// ulps per sub-flow) is not truncation: it is the step's own error floor δ, and it adds up
/// linearly too, n·δ. (It was once counted as a random walk, √n·δ; but the sub-flows' constants
/// are recomputed from the state at every step and round the same way step after step: a body
/// (1, 2, 3) under a constant torque and damping, order 4 over 46 361 steps of 2.2e-3, erred
/// 3.2e-10 where √n·δ read 7.6e-13, and no smaller step took the error below that floor.) The
/// floor makes the error of a step h at least (span/h)·δ: the step that meets rtol is bounded
/// below, and an rtol under the least total estimate cannot be met (choose_step takes the
/// step of least estimate; the run then warns with the number). Three composite steps per probe.
template <class System>
class ErrorProbe {
public:
    using State = typename System::State;
    ErrorProbe(const SplittingStep<System>& stepper, const MomentumNormProjection<System>& keep_G, int order)
        : stepper_(stepper), keep_G_(keep_G), order_(order) {}

    /// le/h^(p+1)·h^(p+1) from (t, y) with the full step's result y_h (projected as the run does).
    double local_error(double t, double h, const State& y, const State& y_h) const {
        State half = stepper_.partial(t, 0.5 * h, y);
        keep_G_.apply(half);
        State two = stepper_.partial(t + 0.5 * h, 0.5 * h, half);
        keep_G_.apply(two);
        const double scale = std::max(y.cwiseAbs().maxCoeff(), std::numeric_limits<double>::min());
        return (y_h - two).cwiseAbs().maxCoeff() / scale / (1.0 - std::ldexp(1.0, -order_));
    }
    /// The same, taking the step of h itself.
    double local_error(double t, double h, const State& y) const {
        State y_h = stepper_.partial(t, h, y);
        keep_G_.apply(y_h);
        return local_error(t, h, y, y_h);
    }

    static constexpr double kRounding = 32.0 * std::numeric_limits<double>::epsilon();
    /// The global estimate over `steps` steps from the largest probed le/h (truncation) and the
    /// largest probed rounding-level le (the step's floor δ): span·le/h + n·δ.
    static double global(double span, double steps, double truncation_per_step, double rounding) {
        return span * truncation_per_step + steps * rounding;
    }
    /// Splits a local error into its truncation (above kRounding) and rounding parts.
    static std::pair<double, double> parts(double le) {
        return {std::max(le - kRounding, 0.0), std::min(le, kRounding)};
    }

    /// A step for the global estimate span·C·h^p + (span/h)·δ ≤ rtol/4, C the largest over 8
    /// states of the free orbit from y0 (a factor 4 of room for the rest of its variation along
    /// the run, which the run's own probes then watch): from a first guess of 1/10 of the fastest
    /// rate's time scale, h ← h (rtol/(4 est(h)))^(1/p) at most four times (each new h within a
    /// factor 100 of the last, never above the span), until est(h) ≤ rtol/4. An estimate of zero
    /// (a perturbation whose composition is exact) takes the whole span. The floor bounds h below:
    /// the step never goes under h* = (δ/(p C))^(1/(p+1)), where the estimate is least (a
    /// smaller step only adds rounding), and the run warns when even that misses rtol.
    double choose_step(const System& system, double t0, const State& y0, double span, double rtol) const {
        // the probe's states: y0 carried by the exact free flow to 8 evenly spaced times of the
        // span (the orbit of the weakly perturbed body; the local error varies along it)
        std::array<State, 8> states;
        std::array<double, 8> times;
        states[0] = y0, times[0] = t0;
        for (std::size_t k = 1; k < states.size(); ++k) {
            states[k] = states[k - 1];
            system.free_flow(span / 8.0, states[k]);
            times[k] = t0 + static_cast<double>(k) * span / 8.0;
        }
        const double speed = y0.template head<3>().cwiseAbs().maxCoeff();
        const double target = 0.25 * rtol;
        double h = speed > 0.0 ? std::min(span, 0.1 / speed) : span;
        constexpr int kTries = 5;
        for (int k = 0; k < kTries; ++k) {
            double largest = 0.0;
            for (std::size_t i = 0; i < states.size(); ++i) largest = std::max(largest, local_error(times[i], h, states[i]));
            const auto [truncation, rounding] = parts(largest);
            const double estimate = global(span, span / h, truncation / h, rounding);
            if (!std::isfinite(estimate)) {
                h /= 100.0;
                continue;
            }
            if (truncation == 0.0) {  // no truncation seen at h: a larger step costs nothing in accuracy until it shows
                if (h == span || k + 1 == kTries) break;
                h = std::min(span, 100.0 * h);
                continue;
            }
            // le = C h^(p+1) + δ measured at h: the largest step whose estimate meets the target
            const double C = truncation / std::pow(h, order_ + 1);
            const double next = std::min(span, std::clamp(least_step(span, C, target), 0.01 * h, 100.0 * h));
            const bool settled = std::abs(next - h) <= 0.1 * h;
            if (settled || (estimate <= target && next >= h && k + 1 == kTries)) {
                h = std::min(h, next);
                break;
            }
            h = next;
        }
        return h;
    }

    /// The largest step h whose estimate span·C·h^p + (span/h)·δ (δ = kRounding) is at most
    /// `target`; the step of least estimate, h* = (δ/(p C))^(1/(p+1)), when none is.
    double least_step(double span, double C, double target) const {
        const double p = order_;
        auto estimate = [&](double h) { return span * C * std::pow(h, p) + span / h * kRounding; };
        const double best = std::pow(kRounding / (p * C), 1.0 / (p + 1.0));
        if (estimate(best) >= target) return best;
        double low = best, high = std::max(best, span);
        if (estimate(high) <= target) return high;
        for (int i = 0; i < 60; ++i) {  // the estimate grows with h above h*: bisect in log h
            const double middle = std::sqrt(low * high);
            (estimate(middle) <= target ? low : high) = middle;
        }
        return low;
    }

private:
    const SplittingStep<System>& stepper_;
    const MomentumNormProjection<System>& keep_G_;
    int order_;
};

}  // namespace splitting_detail

/// Integrates `system` from (t0, y0) to t1 with steps of options.step (the last one shortened to
/// land on t1) and the composition of options.splitting_order. Output times and events inside a
/// step use the method itself: y(t_n + s) = the composite step of size s from y_n (a continuous
/// extension of the method's order, equal to y_{n+1} at s = h). The dense output kept after the
/// run (Options::dense_output) is the cubic Hermite interpolant of (y_n, f_n, y_{n+1}, f_{n+1}).
/// stats.rhs_evals counts the sub-flows (free and perturbation), not right-hand sides.
///
/// Honesty of a fixed step (splitting_detail::ErrorProbe): step = 0 chooses h from rtol; a step
/// above the span is clamped to it with a warning; the run probes its local error at up to
/// kProbes = 32 evenly spaced steps, at most one in three (three extra composite steps each) and reports
/// span·max(le)/h + n·δ (ErrorProbe::global) as Result::error_estimate and in Result::notes, with a warning when it exceeds rtol. A sub-flow
/// that throws (an input its closed form cannot take) ends the run with status solver_failure,
/// the trajectory up to the last step kept.
template <class System>
Result splitting(const System& system, double t0, const typename System::State& y0, double t1, const Options& options,
                 const Control* control = nullptr) {
    using State = typename System::State;
    validate(options, t0, t1);
    require_finite(y0, "initial state y0");
    if (!(options.step >= 0.0) || std::isinf(options.step))
        throw std::invalid_argument("method 'splitting' takes a fixed step h > 0, or step = 0 to choose it from rtol "
                                    "(got step = " + format_value(options.step) + ")");
    system.require_splitting();

    Result result;
    result.method = method_name(Method::Splitting);
    const std::vector<double> outputs = output_times(options, t0, t1);
    Recorder<System> record(system, result, outputs.size(), options.only_measured_outputs);
    EventLocator<System> events(system, options.events, result);
    result.dense = make_dense<System>(options);
    Stats& stats = result.stats;

    const double direction = t1 >= t0 ? 1.0 : -1.0;
    OutputCursor<System> cursor(record, outputs, direction);
    const double span = std::abs(t1 - t0);
    State y = y0;
    model::system::project(system, y);
    cursor.start(t0, y);
    events.start(t0, y);
    if (t0 == t1) return result;
    SplittingStep<System> stepper(system, options.splitting_order);
    const splitting_detail::MomentumNormProjection<System> keep_G(system, y);
    const splitting_detail::ErrorProbe<System> probe(stepper, keep_G, options.splitting_order);
    double t = t0;
    // Stopped (Ctrl-C, or integrate::Interruption from a user's function that saw it) before the
    // step from t: the outputs up to there kept, and (t, y) where the run would continue.
    auto stop_interrupted = [&]() {
        mark_interrupted(result, t);
        keep_last(result, t, y, 0.0);
    };
    double step = options.step;
    try {
        if (step == 0.0) {
            step = probe.choose_step(system, t0, y, span, options.rtol);
            result.notes.push_back("splitting: step h = " + format_number(step, 3) + " chosen from rtol = " +
                                   format_number(options.rtol, 3) + " (order " + std::to_string(options.splitting_order) +
                                   ", local error probed with steps of h and h/2 at 8 points of the free orbit)");
        } else if (step > span) {
            result.warnings.push_back("splitting: step = " + format_value(step) + " exceeds the span |t1 - t0| = " +
                                      format_value(span) + ": clamped to one step of " + format_value(span));
            step = span;
        }
    } catch (const std::invalid_argument& e) {
        result.status = Status::SolverFailure;
        result.message = std::string("the splitting's probe at t0 failed: ") + e.what();
        keep_last(result, t0, y, 0.0);
        return result;
    } catch (const Interruption&) {
        stop_interrupted();
        return result;
    }
    const double h_full = direction * step;
    const double n_steps = std::ceil(span / step * (1.0 - 4.0 * std::numeric_limits<double>::epsilon()));
    const double probe_stride = splitting_detail::probe_stride(n_steps);
    double worst_truncation = 0.0, worst_rounding = 0.0;  // the largest probed le/h and rounding-level le
    Ticker ticker(control, t0, t1);
    State f0, f1;
    // The number of steps is known in advance: run as far as the budget allows, like the
    // adaptive methods, and say why the run stopped.
    const double budget = std::min(n_steps, static_cast<double>(options.max_steps));
    try {
        for (double i = 0.0; i < budget; i += 1.0) {
            if (!ticker.keep_going(t)) {
                stop_interrupted();
                return result;
            }
            // Full steps are of size h_full exactly (t_n = t0 + n h_full only labels them); the last
            // one is shortened to land on t1.
            const bool last = i + 1.0 >= n_steps;
            const double t_new = last ? t1 : t0 + (i + 1.0) * h_full;
            const double h = last ? t1 - t : h_full;
            State y_new = y;
            try {
                stats.rhs_evals += stepper.advance(t, h, y_new);
                model::system::project(system, y_new);
                keep_G.apply(y_new);
                if (std::fmod(i, probe_stride) == 0.0 && h != 0.0 && all_finite(y_new)) {
                    const auto [truncation, rounding] = probe.parts(probe.local_error(t, h, y, y_new));
                    worst_truncation = std::max(worst_truncation, truncation / std::abs(h));
                    worst_rounding = std::max(worst_rounding, rounding);
                }
            } catch (const std::invalid_argument& e) {
                result.status = Status::SolverFailure;
                result.message = "the splitting step from t = " + format_number(t, 17) + " failed: " + e.what();
                keep_last(result, t, y, std::abs(h));
                return result;
            }
            ++stats.steps;
            stats.last_step = std::abs(h);
            if (!all_finite(y_new)) {
                result.status = Status::NonFiniteState;
                result.message = "the state became non-finite (inf/NaN) in the splitting step from t = " + format_number(t, 17);
                return result;
            }
            const State y_start = y;
            const double t_start = t;
            auto dense = [&](double time) { return stepper.partial(t_start, time - t_start, y_start); };
            const double t_stop = events.step(t, t_new, y_new, dense);
            const bool terminated = !std::isnan(t_stop);
            if (result.dense) {  // cubic Hermite in s = (t − t_n)/h
                system.rhs(t, y, f0);
                system.rhs(t_new, y_new, f1);
                std::array<State, 4> c;
                c[0] = y;
                c[1] = h * f0;
                c[2] = 3.0 * (y_new - y) - h * (2.0 * f0 + f1);
                c[3] = 2.0 * (y - y_new) + h * (f0 + f1);
                result.dense->add(t, terminated ? t_stop : t_new, t, h, 3, c[0].data());
            }
            if (cursor.inside(t_new, t_stop, dense)) {
                mark_terminated(result, t_stop);
                return result;
            }
            t = t_new;
            y = y_new;
            cursor.at_end(t, y, options.every_step);
        }
    } catch (const Interruption&) {  // in the step from t (its outputs are recorded only once it is whole)
        stop_interrupted();
        return result;
    }
    if (budget < n_steps) {
        result.status = Status::MaxStepsReached;
        result.message = "max_steps = " + std::to_string(options.max_steps) + " reached at t = " + format_number(t) +
                         " before t1 = " + format_number(t1) + ": splitting with step " + format_value(step) +
                         " needs " + format_number(n_steps, 17) + " steps (raise max_steps or the step)";
    }
    result.error_estimate = probe.global(std::abs(t - t0), static_cast<double>(stats.steps), worst_truncation, worst_rounding);
    result.notes.push_back("splitting: estimated global error " + format_number(result.error_estimate, 2) +
                           " relative to max|y_i| (steps of h = " + format_number(step, 3) +
                           " against h/2, probed at " + format_number(std::ceil(stats.steps / probe_stride), 1) + " of " +
                           std::to_string(stats.steps) + " steps)");
    if (result.error_estimate > options.rtol) {
        const double floor = static_cast<double>(stats.steps) * worst_rounding;
        if (floor > 0.5 * result.error_estimate) {  // rounding, not truncation: a smaller step only adds to it
            result.warnings.push_back("splitting: estimated error " + format_number(result.error_estimate, 2) +
                                      " exceeds rtol = " + format_number(options.rtol, 2) + ", mostly the steps' rounding (" +
                                      format_number(worst_rounding, 2) + " per step over " + std::to_string(stats.steps) +
                                      " steps of h = " + format_number(step, 3) + "), which a smaller step only adds to: "
                                      "rtol below ~" + format_number(result.error_estimate, 1) + " needs fewer steps of "
                                      "a higher order (splitting_order) or another method (taylor, dop853)");
        } else {
            const double suggested = step * std::pow(0.5 * options.rtol / result.error_estimate, 1.0 / options.splitting_order);
            result.warnings.push_back("splitting: estimated error " + format_number(result.error_estimate, 2) +
                                      " exceeds rtol = " + format_number(options.rtol, 2) + " with step h = " +
                                      format_number(step, 3) + ": take h <= " + format_number(suggested, 2) +
                                      " or leave step out to have it chosen from rtol");
        }
    }
    return result;
}

}  // namespace gyrostat::integrate
