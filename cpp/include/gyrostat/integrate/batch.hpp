// SIMD batches: W members of an ensemble integrated side by side, one per lane of a fixed-size
// Eigen array (lanes.hpp), each lane with its own model parameters, time, step size, outputs,
// statistics and status. Every arithmetic operation of a step (the Taylor recursion, DOP853's
// stages and error estimate, Horner's evaluation) acts on the W lanes at once; the per-lane
// bookkeeping (outputs, failures, the end of the span) is scalar.
//
// A lane follows the same rules as the scalar integrator (taylor.hpp, dop853.hpp): the same step
// size formula, controller and error norm, per lane. Results agree with the scalar path to the
// tolerance, not bit for bit: the batch's right-hand side is the affine form of Euler's equations
// (model/gyrostat.hpp: affine_euler_rhs), the batch Taylor method keeps the order of rtol in
// absolute mode too, and vectorised arithmetic may round differently (exp, log, fused
// multiply-adds). A lane's arithmetic never depends on the other lanes, so a member's result is
// the same, bit for bit, whichever members share its batch (and a member alone runs as a batch
// of one): ensembles and sweeps give the same numbers however they are chunked.
//
// What a batch covers (solve_ensemble falls back to the scalar path for everything else): no
// events, no dense output, no every_step; the gyrostat with constant and linear torques (with and
// without attitude) for taylor and dop853; the averaged symmetric system for dop853 (its
// right-hand side, a sum of each torque's averaged formula, is evaluated lane by lane; the
// stages' arithmetic is vectorised).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "gyrostat/integrate/control.hpp"
#include "gyrostat/integrate/dop853.hpp"
#include "gyrostat/integrate/dop853_tableau.hpp"
#include "gyrostat/integrate/options.hpp"
#include "gyrostat/integrate/recorder.hpp"
#include "gyrostat/integrate/taylor.hpp"
#include "gyrostat/lanes.hpp"
#include "gyrostat/model/averaged.hpp"
#include "gyrostat/model/gyrostat.hpp"

namespace gyrostat::integrate::batch {

using lanes::Lanes;
constexpr int W = lanes::width;

// ------------------------------------------------------------------------------------------------
// Lane models: the right-hand side (and the Taylor recursion) of W members at once.
// A lane model gives
//   using System; static constexpr int dim;          the scalar model and its state size
//   void rhs(const Lanes& t, const Lanes* y, Lanes* dy) const;
//   void project(Lanes* y) const;                    back onto |q| = 1 (or nothing)
// and for the Taylor method
//   static constexpr int max_taylor_order;
//   template <int Order> void taylor(Lanes (*c)[dim]) const;   c[0] given, c[1..Order] computed
// ------------------------------------------------------------------------------------------------

/// The gyrostat with constant and linear torques: Euler's affine equations (model/gyrostat.hpp),
/// each lane with its member's moments, rotor and torques.
template <bool WithAttitude>
struct GyrostatLanes {
    using System = model::Gyrostat<WithAttitude>;
    static constexpr int dim = System::dim;
    static constexpr int max_taylor_order = System::max_taylor_order;
    model::AffineEuler<Lanes> euler;

    /// members[0..W): the lanes' models (lanes past the batch repeat a member).
    explicit GyrostatLanes(const System* const* members) {
        auto gather = [&](auto field) {
            Lanes v;
            for (int l = 0; l < W; ++l) v[l] = field(members[l]->affine_euler());
            return v;
        };
        for (int i = 0; i < 3; ++i) {
            euler.inverse_moments[i] = gather([i](const auto& e) { return e.inverse_moments[i]; });
            euler.differences[i] = gather([i](const auto& e) { return e.differences[i]; });
            euler.rotor[i] = gather([i](const auto& e) { return e.rotor[i]; });
            euler.constant[i] = gather([i](const auto& e) { return e.constant[i]; });
        }
        for (int i = 0; i < 9; ++i) euler.damping[i] = gather([i](const auto& e) { return e.damping[i]; });
        euler.has_rotor = euler.damped = false;
        for (int l = 0; l < W; ++l) {
            euler.has_rotor = euler.has_rotor || members[l]->affine_euler().has_rotor;
            euler.damped = euler.damped || members[l]->affine_euler().damped;
        }
    }
    void rhs(const Lanes& /*t*/, const Lanes* y, Lanes* dy) const { model::affine_euler_rhs<WithAttitude>(euler, y, dy); }
    template <int Order>
    void taylor(Lanes (*c)[dim]) const {
        model::euler_taylor_recursion<Order, WithAttitude>(euler, [c](int n, int i) -> Lanes& { return c[n][i]; });
    }
    void project(Lanes* y) const {
        if constexpr (WithAttitude) {
            const Lanes norm = (y[3].square() + y[4].square() + y[5].square() + y[6].square()).sqrt();
            for (int i = 3; i < 7; ++i) y[i] /= norm;
        }
    }
};

/// The averaged symmetric system (a, r): its right-hand side lane by lane (each member's torques
/// are a list of formulas, model/averaged.hpp), the rest of DOP853 vectorised.
struct AveragedLanes {
    using System = model::AveragedSymmetric;
    static constexpr int dim = System::dim;
    const System* members[W];

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

/// The lane model of a scalar model, where one exists.
template <class System>
struct LanesOf;
template <bool A>
struct LanesOf<model::Gyrostat<A>> {
    using type = GyrostatLanes<A>;
};
template <>
struct LanesOf<model::AveragedSymmetric> {
    using type = AveragedLanes;
};

/// Whether the lanes fill a register wider than SSE2's (an AVX or AVX-512 build: lanes.hpp).
#if defined(__AVX__)
inline constexpr bool WithWideLanes = true;
#else
inline constexpr bool WithWideLanes = false;
#endif

/// Whether a batch integrates `system` with `options` (else the scalar path does).
template <class System>
bool applies(const System& system, const Options& options) {
    if (!options.events.empty() || options.dense_output || options.every_step) return false;
    if constexpr (std::is_same_v<System, model::AveragedSymmetric>) {
        (void)system;
        return options.method == Method::Dop853;
    } else if constexpr (std::is_same_v<System, model::Gyrostat<false>> || std::is_same_v<System, model::Gyrostat<true>>) {
        if constexpr (!WithWideLanes && std::is_same_v<System, model::Gyrostat<false>>) {
            // The portable build's 4 lanes in SSE2 pairs lose to one body at a time where the
            // scalar Taylor recursion runs in AVX2 (model/affine_euler_avx2.hpp): ω alone, 512
            // torque-free members, t = 200, 1 thread: 10.8 against 14.9 ms at rtol 1e-8, 14.9
            // against 25.2 ms at 1e-12 (with the attitude the batch still wins: 31 against 42 ms).
            if (options.method == Method::Taylor && model::affine_euler_avx2_available()) return false;
        }
        return (options.method == Method::Taylor || options.method == Method::Dop853) && system.supports_taylor();
    } else {
        (void)system;
        return false;
    }
}

// ------------------------------------------------------------------------------------------------
// Per-lane bookkeeping shared by both integrators.
// ------------------------------------------------------------------------------------------------

template <class LaneModel>
class LaneRecords {
public:
    using System = typename LaneModel::System;
    using State = typename System::State;
    static constexpr int dim = LaneModel::dim;

    LaneRecords(const System* const* systems, int count, Result* results, const Options& options, double t0, double t1)
        : systems_(systems), count_(count), results_(results), outputs_(output_times(options, t0, t1)),
          direction_(t1 >= t0 ? 1.0 : -1.0), t1_(t1) {
        for (int l = 0; l < count; ++l) {
            results[l] = Result{};
            results[l].method = method_name(options.method);
            results[l].methods_used = {results[l].method};
            records_[l] = std::make_unique<Recorder<System>>(*systems[l], results[l], outputs_.size());
            active_[l] = true;
        }
    }

    int count() const { return count_; }
    bool active(int l) const { return l < count_ && active_[l]; }
    bool any_active() const {
        for (int l = 0; l < count_; ++l)
            if (active_[l]) return true;
        return false;
    }
    Result& result(int l) { return results_[l]; }
    const System& system(int l) const { return *systems_[l]; }
    Stats& stats(int l) { return results_[l].stats; }

    static State lane_state(const Lanes* y, int l) {
        State s;
        for (int i = 0; i < dim; ++i) s[i] = y[i][l];
        return s;
    }
    /// The lanes' initial states (lanes past `count` repeat the last member).
    void load(const State* y0, Lanes* y) const {
        for (int l = 0; l < W; ++l)
            for (int i = 0; i < dim; ++i) y[i][l] = y0[std::min(l, count_ - 1)][i];
    }
    /// Asks the ticker whether to go on (at the earliest running lane's time); when not, every
    /// running lane ends Interrupted where it is.
    bool keep_going(Ticker& ticker, const Lanes& t, const Lanes* y, const Lanes& h_next) {
        double earliest = std::numeric_limits<double>::infinity();
        for (int l = 0; l < count_; ++l)
            if (active_[l]) earliest = std::min(earliest, direction_ * t[l]);
        if (ticker.keep_going(direction_ * earliest)) return true;
        for (int l = 0; l < count_; ++l)
            if (active_[l]) {
                mark_interrupted(results_[l], t[l]);
                finish(l, t[l], lane_state(y, l), h_next[l]);
            }
        return false;
    }
    /// Lanes that are done take a running lane's values (t and the arrays given), so that no NaN
    /// or overflow lingers in their arithmetic.
    template <class... Arrays>
    void fill_done_lanes(Lanes& t, Arrays*... arrays) const {
        int running = -1;
        for (int l = 0; l < count_ && running < 0; ++l)
            if (active_[l]) running = l;
        if (running < 0) return;
        for (int l = 0; l < W; ++l) {
            if (l < count_ && active_[l]) continue;
            t[l] = t[running];
            for (int i = 0; i < dim; ++i) ((arrays[i][l] = arrays[i][running]), ...);
        }
    }
    /// The outputs at t0.
    void start(double t0, const Lanes* y) {
        for (int l = 0; l < count_; ++l)
            while (next_[l] < outputs_.size() && outputs_[next_[l]] == t0) records_[l]->push(t0, lane_state(y, l)), ++next_[l];
    }
    /// Whether lane l has an output time strictly inside its step to t_new.
    bool output_inside(int l, double t_new) const {
        return next_[l] < outputs_.size() && direction_ * (outputs_[next_[l]] - t_new) < 0.0;
    }
    /// Records lane l's outputs strictly inside its step to t_new from `value(time)`.
    template <class Value>
    void inside(int l, double t_new, Value&& value) {
        while (output_inside(l, t_new)) records_[l]->push(outputs_[next_[l]], value(outputs_[next_[l]])), ++next_[l];
    }
    /// Whether lane l, its step ended at t, records an output there or is done.
    bool output_or_end(int l, double t) const {
        return t == t1_ || (next_[l] < outputs_.size() && outputs_[next_[l]] == t);
    }
    /// Records lane l's outputs at the end of its step; ends the lane with success at t1.
    void at_end(int l, double t, const State& y, double h_next) {
        while (next_[l] < outputs_.size() && outputs_[next_[l]] == t) records_[l]->push(t, y), ++next_[l];
        if (t == t1_) finish(l, t, y, h_next);
    }
    /// Ends lane l where it is (its status and message already set, or success).
    void finish(int l, double t, const State& y, double h_next) {
        keep_last(results_[l], t, y, h_next);
        active_[l] = false;
    }
    void fail(int l, Status status, std::string message, double t, const State& y, double h_next) {
        results_[l].status = status;
        results_[l].message = std::move(message);
        finish(l, t, y, h_next);
    }

private:
    const System* const* systems_;
    int count_;
    Result* results_;
    std::vector<double> outputs_;
    double direction_, t1_;
    std::array<std::unique_ptr<Recorder<System>>, W> records_;
    std::array<std::size_t, W> next_{};
    std::array<bool, W> active_{};
};

/// max_i |y_i| per lane.
template <int dim>
Lanes max_abs(const Lanes* y) {
    Lanes m = y[0].abs();
    for (int i = 1; i < dim; ++i) m = m.max(y[i].abs());
    return m;
}

/// The smallest step that still changes t (10 ulp), per lane.
inline double min_step(double t, double direction) {
    return 10.0 * std::abs(std::nextafter(t, direction * std::numeric_limits<double>::infinity()) - t);
}

// ------------------------------------------------------------------------------------------------
// Taylor
// ------------------------------------------------------------------------------------------------

namespace taylor_lanes {
template <class LaneModel, int Order>
void coefficients(const LaneModel& model, Lanes (*c)[LaneModel::dim]) {
    model.template taylor<(Order < 2 ? 2 : Order)>(c);
}
template <class LaneModel, int... Orders>
constexpr auto table(std::integer_sequence<int, Orders...>) {
    using Fn = void (*)(const LaneModel&, Lanes(*)[LaneModel::dim]);
    return std::array<Fn, sizeof...(Orders)>{&coefficients<LaneModel, Orders>...};
}
}  // namespace taylor_lanes

/// Method 'taylor' for `count` ≤ W members (systems[0..W) padded by repetition) from
/// (t0, y0[l]) to t1; results[0..count) receive the trajectories.
template <class LaneModel>
void taylor(const LaneModel& model, const typename LaneModel::System* const* systems, int count,
            const typename LaneModel::System::State* y0, double t0, double t1, const Options& options,
            const Control* control, Result* results) {
    constexpr int dim = LaneModel::dim;
    constexpr int max_order = LaneModel::max_taylor_order;
    using Records = LaneRecords<LaneModel>;
    using State = typename Records::State;
    static constexpr auto coefficients_of =
        taylor_lanes::table<LaneModel>(std::make_integer_sequence<int, max_order + 1>{});

    Records record(systems, count, results, options, t0, t1);
    const double direction = t1 >= t0 ? 1.0 : -1.0;
    Lanes y[dim];
    record.load(y0, y);
    model.project(y);
    Lanes t = Lanes::Constant(t0);
    record.start(t0, y);
    for (int l = 0; l < count; ++l)
        if (t0 == t1) record.finish(l, t0, Records::lane_state(y, l), 0.0);

    // One order for every lane and every step, from rtol (atol when rtol = 0), so that a lane's
    // arithmetic never depends on its neighbours: a member's result is the same in any batch.
    // A lane in absolute mode (rtol·‖y‖ ≤ atol) sizes its steps for atol at that order.
    const double rtol = options.rtol, atol = std::max(options.atol, 0.0);
    const int order = taylor_detail::order_for(std::max(rtol > 0.0 ? rtol : atol, 1e-300), max_order);
    const double safety_relative = taylor_detail::safety_for(std::max(rtol, 1e-300), order);
    const double safety_absolute = taylor_detail::safety_for(std::max(atol, 1e-300), order);
    constexpr double ln2 = 0.69314718055994530942;
    Ticker ticker(control, t0, t1);
    Lanes c[max_order + 1][dim];

    while (record.any_active()) {
        if (!record.keep_going(ticker, t, y, Lanes::Zero())) return;
        const Lanes norm = max_abs<dim>(y);
        for (int l = 0; l < count; ++l)
            if (record.active(l) && record.stats(l).steps >= options.max_steps)
                record.fail(l, Status::MaxStepsReached,
                            "max_steps = " + std::to_string(options.max_steps) + " reached at t = " + format_number(t[l]) +
                                " before t1 = " + format_number(t1) + ".",
                            t[l], Records::lane_state(y, l), 0.0);
        if (!record.any_active()) break;
        const auto relative = rtol * norm > atol;
        const Lanes log2_scale = relative.select(norm.log() / ln2, Lanes::Zero());
        const Lanes safety = relative.select(Lanes::Constant(safety_relative), Lanes::Constant(safety_absolute));
        for (int i = 0; i < dim; ++i) c[0][i] = y[i];
        coefficients_of[order](model, c);
        // h = safety · min(ρ_{p−1}, ρ_p), ρ_m = (scale / ‖c_m‖)^{1/m} (a zero coefficient: no limit)
        const Lanes low = (log2_scale - max_abs<dim>(c[order - 1]).log() / ln2) / (order - 1);
        const Lanes high = (log2_scale - max_abs<dim>(c[order]).log() / ln2) / order;
        Lanes h = safety * (low.min(high) * ln2).exp();
        Lanes dt;  // the signed step of each lane (0 for lanes that are done)
        for (int l = 0; l < W; ++l) {
            dt[l] = 0.0;
            if (!record.active(l)) continue;
            bool finite = std::isfinite(norm[l]) && !std::isnan(h[l]);
            for (int i = 0; i < dim && finite; ++i) finite = std::isfinite(c[order][i][l]);
            const State here = Records::lane_state(y, l);
            if (!finite) {
                record.fail(l, Status::NonFiniteState,
                           "the Taylor coefficients became non-finite (inf/NaN) at t = " + format_number(t[l], 17) +
                               ": the solution overflows or leaves the model's domain there",
                           t[l], here, 0.0);
                continue;
            }
            const double remaining = std::abs(t1 - t[l]);
            const double step = std::min({h[l], options.max_step, remaining});
            if (step < min_step(t[l], direction) && step != remaining) {
                record.fail(l, Status::StepSizeUnderflow,
                           "step size underflow at t = " + format_number(t[l], 17) + ": the step needed (" +
                               format_number(step) + ") is below the resolution of t.",
                           t[l], here, 0.0);
                continue;
            }
            dt[l] = direction * step;
        }
        // Horner at each lane's own step (dt = 0 leaves a finished lane where it is).
        Lanes y_new[dim];
        for (int i = 0; i < dim; ++i) {
            Lanes v = c[order][i];
            for (int n = order - 1; n >= 0; --n) v = v * dt + c[n][i];
            y_new[i] = v;
        }
        for (int l = 0; l < count; ++l) {
            if (!record.active(l)) continue;
            const double t_new = (std::abs(t1 - t[l]) <= std::abs(dt[l])) ? t1 : t[l] + dt[l];
            record.inside(l, t_new, [&](double time) {
                const double s = time - t[l];
                State v;
                for (int i = 0; i < dim; ++i) {
                    double x = c[order][i][l];
                    for (int n = order - 1; n >= 0; --n) x = x * s + c[n][i][l];
                    v[i] = x;
                }
                return v;
            });
            Stats& stats = record.stats(l);
            ++stats.steps;
            ++stats.rhs_evals;  // one evaluation of the coefficient recursion per step
            stats.last_step = std::abs(dt[l]);
            t[l] = t_new;
        }
        model.project(y_new);
        for (int l = 0; l < W; ++l) {
            if (!record.active(l)) {  // a lane that is done follows an active one (finite values only)
                continue;
            }
            for (int i = 0; i < dim; ++i) y[i][l] = y_new[i][l];
            if (record.output_or_end(l, t[l])) record.at_end(l, t[l], Records::lane_state(y, l), 0.0);
        }
        record.fill_done_lanes(t, y);
    }
}

// ------------------------------------------------------------------------------------------------
// DOP853
// ------------------------------------------------------------------------------------------------

/// Method 'dop853' for `count` ≤ W members, as `taylor` above: each lane with its own step size,
/// accepted or rejected on its own error (dop853.hpp's controller and norm, per lane).
template <class LaneModel>
void dop853(const LaneModel& model, const typename LaneModel::System* const* systems, int count,
            const typename LaneModel::System::State* y0, double t0, double t1, const Options& options,
            const Control* control, Result* results) {
    using namespace dop853_detail;
    namespace tab = dop853_tableau;
    constexpr int dim = LaneModel::dim;
    using Records = LaneRecords<LaneModel>;
    using State = typename Records::State;

    Records record(systems, count, results, options, t0, t1);
    const double direction = t1 >= t0 ? 1.0 : -1.0, span = std::abs(t1 - t0);
    const double rtol = options.rtol, atol = options.atol;
    Lanes y[dim], f[dim];
    record.load(y0, y);
    model.project(y);
    Lanes t = Lanes::Constant(t0);
    record.start(t0, y);
    model.rhs(t, y, f);
    for (int l = 0; l < count; ++l) {
        ++record.stats(l).rhs_evals;
        if (t0 == t1) {
            record.finish(l, t0, Records::lane_state(y, l), 0.0);
            continue;
        }
        bool finite = true;
        for (int i = 0; i < dim; ++i) finite = finite && std::isfinite(f[i][l]);
        if (!finite)
            record.fail(l, Status::NonFiniteState,
                       "the right-hand side is not finite at the initial state (t = " + format_number(t0) + ")", t0,
                       Records::lane_state(y, l), 0.0);
    }
    if (!record.any_active()) return;

    // The weighted value v/scale with 0/0 = 0 (dop853.hpp: weighted).
    auto weighted_square = [](const Lanes& v, const Lanes& scale) -> Lanes {
        return Lanes((v == 0.0).select(Lanes::Zero(), v / scale)).square();
    };

    // Initial step (Hairer's algorithm, as in dop853.hpp), per lane.
    Lanes h_abs = Lanes::Constant(options.first_step);
    if (options.first_step == 0.0) {
        Lanes scale[dim], d0 = Lanes::Zero(), d1 = Lanes::Zero(), d2 = Lanes::Zero();
        for (int i = 0; i < dim; ++i) {
            scale[i] = atol + y[i].abs() * rtol;
            d0 += weighted_square(y[i], scale[i]);
            d1 += weighted_square(f[i], scale[i]);
        }
        d0 = (d0 / dim).sqrt();
        d1 = (d1 / dim).sqrt();
        Lanes h0 = Lanes((d0 < 1e-5 || d1 < 1e-5).select(Lanes::Constant(1e-6), 0.01 * d0 / d1)).min(Lanes::Constant(span));
        Lanes y1[dim], f1[dim];
        for (int i = 0; i < dim; ++i) y1[i] = y[i] + h0 * direction * f[i];
        model.rhs(t + h0 * direction, y1, f1);
        for (int i = 0; i < dim; ++i) d2 += weighted_square(f1[i] - f[i], scale[i]);
        d2 = (d2 / dim).sqrt() / h0;
        for (int l = 0; l < W; ++l) {
            if (l < count) ++record.stats(l).rhs_evals;
            const double h1 = (d1[l] <= 1e-15 && d2[l] <= 1e-15) ? std::max(1e-6, h0[l] * 1e-3)
                                                                  : std::pow(0.01 / std::max(d1[l], d2[l]), 1.0 / 8.0);
            h_abs[l] = std::min({100 * h0[l], h1, span});
            if (!std::isfinite(h_abs[l]) || h_abs[l] <= 0.0) h_abs[l] = std::min(1e-6, span);
        }
    }

    Lanes k[tab::n_stages_extended][dim];
    Lanes y_new[dim], f_new[dim], stage[dim];
    std::array<bool, W> rejected{};
    std::array<int, W> non_finite_trials{};
    Ticker ticker(control, t0, t1);

    while (record.any_active()) {
        if (!record.keep_going(ticker, t, y, h_abs)) return;
        // Each lane's trial step (0 for lanes that are done).
        Lanes h = Lanes::Zero(), t_new = t;
        for (int l = 0; l < count; ++l) {
            if (!record.active(l)) continue;
            const State here = Records::lane_state(y, l);
            Stats& stats = record.stats(l);
            if (stats.steps >= options.max_steps) {
                record.fail(l, Status::MaxStepsReached,
                            "max_steps = " + std::to_string(options.max_steps) + " reached at t = " + format_number(t[l]) +
                                " before t1 = " + format_number(t1) + "." +
                                stiffness_hint(record.system(l), t[l], here, stats.last_step, span),
                            t[l], here, h_abs[l]);
                continue;
            }
            const double smallest = min_step(t[l], direction);
            if (!rejected[l]) h_abs[l] = std::max(std::min(h_abs[l], options.max_step), smallest);
            if (h_abs[l] < smallest || non_finite_trials[l] >= kMaxNonFiniteTrials) {
                if (non_finite_trials[l] > 0)
                    record.fail(l, Status::NonFiniteState,
                               "the state became non-finite (inf/NaN) on every trial step from t = " +
                                   format_number(t[l], 17) + " (|y| = " + format_number(here.norm()) +
                                   "): the solution overflows or leaves the model's domain there",
                               t[l], here, stats.last_step);
                else
                    record.fail(l, Status::StepSizeUnderflow,
                               "step size underflow at t = " + format_number(t[l], 17) + ": the step needed (< " +
                                   format_number(smallest) + ") is below the resolution of t." +
                                   stiffness_hint(record.system(l), t[l], here, stats.last_step, span),
                               t[l], here, stats.last_step);
                continue;
            }
            double end = t[l] + h_abs[l] * direction;
            if (direction * (end - t1) > 0.0) end = t1;
            t_new[l] = end;
            h[l] = end - t[l];
            h_abs[l] = std::abs(h[l]);
        }
        if (!record.any_active()) break;

        // Stage s: k_s = f(t + c_s h, y + h Σ_j a_sj k_j), all lanes at once.
        auto compute_stage = [&](int s) {
            for (int i = 0; i < dim; ++i) {
                Lanes dy = tab::a[s][0] * k[0][i];
                for (int j = 1; j < s; ++j)
                    if (tab::a[s][j] != 0.0) dy += tab::a[s][j] * k[j][i];
                stage[i] = y[i] + h * dy;
            }
            model.rhs(t + tab::c[s] * h, stage, k[s]);
        };
        // The 12 stages and the 8th-order solution, all lanes at once.
        for (int i = 0; i < dim; ++i) k[0][i] = f[i];
        for (int s = 1; s < tab::n_stages; ++s) compute_stage(s);
        for (int i = 0; i < dim; ++i) {
            Lanes incr = tab::b[0] * k[0][i];
            for (int j = 1; j < tab::n_stages; ++j)
                if (tab::b[j] != 0.0) incr += tab::b[j] * k[j][i];
            y_new[i] = y[i] + h * incr;
        }
        model.rhs(t_new, y_new, f_new);
        for (int i = 0; i < dim; ++i) k[tab::n_stages][i] = f_new[i];

        // The error: DOP853's 5th- and 3rd-order estimates combined, per lane.
        Lanes e5 = Lanes::Zero(), e3 = Lanes::Zero();
        for (int i = 0; i < dim; ++i) {
            const Lanes scale = atol + y[i].abs().max(y_new[i].abs()) * rtol;
            Lanes err5 = Lanes::Zero(), err3 = Lanes::Zero();
            for (int j = 0; j <= tab::n_stages; ++j) {
                if (tab::e5[j] != 0.0) err5 += tab::e5[j] * k[j][i];
                if (tab::e3[j] != 0.0) err3 += tab::e3[j] * k[j][i];
            }
            e5 += weighted_square(err5, scale);
            e3 += weighted_square(err3, scale);
        }
        const Lanes error_norm =
            (e5 == 0.0 && e3 == 0.0).select(Lanes::Zero(), h_abs * e5 / ((e5 + 0.01 * e3) * dim).sqrt());

        std::array<bool, W> accepted{};
        bool dense_needed = false;
        for (int l = 0; l < count; ++l) {
            if (!record.active(l)) continue;
            Stats& stats = record.stats(l);
            stats.rhs_evals += tab::n_stages;
            const double err = error_norm[l];
            if (!std::isfinite(err)) {
                ++non_finite_trials[l];
                ++stats.rejected_steps;
                h_abs[l] *= kMinFactor;
                rejected[l] = true;
            } else if (err < 1.0) {
                double factor = err == 0.0 ? kMaxFactor : std::min(kMaxFactor, kSafety * std::pow(err, kErrorExponent));
                if (rejected[l]) factor = std::min(1.0, factor);
                h_abs[l] *= factor;
                accepted[l] = true;
                rejected[l] = false;
                non_finite_trials[l] = 0;
                ++stats.steps;
                stats.last_step = std::abs(h[l]);
                dense_needed = dense_needed || record.output_inside(l, t_new[l]);
            } else {
                h_abs[l] *= std::max(kMinFactor, kSafety * std::pow(err, kErrorExponent));
                ++stats.rejected_steps;
                rejected[l] = true;
            }
        }

        // Outputs inside accepted steps: the 7th-order dense output (its three extra stages for
        // all lanes, when any lane needs them).
        if (dense_needed) {
            for (int s = tab::n_stages + 1; s < tab::n_stages_extended; ++s) compute_stage(s);
            Lanes F[7][dim];
            for (int i = 0; i < dim; ++i) {
                const Lanes delta = y_new[i] - y[i];
                F[0][i] = delta;
                F[1][i] = h * k[0][i] - delta;
                F[2][i] = 2.0 * delta - h * (f_new[i] + k[0][i]);
                for (int r = 0; r < 4; ++r) {
                    Lanes acc = tab::d[r][0] * k[0][i];
                    for (int j = 1; j < tab::n_stages_extended; ++j)
                        if (tab::d[r][j] != 0.0) acc += tab::d[r][j] * k[j][i];
                    F[3 + r][i] = h * acc;
                }
            }
            for (int l = 0; l < count; ++l) {
                if (!accepted[l] || !record.output_inside(l, t_new[l])) continue;
                record.stats(l).rhs_evals += tab::n_stages_extended - tab::n_stages - 1;
                record.inside(l, t_new[l], [&](double time) {
                    const double x = (time - t[l]) / h[l];
                    State value = State::Zero();
                    for (int r = 0; r < 7; ++r) {
                        for (int i = 0; i < dim; ++i) value[i] += F[6 - r][i][l];
                        value *= (r % 2 == 0) ? x : (1.0 - x);
                    }
                    for (int i = 0; i < dim; ++i) value[i] += y[i][l];
                    return value;
                });
            }
        }
        if constexpr (model::system::has_projection<typename LaneModel::System>::value) {
            model.project(y_new);
            model.rhs(t_new, y_new, f_new);
            for (int l = 0; l < count; ++l)
                if (accepted[l]) ++record.stats(l).rhs_evals;
        }
        for (int l = 0; l < count; ++l) {
            if (!accepted[l]) continue;
            t[l] = t_new[l];
            for (int i = 0; i < dim; ++i) y[i][l] = y_new[i][l], f[i][l] = f_new[i][l];
            if (record.output_or_end(l, t[l])) record.at_end(l, t[l], Records::lane_state(y, l), h_abs[l]);
        }
        record.fill_done_lanes(t, y, f);
    }
}

/// Integrates `count` ≤ W members in one batch with options.method (taylor or dop853; see
/// `applies`): results[0..count).
template <class System>
void solve_lanes(const System* const* members, int count, const typename System::State* y0, double t0, double t1,
                 const Options& options, const Control* control, Result* results) {
    const System* padded[W];
    for (int l = 0; l < W; ++l) padded[l] = members[std::min(l, count - 1)];
    using LaneModel = typename LanesOf<System>::type;
    const LaneModel model(padded);
    if constexpr (std::is_same_v<System, model::AveragedSymmetric>) {
        dop853(model, padded, count, y0, t0, t1, options, control, results);
    } else {
        if (options.method == Method::Taylor)
            taylor(model, padded, count, y0, t0, t1, options, control, results);
        else
            dop853(model, padded, count, y0, t0, t1, options, control, results);
    }
}

}  // namespace gyrostat::integrate::batch
