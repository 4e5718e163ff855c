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
#include "gyrostat/numeric/dop853_tableau.hpp"
#include "gyrostat/integrate/options.hpp"
#include "gyrostat/integrate/recording.hpp"
#include "gyrostat/integrate/stiffness.hpp"
#include "gyrostat/model/system.hpp"
#include "gyrostat/integrate/trajectories.hpp"

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

/// One trajectory for the step loop below (integrate/trajectories.hpp): its Recording (outputs,
/// events, dense output, statistics) and, for method 'auto', the stiffness monitor.
/// The work after an accepted step (stiff, inside, at_end) stays out of line: dop853_steps is
/// flattened, and inlining the event locator, the recorder and the monitor into it (per model)
/// cost up to 80 s of compile time for one model and no measurable speed (a step is 12
/// right-hand sides; measured on the gyrostat with and without attitude: same time to 1 %).
template <class System>
class OneRun : public OneTrajectory<System> {
public:
    using typename OneTrajectory<System>::Vector;
    using typename OneTrajectory<System>::State;

    OneRun(const System& system, Recording<System>& run, StiffnessMonitor<System>* monitor)
        : OneTrajectory<System>(system, run.result), run_(run), monitor_(monitor) {}

    void rhs(double t, const Vector& y, Vector& dy) const { this->system_.rhs(t, y[0], dy[0]); }
    void start(double t, const Vector& y) { reached(t, y[0], 0.0); }  // the caller recorded t0 (Recording::start)
    void empty_span(int, double, const Vector&) { this->active_ = false; }
    void fail_at_start(int, Status status, std::string message, double, const Vector&) {
        run_.result.status = status;
        run_.result.message = std::move(message);
        this->active_ = false;
    }
    /// Hairer's stiffness test after an accepted step (method 'auto'): true asks for BDF.
    [[gnu::noinline]] bool stiff(double t, double h, const Vector& y_new, const Vector& f_new, const Vector& stage, const Vector& f_stage) {
        return monitor_ && monitor_->explicit_step(t, h, y_new[0], f_new[0], stage[0], f_stage[0]);
    }
    /// The accepted step from t to t_new: events, dense output and the outputs inside it from
    /// `dense` (dense.value(0, time), dense.coefficients()). True: a terminal event ended the run.
    template <class Dense>
    [[gnu::noinline]] bool inside(int, double t, double t_new, double h, const Vector& y, const Vector& y_new, Dense& dense) {
        auto value = [&](double time) { return dense.value(0, time); };
        const double t_stop = run_.events.step(t, t_new, y_new[0], value);
        const bool terminated = !std::isnan(t_stop);
        if (run_.result.dense) {
            const auto& F = dense.coefficients(0);
            std::array<State, 7> f;
            for (int i = 0; i < 7; ++i) f[i] = F[i][0];
            std::array<State, 8> c;
            dop853_detail::monomials(f, y[0], c.data());
            run_.result.dense->add(t, terminated ? t_stop : t_new, t, h, 7, c[0].data());
        }
        if (run_.cursor.inside(t_new, t_stop, value)) {
            mark_terminated(run_.result, t_stop);
            this->active_ = false;
            return true;
        }
        reached(t_new, y_new[0], std::abs(h));  // the outputs reach t_new (the step's end comes next)
        return false;
    }
    [[gnu::noinline]] void at_end(int l, double t, const Vector& y, double h_next, bool every_step) {
        reached(t, y[0], h_next);
        run_.cursor.at_end(t, y[0], every_step);
        if (t == run_.t1) this->finish(l, t, y[0], h_next);
    }
    /// The hand-over to BDF at (t, y) (method 'auto').
    void hand_over(double t, const Vector& y, double h_next) { this->finish(0, t, y[0], h_next); }
    /// A user's function stopped the run (integrate::Interruption, thrown in a right-hand side):
    /// it ends Interrupted where its recorded outputs reach, as when the Ticker stops it.
    void interrupt() {
        if (!this->active_) return;
        mark_interrupted(run_.result, reached_t_);
        this->finish(0, reached_t_, reached_y_, reached_h_);
    }

private:
    /// The last point the run's outputs reach: the start, the end of an accepted step, or (between
    /// the outputs inside a step and its end) the step's end before projection.
    void reached(double t, const State& y, double h_next) { reached_t_ = t, reached_y_ = y, reached_h_ = h_next; }

    Recording<System>& run_;
    StiffnessMonitor<System>* monitor_;
    double reached_t_ = 0.0, reached_h_ = 0.0;
    State reached_y_;
};

namespace dop853_detail {
// The failures of a trajectory before its trial step, out of the step loop (cold, and so that
// the loop stays small enough for the compiler to inline the model's right-hand side into it).
/// The first step (Hairer's algorithm, as in SciPy's select_initial_step), per trajectory, from
/// f = f(t, y). (Out of the step loop, with the failures below: the loop stays small enough for
/// the compiler to inline the model's right-hand side into its stages.)
template <class Run, class WeightedSquares>
[[gnu::noinline]] typename Run::Value initial_step(Run& run, const typename Run::Value& t, const typename Run::Vector& y,
                                                   const typename Run::Vector& f, double span, double direction,
                                                   double rtol, double atol, const WeightedSquares& weighted_squares) {
    using Value = typename Run::Value;
    using Vector = typename Run::Vector;
    using lanes::lane;
    constexpr int n = Run::dim, parts = Run::parts, W = Run::width;
    const int count = run.count();
    Value h_abs;
    Vector scale, y1, f1, df;
    for (int i = 0; i < parts; ++i) scale[i] = atol + y[i].array().abs() * rtol;
    // A quadrature (the averaged models' phase: a rate of O(1) on a value that starts near 0) says
    // nothing of the dynamics' time scale, yet would set h0 ~ 0.01 (atol + rtol |φ0|)/|φ̇| and cost
    // ~log10 of the ramp in steps: an infinite scale leaves it out of d0, d1, d2 (v / ∞ = 0).
    constexpr auto quadratures = model::system::quadratures<typename Run::System>();
    for (const int q : quadratures) {
        if constexpr (parts == 1)
            scale[0][q] = std::numeric_limits<double>::infinity();
        else
            scale[q] = lanes::splat<Value>(std::numeric_limits<double>::infinity());
    }
    constexpr double counted = std::max(1, n - static_cast<int>(quadratures.size()));
    const Value d0 = lanes::sqrt(weighted_squares(y, scale) / counted);
    const Value d1 = lanes::sqrt(weighted_squares(f, scale) / counted);
    const Value h0 = lanes::min(lanes::select(d0 < 1e-5 || d1 < 1e-5, 1e-6, 0.01 * d0 / d1), span);
    for (int i = 0; i < parts; ++i) y1[i] = y[i] + h0 * direction * f[i];
    run.rhs(t + h0 * direction, y1, f1);
    for (int i = 0; i < parts; ++i) df[i] = f1[i] - f[i];
    const Value d2 = lanes::sqrt(weighted_squares(df, scale) / counted) / h0;
    for (int l = 0; l < W; ++l) {  // (lanes past `count` too: they repeat a member)
        if (l < count) ++run.stats(l).rhs_evals;
        double h1 = (lane(d1, l) <= 1e-15 && lane(d2, l) <= 1e-15)
                        ? std::max(1e-6, lane(h0, l) * 1e-3)
                        : std::pow(0.01 / std::max(lane(d1, l), lane(d2, l)), 1.0 / 8.0);
        // Hairer's h1 takes the second as the time scale of the solution's derivatives. A slow
        // system (τ = d0/d1 = |y|/|f| > 10 in the weighted norms: the averaged models, whose rates
        // are O(ε)) has its own, τ: in s = t/τ the same rule reads d1 → d0, d2 → τ² d2, h1 → τ (0.01 /
        // max(d0, τ² d2))^(1/8) (≤ 100 h0 = τ below). Its first step then starts near the slow scale,
        // not at ~0.1 and climbing (the averaged triaxial body at ε = 1e-4: 13 steps → 10). Below
        // τ = 10 (a body turning at ~1 rad/s: τ ~ 1) Hairer's rule stands, as in SciPy's
        // select_initial_step.
        const double tau = lane(d0, l) / lane(d1, l);
        if (tau > 10.0 && std::isfinite(tau))
            h1 = std::max(h1, tau * std::pow(0.01 / std::max(lane(d0, l), tau * tau * lane(d2, l)), 1.0 / 8.0));
        double& h = lane(h_abs, l);
        h = std::min({100 * lane(h0, l), h1, span});
        if (!std::isfinite(h) || h <= 0.0) h = std::min(1e-6, span);
    }
    return h_abs;
}
template <class Run>
[[gnu::cold, gnu::noinline]] void fail_at_start(Run& run, int l, double t0, const typename Run::Vector& y) {
    run.fail_at_start(l, Status::NonFiniteState,
                      "the right-hand side is not finite at the initial state (t = " + format_number(t0) + ")", t0, y);
}
template <class Run>
[[gnu::cold, gnu::noinline]] void fail_max_steps(Run& run, int l, long max_steps, double t, double t1,
                                                 const typename Run::Vector& state, double h_next, double span) {
    decltype(auto) y = run.state(state, l);
    run.fail(l, Status::MaxStepsReached,
             "max_steps = " + std::to_string(max_steps) + " reached at t = " + format_number(t) + " before t1 = " +
                 format_number(t1) + "." + stiffness_hint(run.system(l), t, y, run.stats(l).last_step, span),
             t, y, h_next);
}
template <class Run>
[[gnu::cold, gnu::noinline]] void fail_trial(Run& run, int l, bool non_finite, double t, const typename Run::Vector& state,
                                             double smallest, double span) {
    decltype(auto) y = run.state(state, l);
    const double last_step = run.stats(l).last_step;
    if (non_finite)
        run.fail(l, Status::NonFiniteState,
                 "the state became non-finite (inf/NaN) on every trial step from t = " + format_number(t, 17) +
                     " (|y| = " + format_number(y.norm()) + "): the solution overflows or leaves the model's domain there",
                 t, y, last_step);
    else
        run.fail(l, Status::StepSizeUnderflow,
                 "step size underflow at t = " + format_number(t, 17) + ": the step needed (< " + format_number(smallest) +
                     ") is below the resolution of t." + stiffness_hint(run.system(l), t, y, last_step, span),
                 t, y, last_step);
}
}  // namespace dop853_detail

/// The DOP853 step loop, for one trajectory (OneRun) or the W lanes of a batch (LaneRuns,
/// integrate/trajectories.hpp) from (t0, y0) to t1: each trajectory with its own step size,
/// accepted or rejected on its own error (SciPy's controller and norm). Returns true when a
/// trajectory's stiffness monitor asks for BDF (OneRun::hand_over then noted where).
template <class Run>
[[gnu::flatten]] bool dop853_steps(Run& run, double t0, typename Run::Vector y, double t1, const Options& options,
                  const Control* control) {
    using namespace dop853_detail;
    namespace tab = dop853_tableau;
    using Value = typename Run::Value;
    using Part = typename Run::Part;
    using Vector = typename Run::Vector;
    using State = typename Run::State;
    using lanes::lane;
    constexpr int n = Run::dim, parts = Run::parts, W = Run::width;
    const int count = run.count();
    const double direction = t1 >= t0 ? 1.0 : -1.0, span = std::abs(t1 - t0);
    const double rtol = options.rtol, atol = options.atol;

    // Σ_i (v_i / scale_i)² with 0/0 = 0 (weighted) over one part of the state, and over all of
    // it, per trajectory.
    auto part_squares = [](const Part& v, const Part& scale) -> Value {
        if constexpr (parts == 1)
            return weighted(v, scale).squaredNorm();
        else
            return Value((v == 0.0).select(Value::Zero(), v / scale)).square();
    };
    auto weighted_squares = [&](const Vector& v, const Vector& scale) {
        Value sum = lanes::splat<Value>(0.0);
        for (int i = 0; i < parts; ++i) sum += part_squares(v[i], scale[i]);
        return sum;
    };

    // A quadrature (model/system.hpp: the averaged triaxial model's phase, whose rate depends on the
    // slow variables and feeds back into none) is left out of the local error test, as CVODES
    // leaves its quadratures out by default (errconQ = false): its truncation error is its rate's,
    // which the slow variables' control bounds, while a test relative to its value depends on the
    // value's arbitrary origin (a phase near 0 held the first steps at ~5x growth on its rounding).
    constexpr auto quadratures = model::system::quadratures<typename Run::System>();
    constexpr double controlled = std::max(1, n - static_cast<int>(quadratures.size()));
    auto exclude_quadratures = [&](int part, Part& scale) {
        for (const int q : quadratures) {
            if constexpr (parts == 1)
                scale[q] = std::numeric_limits<double>::infinity();
            else if (q == part)
                scale = Part::Constant(std::numeric_limits<double>::infinity());
        }
        (void)part;
    };

    run.project(y);
    Value t = lanes::splat<Value>(t0);
    run.start(t0, y);
    Vector f;
    run.rhs(t, y, f);
    for (int l = 0; l < count; ++l) {
        ++run.stats(l).rhs_evals;
        if (t0 == t1) {
            run.empty_span(l, t0, y);
            continue;
        }
        if (!all_finite(run.state(f, l))) fail_at_start(run, l, t0, y);
    }
    if (!run.any_active()) return false;

    Value h_abs = lanes::splat<Value>(options.first_step);
    if (options.first_step == 0.0) h_abs = initial_step(run, t, y, f, span, direction, rtol, atol, weighted_squares);

    Vector k[tab::n_stages_extended];
    Vector y_new, f_new, stage;  // stage: the argument of the last stage computed (c = 1 after the 12th)
    Vector F[7];                 // the dense output's coefficients of the step (when needed)
    std::array<bool, W> rejected{}, accepted{};
    std::array<int, W> non_finite_trials{};
    Ticker ticker(control, t0, t1);

    // Stage s: k_s = f(t + c_s h, y + h Σ_j a_sj k_j).
    auto compute_stage = [&](int s, const Value& h) {
        for (int i = 0; i < parts; ++i) {
            Part dy = tab::a[s][0] * k[0][i];
            for (int j = 1; j < s; ++j)
                if (tab::a[s][j] != 0.0) dy += tab::a[s][j] * k[j][i];
            stage[i] = y[i] + h * dy;
        }
        run.rhs(t + tab::c[s] * h, stage, k[s]);
    };

    while (run.any_active()) {
        if (!run.keep_going(ticker, t, y, h_abs)) return false;
        // Each trajectory's trial step (0 for those that are done).
        Value h = lanes::splat<Value>(0.0), t_new = t;
        for (int l = 0; l < count; ++l) {
            if (!run.active(l)) continue;
            const double tl = lane(t, l);
            double& hl = lane(h_abs, l);
            if (run.stats(l).steps >= options.max_steps) {
                fail_max_steps(run, l, options.max_steps, tl, t1, y, hl, span);
                continue;
            }
            const double smallest = min_step(tl, direction);
            if (!rejected[l]) hl = std::max(std::min(hl, options.max_step), smallest);
            if (hl < smallest || non_finite_trials[l] >= kMaxNonFiniteTrials) {
                fail_trial(run, l, non_finite_trials[l] > 0, tl, y, smallest, span);
                continue;
            }
            double end = tl + hl * direction;
            if (direction * (end - t1) > 0.0) end = t1;
            lane(t_new, l) = end;
            lane(h, l) = end - tl;
            hl = std::abs(lane(h, l));
        }
        if (!run.any_active()) break;

        // The 12 stages and the 8th-order solution.
        for (int i = 0; i < parts; ++i) k[0][i] = f[i];
        for (int s = 1; s < tab::n_stages; ++s) compute_stage(s, h);
        for (int i = 0; i < parts; ++i) {
            Part incr = tab::b[0] * k[0][i];
            for (int j = 1; j < tab::n_stages; ++j)
                if (tab::b[j] != 0.0) incr += tab::b[j] * k[j][i];
            y_new[i] = y[i] + h * incr;
        }
        run.rhs(t_new, y_new, f_new);
        for (int i = 0; i < parts; ++i) k[tab::n_stages][i] = f_new[i];

        // Error: the 5th- and 3rd-order embedded estimates combined as in DOP853, over the state
        // less its quadratures (below).
        Value e5 = lanes::splat<Value>(0.0), e3 = e5;
        for (int i = 0; i < parts; ++i) {
            Part scale(atol + y[i].array().abs().max(y_new[i].array().abs()) * rtol);
            exclude_quadratures(i, scale);
            Part err5 = Part::Zero(), err3 = Part::Zero();
            for (int j = 0; j <= tab::n_stages; ++j) {
                if (tab::e5[j] != 0.0) err5 += tab::e5[j] * k[j][i];
                if (tab::e3[j] != 0.0) err3 += tab::e3[j] * k[j][i];
            }
            e5 += part_squares(err5, scale);
            e3 += part_squares(err3, scale);
        }
        const Value error_norm =
            lanes::select(e5 == 0.0 && e3 == 0.0, 0.0, h_abs * e5 / lanes::sqrt((e5 + 0.01 * e3) * controlled));

        bool any_accepted = false;
        for (int l = 0; l < count; ++l) {
            accepted[l] = false;
            if (!run.active(l)) continue;
            Stats& stats = run.stats(l);
            stats.rhs_evals += tab::n_stages;
            const double err = lane(error_norm, l);
            double& hl = lane(h_abs, l);
            if (!std::isfinite(err)) {
                ++non_finite_trials[l];
                ++stats.rejected_steps;
                hl *= kMinFactor;
                rejected[l] = true;
            } else if (err < 1.0) {
                double factor = err == 0.0 ? kMaxFactor : std::min(kMaxFactor, kSafety * std::pow(err, kErrorExponent));
                if (rejected[l]) factor = std::min(1.0, factor);
                hl *= factor;
                accepted[l] = any_accepted = true;
                rejected[l] = false;
                non_finite_trials[l] = 0;
                ++stats.steps;
                stats.last_step = std::abs(lane(h, l));
            } else {
                hl *= std::max(kMinFactor, kSafety * std::pow(err, kErrorExponent));
                ++stats.rejected_steps;
                rejected[l] = true;
            }
        }
        if (!any_accepted) {
            run.fill_done_lanes(t, y, f);
            continue;
        }
        bool stiff = false;
        if constexpr (W == 1) stiff = run.stiff(t, h, y_new, f_new, stage, k[tab::n_stages - 1]);

        // The 7th-order dense output of the step, its three extra stages computed (for every
        // trajectory at once) only when one of them has an output time or an event inside it.
        struct Dense {
            decltype(compute_stage)& stage_of;
            const Value& h;
            const Vector &y, &y_new, &f_new, (&k)[tab::n_stages_extended];
            Run& run;
            Vector (&F)[7];
            const Value& t_of;
            bool ready = false;
            std::array<bool, W> counted{};
            // (out of line: needed only for steps with an output or event inside)
            [[gnu::noinline]] const Vector (&coefficients(int l))[7] {
                if (!ready) {
                    for (int s = tab::n_stages + 1; s < tab::n_stages_extended; ++s) stage_of(s, h);
                    for (int i = 0; i < parts; ++i) {
                        const Part delta = y_new[i] - y[i];
                        F[0][i] = delta;
                        F[1][i] = h * k[0][i] - delta;
                        F[2][i] = 2.0 * delta - h * (f_new[i] + k[0][i]);
                        for (int r = 0; r < 4; ++r) {
                            Part acc = tab::d[r][0] * k[0][i];
                            for (int j = 1; j < tab::n_stages_extended; ++j)
                                if (tab::d[r][j] != 0.0) acc += tab::d[r][j] * k[j][i];
                            F[3 + r][i] = h * acc;
                        }
                    }
                    ready = true;
                }
                if (!counted[l]) run.stats(l).rhs_evals += tab::n_stages_extended - tab::n_stages - 1, counted[l] = true;
                return F;
            }
            State value(int l, double time) {
                const Vector(&c)[7] = coefficients(l);
                const double x = (time - lane(t_of, l)) / lane(h, l);
                State v = State::Zero();
                for (int r = 0; r < 7; ++r) {
                    v += run.state(c[6 - r], l);
                    v *= (r % 2 == 0) ? x : (1.0 - x);
                }
                return State(v + run.state(y, l));
            }
        } dense{compute_stage, h, y, y_new, f_new, k, run, F, t};
        for (int l = 0; l < count; ++l)
            if (accepted[l] && run.inside(l, lane(t, l), lane(t_new, l), lane(h, l), y, y_new, dense)) return false;

        if constexpr (model::system::has_projection<typename Run::System>::value) {
            run.project(y_new);
            run.rhs(t_new, y_new, f_new);
            for (int l = 0; l < count; ++l)
                if (accepted[l]) ++run.stats(l).rhs_evals;
        }
        for (int l = 0; l < count; ++l) {
            if (!accepted[l]) continue;
            lane(t, l) = lane(t_new, l);
            Run::copy_lane(y, y_new, l);
            Run::copy_lane(f, f_new, l);
            run.at_end(l, lane(t, l), y, lane(h_abs, l), options.every_step);
        }
        if constexpr (W == 1) {
            if (stiff && run.active(0)) {
                run.hand_over(lane(t, 0), y, lane(h_abs, 0));
                return true;
            }
        }
        run.fill_done_lanes(t, y, f);
    }
    return false;
}

/// One DOP853 segment of `run` from (t0, y0) to run.t1: outputs, events, dense output and
/// statistics continue those already in run.result (a plain run has one segment, method 'auto'
/// several). With a `monitor`, Hairer's stiffness test runs after every accepted step and the
/// segment stops where the monitor asks for BDF: returns true then, with Result::t_last,
/// y_last, h_next at the hand-over; false when the run ended (at t1, a terminal event, a
/// failure or an interruption, the Result saying which).
template <class System>
bool dop853_segment(const System& system, Recording<System>& run, double t0, const typename System::State& y0,
                    const Options& options, const Control* control, StiffnessMonitor<System>* monitor = nullptr) {
    OneRun<System> one(system, run, monitor);
    try {
        return dop853_steps(one, t0, {y0}, run.t1, options, control);
    } catch (const Interruption&) {  // Ctrl-C in a user's function: stop where the outputs reach
        one.interrupt();
        return false;
    }
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
