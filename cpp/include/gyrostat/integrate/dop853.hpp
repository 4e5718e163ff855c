// Fixed-size, allocation-free DOP853: Dormand–Prince 8(5,3) with step-size control and the
// 7th-order dense output (Hairer, Nørsett & Wanner, Solving ODEs I, §II.5 and §II.10).
// The step-size controller and error norm follow SciPy's DOP853 (same method, same norm), so the
// two are comparable at equal tolerance; the hot loop has no allocation and no virtual call.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "gyrostat/integrate/control.hpp"
#include "gyrostat/integrate/diagnose.hpp"
#include "gyrostat/integrate/events.hpp"
#include "gyrostat/integrate/dop853_tableau.hpp"
#include "gyrostat/integrate/options.hpp"
#include "gyrostat/integrate/recording.hpp"
#include "gyrostat/integrate/stiffness.hpp"

namespace gyrostat::integrate {

namespace dop853_detail {
constexpr double kSafety = 0.9;
constexpr double kMinFactor = 0.2;
constexpr double kMaxFactor = 10.0;
constexpr double kErrorExponent = -1.0 / 8.0;   // error estimator of order 7
constexpr int kMaxNonFiniteTrials = 25;          // 0.2^25 ≈ 3e-18: the step cannot shrink further usefully

template <class State>
double rms(const State& v) {
    return std::sqrt(v.squaredNorm() / static_cast<double>(v.size()));
}

/// v / scale componentwise, with 0/0 = 0: a component that is exactly zero with atol = 0 has no
/// error scale, and an exactly zero error there is no error (not NaN).
template <class State>
State weighted(const State& v, const State& scale) {
    State w;
    for (Eigen::Index i = 0; i < v.size(); ++i) w[i] = v[i] == 0.0 ? 0.0 : v[i] / scale[i];
    return w;
}

/// The dense output y + x(F0 + (1−x)(F1 + x(F2 + (1−x)(F3 + x(F4 + (1−x)(F5 + x F6)))))),
/// x = (t − t_n)/h, as the monomials c_0 … c_7 in x (for DenseOutput).
template <class State>
void monomials(const std::array<State, 7>& F, const State& y, State* c) {
    int degree = 0;
    c[0] = F[6];
    auto x_times_plus = [&](const State& a) {  // c ← a + x c
        for (int k = degree; k >= 0; --k) c[k + 1] = c[k];
        c[0] = a;
        ++degree;
    };
    auto one_minus_x_times_plus = [&](const State& a) {  // c ← a + (1 − x) c
        c[degree + 1] = -c[degree];
        for (int k = degree; k >= 1; --k) c[k] = c[k] - c[k - 1];
        c[0] += a;
        ++degree;
    };
    x_times_plus(F[5]);
    one_minus_x_times_plus(F[4]);
    x_times_plus(F[3]);
    one_minus_x_times_plus(F[2]);
    x_times_plus(F[1]);
    one_minus_x_times_plus(F[0]);
    x_times_plus(y);
}
}  // namespace dop853_detail

/// One DOP853 segment of `run` from (t0, y0) to run.t1: outputs, events, dense output and
/// statistics continue those already in run.result (a plain run has one segment, method 'auto'
/// several). With a `monitor`, Hairer's stiffness test runs after every accepted step and the
/// segment stops where the monitor asks for BDF: returns true then, with Result::t_last,
/// y_last, h_next at the hand-over; false when the run ended (at t1, a terminal event, a
/// failure or an interruption, the Result saying which).
template <class System>
bool dop853_segment(const System& system, Recording<System>& run, double t0, const typename System::State& y0,
                    const Options& options, const Control* control, StiffnessMonitor<System>* monitor = nullptr) {
    using namespace dop853_detail;
    namespace tab = dop853_tableau;
    using State = typename System::State;
    constexpr int n = System::dim;

    Result& result = run.result;
    const double t1 = run.t1, direction = run.direction;
    const double rtol = options.rtol, atol = options.atol;
    Stats& stats = result.stats;

    double t = t0;
    State y = y0;
    model::system::project(system, y);
    State f;
    system.rhs(t, y, f);
    ++stats.rhs_evals;

    if (t0 == t1) return false;
    if (!all_finite(f)) {
        result.status = Status::NonFiniteState;
        result.message = "the right-hand side is not finite at the initial state (t = " + format_number(t0) + ")";
        return false;
    }

    // Initial step (Hairer's algorithm, as in SciPy's select_initial_step).
    double h_abs = options.first_step;
    const double span = std::abs(t1 - t0);
    if (h_abs == 0.0) {
        const State scale = (atol + (y.cwiseAbs() * rtol).array()).matrix();
        const double d0 = rms(weighted(y, scale));
        const double d1 = rms(weighted(f, scale));
        double h0 = (d0 < 1e-5 || d1 < 1e-5) ? 1e-6 : 0.01 * d0 / d1;
        h0 = std::min(h0, span);
        State y1 = y + h0 * direction * f, f1;
        system.rhs(t + h0 * direction, y1, f1);
        ++stats.rhs_evals;
        const double d2 = rms(weighted(State(f1 - f), scale)) / h0;
        const double h1 = (d1 <= 1e-15 && d2 <= 1e-15) ? std::max(1e-6, h0 * 1e-3)
                                                       : std::pow(0.01 / std::max(d1, d2), 1.0 / 8.0);
        h_abs = std::min({100 * h0, h1, span});
        if (!std::isfinite(h_abs) || h_abs <= 0.0) h_abs = std::min(1e-6, span);
    }

    std::array<State, tab::n_stages_extended> k;
    State y_new, f_new, err5, err3, scale, stage;  // stage: the argument of the last stage (c = 1)
    Ticker ticker(control, run.t0, t1);

    while (direction * (t - t1) < 0.0) {
        if (!ticker.keep_going(t)) {
            mark_interrupted(result, t);
            keep_last(result, t, y, h_abs);
            return false;
        }
        if (stats.steps >= options.max_steps) {
            result.status = Status::MaxStepsReached;
            result.message = "max_steps = " + std::to_string(options.max_steps) + " reached at t = " + format_number(t) +
                             " before t1 = " + format_number(t1) + "." + stiffness_hint(system, t, y, stats.last_step, span);
            keep_last(result, t, y, h_abs);
            return false;
        }
        const double min_step = 10.0 * std::abs(std::nextafter(t, direction * std::numeric_limits<double>::infinity()) - t);
        h_abs = std::min(h_abs, options.max_step);
        if (h_abs < min_step) h_abs = min_step;

        bool accepted = false, rejected = false;
        int non_finite_trials = 0;
        double h = 0.0, t_new = t, error_norm = 0.0;
        while (!accepted) {
            if (h_abs < min_step || non_finite_trials >= kMaxNonFiniteTrials) {
                if (non_finite_trials > 0) {
                    result.status = Status::NonFiniteState;
                    result.message = "the state became non-finite (inf/NaN) on every trial step from t = " +
                                     format_number(t, 17) + " (|y| = " + format_number(y.norm()) +
                                     "): the solution overflows or leaves the model's domain there";
                } else {
                    result.status = Status::StepSizeUnderflow;
                    result.message = "step size underflow at t = " + format_number(t, 17) + ": the step needed (< " +
                                     format_number(min_step) + ") is below the resolution of t." +
                                     stiffness_hint(system, t, y, stats.last_step, span);
                }
                keep_last(result, t, y, stats.last_step);
                return false;
            }
            h = h_abs * direction;
            t_new = t + h;
            if (direction * (t_new - t1) > 0.0) t_new = t1;
            h = t_new - t;
            h_abs = std::abs(h);

            // The 12 stages and the 8th-order solution.
            k[0] = f;
            for (int s = 1; s < tab::n_stages; ++s) {
                State dy = tab::a[s][0] * k[0];
                for (int j = 1; j < s; ++j)
                    if (tab::a[s][j] != 0.0) dy += tab::a[s][j] * k[j];
                stage = y + h * dy;
                system.rhs(t + tab::c[s] * h, stage, k[s]);
            }
            State incr = tab::b[0] * k[0];
            for (int j = 1; j < tab::n_stages; ++j)
                if (tab::b[j] != 0.0) incr += tab::b[j] * k[j];
            y_new = y + h * incr;
            system.rhs(t_new, y_new, f_new);
            k[tab::n_stages] = f_new;
            stats.rhs_evals += tab::n_stages;

            // Error: the 5th- and 3rd-order embedded estimates combined as in DOP853.
            scale = (atol + (y.cwiseAbs().cwiseMax(y_new.cwiseAbs()) * rtol).array()).matrix();
            err5.setZero();
            err3.setZero();
            for (int j = 0; j <= tab::n_stages; ++j) {
                if (tab::e5[j] != 0.0) err5 += tab::e5[j] * k[j];
                if (tab::e3[j] != 0.0) err3 += tab::e3[j] * k[j];
            }
            const double e5 = weighted(err5, scale).squaredNorm();
            const double e3 = weighted(err3, scale).squaredNorm();
            error_norm = (e5 == 0.0 && e3 == 0.0) ? 0.0 : h_abs * e5 / std::sqrt((e5 + 0.01 * e3) * n);

            if (!std::isfinite(error_norm)) {
                ++non_finite_trials;
                ++stats.rejected_steps;
                h_abs *= kMinFactor;
                rejected = true;
                continue;
            }
            if (error_norm < 1.0) {
                double factor = error_norm == 0.0 ? kMaxFactor
                                                  : std::min(kMaxFactor, kSafety * std::pow(error_norm, kErrorExponent));
                if (rejected) factor = std::min(1.0, factor);
                h_abs *= factor;
                accepted = true;
            } else {
                h_abs *= std::max(kMinFactor, kSafety * std::pow(error_norm, kErrorExponent));
                ++stats.rejected_steps;
                rejected = true;
            }
        }
        ++stats.steps;
        stats.last_step = std::abs(h);
        const bool stiff = monitor && monitor->explicit_step(t, h, y_new, f_new, stage, k[tab::n_stages - 1]);

        // The 7th-order dense output of the step, its three extra stages computed only for steps
        // that contain an output time or an event.
        bool dense_ready = false;
        std::array<State, 7> F;
        auto dense = [&](double time) {
            if (!dense_ready) {
                for (int s = tab::n_stages + 1; s < tab::n_stages_extended; ++s) {
                    State dy = tab::a[s][0] * k[0];
                    for (int j = 1; j < s; ++j)
                        if (tab::a[s][j] != 0.0) dy += tab::a[s][j] * k[j];
                    system.rhs(t + tab::c[s] * h, State(y + h * dy), k[s]);
                }
                stats.rhs_evals += tab::n_stages_extended - tab::n_stages - 1;
                const State delta = y_new - y;
                F[0] = delta;
                F[1] = h * k[0] - delta;
                F[2] = 2.0 * delta - h * (f_new + k[0]);
                for (int i = 0; i < 4; ++i) {
                    State acc = tab::d[i][0] * k[0];
                    for (int j = 1; j < tab::n_stages_extended; ++j)
                        if (tab::d[i][j] != 0.0) acc += tab::d[i][j] * k[j];
                    F[3 + i] = h * acc;
                }
                dense_ready = true;
            }
            const double x = (time - t) / h;
            State value = State::Zero();
            for (int i = 0; i < 7; ++i) {
                value += F[6 - i];
                value *= (i % 2 == 0) ? x : (1.0 - x);
            }
            return State(value + y);
        };
        const double t_stop = run.events.step(t, t_new, y_new, dense);
        const bool terminated = !std::isnan(t_stop);
        if (result.dense) {
            dense(t);  // the dense coefficients F of this step
            std::array<State, 8> c;
            monomials(F, y, c.data());
            result.dense->add(t, terminated ? t_stop : t_new, t, h, 7, c[0].data());
        }
        if (run.cursor.inside(t_new, t_stop, dense)) {
            mark_terminated(result, t_stop);
            return false;
        }

        if constexpr (model::system::has_projection<System>::value) {
            system.project(y_new);
            system.rhs(t_new, y_new, f_new);
            ++stats.rhs_evals;
        }
        t = t_new;
        y = y_new;
        f = f_new;
        run.cursor.at_end(t, y, options.every_step);
        if (stiff && direction * (t - t1) < 0.0) {
            keep_last(result, t, y, h_abs);
            return true;
        }
    }
    keep_last(result, t, y, h_abs);
    return false;
}

/// Integrates `system` from (t0, y0) to t1. Never throws on a failing run: the result carries the
/// partial trajectory, the status and the reason. Throws std::invalid_argument on bad options.
template <class System>
Result dop853(const System& system, double t0, const typename System::State& y0, double t1, const Options& options,
              const Control* control = nullptr) {
    validate(options, t0, t1);
    require_finite(y0, "initial state y0");
    Result result;
    result.method = method_name(Method::Dop853);
    Recording<System> run(system, options, t0, t1, result);
    typename System::State y = y0;
    model::system::project(system, y);
    run.start(y);
    dop853_segment(system, run, t0, y, options, control);
    return result;
}

}  // namespace gyrostat::integrate
