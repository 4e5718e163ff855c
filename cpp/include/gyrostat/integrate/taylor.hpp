// Taylor-series integrator for systems whose right-hand side is polynomial, so that the Taylor
// coefficients of the solution follow from a recursion (automatic differentiation) instead of
// stage evaluations. Step size after Jorba & Zou (2005), "A software package for the numerical
// integration of ODEs by means of high-order Taylor methods", §3.2:
//   ρ_m = (1/‖y[m]‖∞)^{1/m}       (absolute mode, rtol·‖y‖∞ ≤ atol, ε = atol),
//   ρ_m = (‖y‖∞/‖y[m]‖∞)^{1/m}    (relative mode, ε = rtol),
//   p = ⌈−½ ln ε⌉ + 6  (a single run: + 8 below ε = 1e-12, single_run_order),
//   h = min(ρ_{p−1}, ρ_p) · δ^{1/p} · exp(−0.7/(p − 1)),   δ = ε/10 (ε ≥ 1e-12; below, smaller:
//                                                           local_error_fraction),
// so that the truncation term (h/ρ)^p ≈ δ·e^{−0.7} per step.
// Why this order: the global error is about (number of steps N) × (local error δ), and
// N ∝ 1/h ∝ δ^{−1/p}; with a cost per step a + b·p² (a: step size, new state, bookkeeping; b·p²:
// the recursion) the cost at equal global error is least near p ≈ ½ ln(1/δ)·(1 + a/(b p²)),
// above Jorba & Zou's p = ⌈−½ ln ε⌉ + 1 with h = ρ/e² (the optimum when the recursion is the whole
// cost). Measured on the torque-free body (bench/taylor_vs_heyoka.py), orders +3 … +8 lie on the
// same work-precision front within the machine's noise; +6 is at its fast end for rtol ≥ 1e-10.
// Why ε/10: heyoka (Jorba & Zou's rule) makes a local error of e^{−2p}·e^{−0.7p/(p−1)} ≈ ε/15 …
// ε/110 (p rounded up) over ~1.7× as many steps; ε/10 over our fewer steps gives the same
// global error as heyoka at tol = rtol within a factor ~2, so rtol means what it says there
// (I = (2, 3, 4), t = 2000, rtol 1e-12: 1.4e-10 here, 8.7e-11 heyoka; it was 9.3e-10 with the
// previous rule, order +3 and local error ε·e^{−0.7}).
// The step is one dependent chain (recursion → step size → new state → next recursion), so its
// latency counts: the step size uses cheap log2/exp2 (fast_log2, fast_exp2) and the change of
// state Estrin's scheme (increment, evaluate_polynomial), and a single run takes a step predicted
// from the previous ones wherever it is within the allowed one, so that the step size's own chain
// is only waited for when the prediction fails (OneTaylorRun::step_size). No step is rejected;
// outputs inside a step evaluate the step's Taylor polynomial.
// Rounding: at tight tolerances (ε < 1e-12) the state is carried with its rounding error
// (y + y_low, advance_compensated): the first-order term c_1 h is added exactly, the rest summed
// smallest first, and a system that can (System::taylor_rate_error, the gyrostat) also gives
// c_1's own rounding and the effect of y_low on it. The error of a long run there is a phase
// error from the drift of the invariants; rounding the state once per step (and Estrin's scheme
// over the whole polynomial, two roundings at the state's size) made it a random walk that
// stalled the error at ~1e-11 … 5e-12 for rtol 1e-13 … 1e-14 on the torque-free body over
// t = 2000 (bench/taylor_vs_heyoka.py; 7.0e-12 at rtol 1e-14). With all of these, and the local
// error ε·local_error_fraction(ε) (below), the median error over 24 rtols in 1e-14 … 1.46e-14
// is 1.4e-13 (7.5e-13 with the compensated sum alone and a local error ε/10), near the floor of
// the remaining roundings (c_2 h² and higher, ~1e-13 there whatever the step rule).
// A system opts in with `max_taylor_order`, `supports_taylor()` and
//   template <int Order> void taylor_coefficients(double t, const State& y, State* c) const;
// (model/system.hpp).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <utility>

#include "gyrostat/integrate/control.hpp"
#include "gyrostat/integrate/events.hpp"
#include "gyrostat/integrate/options.hpp"
#include "gyrostat/integrate/recorder.hpp"
#include "gyrostat/integrate/trajectories.hpp"
#include "gyrostat/numeric/double_double.hpp"

namespace gyrostat::integrate {

namespace taylor_detail {

/// log2 of the mantissa of x's bits (1 + u, u ∈ [0, 1)) by fast_log2's cubic (shared with the
/// SIMD lanes' form, batch.hpp).
inline double log2_of_mantissa(std::uint64_t bits) {
    bits = (bits & 0x000fffffffffffffULL) | 0x3ff0000000000000ULL;
    double mantissa;
    std::memcpy(&mantissa, &bits, sizeof mantissa);
    const double u = mantissa - 1.0;
    return (1.33453924e-03 + 1.41348539 * u) + u * u * (-5.67752150e-01 + 1.53913535e-01 * u);
}

/// 2^f for f ∈ [0, 1) by fast_exp2's cubic.
inline double exp2_of_fraction(double f) {
    return (0.99981196 + 0.69683858 * f) + f * f * (0.22412644 + 0.07901994 * f);
}

/// log2 of a positive x to 1.4e-3 (the exponent's bits plus a cubic fit of log2 on the mantissa in
/// [1, 2), Chebyshev nodes). The step size needs ρ to a few digits only: this error moves h by
/// ≤ 1e-4 (it is divided by the order), while libm's log2 on the step's critical path (recursion →
/// step size → new state → next recursion) would cost more than the rest of the step-size logic.
/// Subnormal x, read as 2^−1023·(1 + mantissa), are overestimated: a smaller step (the safe side).
inline double fast_log2(double x) {
    std::uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    const double exponent = static_cast<double>(static_cast<int>(bits >> 52) - 1023);
    return exponent + log2_of_mantissa(bits);
}

/// 2^y to 1.9e-4 relative (a cubic fit of 2^f on f ∈ [0, 1), scaled by 2^⌊y⌋ in the exponent's
/// bits); +∞ for y ≥ 1023 (NaN for NaN), 0 below −1022.
inline double fast_exp2(double y) {
    if (!(y < 1023.0)) return y + std::numeric_limits<double>::infinity();
    if (y < -1022.0) return 0.0;
    int n = static_cast<int>(y);
    n -= (n > y);  // ⌊y⌋
    const double f = y - n;
    const double fraction = exp2_of_fraction(f);
    const std::uint64_t bits = static_cast<std::uint64_t>(n + 1023) << 52;
    double scale;
    std::memcpy(&scale, &bits, sizeof scale);
    return fraction * scale;
}

/// min(ρ_{p−1}, ρ_p)·safety with ρ_m = (s/c_m)^{1/m}, in base-2 logarithms to ~2e-4 (fast_log2,
/// fast_exp2; multiplications by 1/m, which fold to constants when the order is one).
inline double step_size(double scale, double c_low, double c_high, int order, double safety) {
    constexpr double inf = std::numeric_limits<double>::infinity();
    const double log_scale = fast_log2(scale);
    const double low = c_low == 0.0 ? inf : (log_scale - fast_log2(c_low)) * (1.0 / (order - 1));
    const double high = c_high == 0.0 ? inf : (log_scale - fast_log2(c_high)) * (1.0 / order);
    return safety * fast_exp2(std::min(low, high));
}

/// Σ c_n dtⁿ, n = 0 … Order, by Estrin's scheme: pairs c_{2i} + c_{2i+1} dt, then pairs of those
/// with dt², dt⁴, …: about log2(Order) dependent multiply-adds instead of Horner's Order. The new
/// state is on the critical path from one step's coefficients to the next step's.
template <int Order, class State>
State evaluate_polynomial(const State* c, double dt) {
    constexpr int terms = Order + 1;
    State a[(terms + 1) / 2];
#pragma GCC unroll 32
    for (int i = 0; 2 * i + 1 < terms; ++i) a[i] = c[2 * i] + c[2 * i + 1] * dt;
    if constexpr (terms % 2 == 1) a[terms / 2] = c[terms - 1];
    double x = dt * dt;
#pragma GCC unroll 8
    for (int n = (terms + 1) / 2; n > 1; n = (n + 1) / 2, x *= x) {
#pragma GCC unroll 16
        for (int i = 0; 2 * i + 1 < n; ++i) a[i] = a[2 * i] + a[2 * i + 1] * x;
        if (n % 2 == 1) a[n / 2] = a[n - 1];
    }
    return a[0];
}

/// The change of the state over dt, Σ c_n dtⁿ for n = 1 … Order, summed smallest first:
///   c_1 dt + dt²·(c_2 + c_3 dt + … + c_Order dt^{Order−2}),
/// the tail by Estrin's scheme (its rounding is relative to the tail, ≲ (h/ρ)² of the state) and
/// the largest term c_1 dt added last, so that the change carries about one rounding of its own
/// size (Estrin's scheme over c_0 … c_Order rounds twice at the size of the state: c_0 + c_1 dt,
/// then the sum of the pairs).
template <int Order, class State>
State increment(const State* c, double dt) {
    static_assert(Order >= 2, "the Taylor steps have order 2 or more");
    return c[1] * dt + evaluate_polynomial<Order - 2>(c + 2, dt) * (dt * dt);
}

/// s = a + b rounded, and its rounding error e = (a + b) − s exactly (Knuth's two-sum:
/// b' = s − a, e = (a − (s − b')) + (b − b'), exact for any a, b).
template <class State>
State two_sum_error(const State& a, const State& b, const State& s) {
    const State b_virtual = s - a;
    return (a - (s - b_virtual)) + (b - b_virtual);
}

/// y ← y + Σ_{n≥1} c_n dtⁿ + y_low with the rounding error kept in y_low (compensated summation,
/// as heyoka's high_accuracy mode): the first-order term c_1 dt, the largest, is added exactly
/// (its product's and its sum's rounding errors, model::dekker_product_error and two_sum_error, go to the
/// low part), then the rest dt²·(c_2 + c_3 dt + …) with the low parts, whose rounding is relative
/// to that smaller sum, and the final sum's rounding error is the new y_low. Carrying y_low from
/// step to step keeps the state's rounding (half an ulp per step, a random walk of the invariants
/// and so a phase error growing like t·√N) out of long runs; adding c_1 dt exactly takes the
/// largest rounding of the change of state out of that walk too (bench/README.md, "The floor at
/// tight tolerances").
template <int Order, class State>
void advance_compensated(State& y, State& y_low, const State* c, double dt) {
    static_assert(Order >= 2, "the Taylor steps have order 2 or more");
    const State first = c[1] * dt;
    const State rest = evaluate_polynomial<Order - 2>(c + 2, dt) * (dt * dt);
    const State partial = y + first;
    const State low = (two_sum_error(y, first, partial) + model::dekker_product_error(c[1], dt, first)) + y_low;
    const State b = rest + low;
    const State sum = partial + b;
    y_low = two_sum_error(partial, b, sum);
    y = sum;
}

/// The step's Taylor polynomial at dt as the new state is computed from it: compensated (the state
/// carried with its rounding error `low`, advance_compensated), c_0 + (Σ_{n≥1} c_n dtⁿ + low); else
/// Estrin's scheme over the whole polynomial (one chain, shortest). For the outputs inside a step.
template <int Order, class State>
State evaluate_step(const State* c, double dt, bool compensated, const State& low) {
    if (compensated) return c[0] + (increment<Order>(c, dt) + low);
    return evaluate_polynomial<Order>(c, dt);
}

/// The next step predicted from the last two allowed ones (a, before it a_prev; 0: none): a times
/// their ratio (at most 1.25), times 0.97. The allowed step moves by up to ~25 % from one step to
/// the next on the torque-free body (ρ from the last two coefficients); this prediction is within
/// the next allowed step on ~85 % of the steps, for ~5 % more steps than taking the allowed ones
/// (0.90: ~11 % misses and 12 % more steps; 0.99: 16 % and 3 %; the same ratio without the trend:
/// 40 % misses at 0.97).
inline double predicted_step(double allowed, double allowed_before) {
    const double trend = allowed_before > 0.0 ? std::min(allowed / allowed_before, 1.25) : 1.0;
    return 0.97 * allowed * trend;
}

/// An empty statement with a side effect, so that the compiler keeps the branch around it as a
/// branch (not a select or a minimum, which would wait on both operands): see OneTaylorRun::step_size.
inline void keep_branch() {
#if defined(__GNUC__)
    asm volatile("");
#endif
}

/// `condition`, marked as rarely true for the compiler's layout of the branch.
inline bool rarely(bool condition) {
#if defined(__GNUC__)
    return __builtin_expect(condition, 0);
#else
    return condition;
#endif
}

/// Whether a step h from t (not ending the run at t1) is below the resolution of t: 10 to 20 units
/// in the last place of t (no nextafter call on every step).
inline bool below_resolution(double t, double h, double t1) {
    const double min_step =
        10.0 * (std::numeric_limits<double>::epsilon() * std::abs(t) + std::numeric_limits<double>::denorm_min());
    return std::abs(h) < min_step && t + h != t1;
}

/// What a run says when its step falls below the resolution of t.
inline std::string underflow_message(double t, double step) {
    return "step size underflow at t = " + format_number(t, 17) + ": the step needed (" + format_number(step) +
           ") is below the resolution of t.";
}

/// The tolerances (ε = rtol, or atol in absolute mode) below which the state is carried with its
/// rounding error (advance_compensated). From 1e-12 up the truncation error per step (ε/10 ≥ 1e-13,
/// ~450 ulp of a state ~1) outweighs the state's rounding (the error at rtol 1e-12 on free_2000 is
/// the same either way, 1.37e-10 and 1.39e-10), and the compensated sum's bookkeeping (~15 ns, 6 %
/// of a step at order 20, measured with --taylor-profile) buys nothing.
inline constexpr double compensate_below = 1e-12;

/// The orders the step loop is compiled for: the even ones from 6 up. Each order is one
/// instantiation of the recursion, the step, the event locator and the dense output per model and
/// per SIMD form (29 orders were ~60 % of the engine's object code and of its compile time); the
/// work-precision front is flat from +3 to +8 above Jorba & Zou's order (the comment at the top of
/// this file), so rounding +6 up to the next even order (+6 or +7) buys the same speed.
/// The sanitizer builds (CMakeLists.txt: GYROSTAT_SANITIZE) compile every 8th order
/// (GYROSTAT_TAYLOR_ORDER_STEP = 8: 8, 16, 24 and the model's highest): the orders still round up,
/// so every tolerance is met (in fewer, costlier steps), and the stages that look for memory
/// errors, undefined behaviour and races compile ~20 % less (three models' integration at -O0
/// under ASan + UBSan: 55 → 45 s of CPU).
#ifndef GYROSTAT_TAYLOR_ORDER_STEP
#define GYROSTAT_TAYLOR_ORDER_STEP 2
#endif
inline constexpr int order_step = GYROSTAT_TAYLOR_ORDER_STEP;
static_assert(order_step % 2 == 0 && order_step > 0, "GYROSTAT_TAYLOR_ORDER_STEP: a positive even number");
inline constexpr int lowest_order = 6;
/// The compiled order that order p rounds up to (at most `highest`, the model's max_taylor_order).
constexpr int compiled_order(int p, int highest) {
    p = p < lowest_order ? lowest_order : p;
    p += (order_step - p % order_step) % order_step;
    return p < highest ? p : highest;
}

/// The order for a local error target ε (rtol in relative mode, atol in absolute mode):
/// p = ⌈−½ ln ε⌉ + `above` (6: five above Jorba & Zou's, see the comment at the top of this file),
/// rounded up to a compiled order (at most max_order, itself even).
inline int order_for(double eps, int max_order, double above = 6.0) {
    const double p = std::min(std::ceil(-0.5 * std::log(eps)) + above, static_cast<double>(max_order));
    return compiled_order(static_cast<int>(p), max_order);
}

/// A single run's order (OneTaylorRun): order_for's, + 8 instead of + 6 below compensate_below.
/// There a step costs more besides its recursion (the compensated sum and c_1's rounding: the a
/// of a + b·p², which moves the cheapest order up), and fewer steps also mean fewer roundings: on
/// the torque-free body (bench/taylor_vs_heyoka.py) + 8 took 1356 steps where + 6 took 1543 at
/// rtol 1e-13, for an error 3.9e-13 against 4.5e-12 (+ 10: faster at 1e-13, slower at 1e-14).
/// The batch lanes keep + 6, not measured for speed at + 8; on tests/test_batch.py's 64 members
/// at rtol 1e-13 over t = 200 their largest error grew from 5.4e-14 to 3.6e-13 with + 8 (a single
/// run's from 1.9e-13 to 3.4e-13: truncation, at that rtol, in the larger steps).
inline int single_run_order(double eps, int max_order) {
    return order_for(eps, max_order, eps < compensate_below ? 8.0 : 6.0);
}

/// The local truncation error a step aims at, as a fraction of ε: 1/10 from ε = 1e-12 up (see the
/// comment at the top of this file), and 0.1·√(ε/1e-12) below (0.01 at ε = 1e-14). Below 1e-12
/// the state is compensated and its rounding no longer sets the error; ε/10 per step then left
/// the truncation error the larger part (torque-free body, t = 2000, 24 rtols in 1e-14 … 1.46e-14:
/// median error 7.5e-13 with ε/10, 2.3e-13 with ε/100, 1.7e-13 with ε/1000, where the rounding
/// floor is reached), for 11 % more steps at 1e-14.
inline double local_error_fraction(double eps) {
    return eps < compensate_below ? 0.1 * std::sqrt(eps / compensate_below) : 0.1;
}

/// The factor of min(ρ_{p−1}, ρ_p) in the step size: (δ/ε · ε)^{1/p}·e^{−0.7/(p−1)}, for a local
/// truncation error of about δ = local_error_fraction(ε)·ε per step (see the comment at the top
/// of this file).
inline double safety_for(double eps, int order) {
    return std::exp(-0.7 / (order - 1)) * std::exp(std::log(local_error_fraction(eps) * eps) / order);
}

/// The system's projection (back onto |q| = 1, model/system.hpp) of a state carried with its
/// rounding error: the components it moves drop their low part (the projection's change is larger).
template <class System>
void project_compensated(const System& system, typename System::State& y, typename System::State& y_low) {
    if constexpr (model::system::has_projection<System>::value) {
        const typename System::State before = y;
        system.project(y);
        for (int i = 0; i < y.size(); ++i)
            if (y[i] != before[i]) y_low[i] = 0.0;
    } else {
        (void)system, (void)y, (void)y_low;
    }
}

/// One step of fixed order of every running trajectory of `run`: the coefficients, the step
/// size, the checks that end a trajectory before its step, then the run's new state (with the
/// outputs inside the step and the statistics: Run::advance).
template <int Order, class Run>
struct Step {
    static void run(Run& run, typename Run::Value& t, typename Run::Vector& y, double t1, double direction,
                    const Options& options) {
        using Value = typename Run::Value;
        using lanes::lane;
        typename Run::Coefficient c[Order + 1];
        run.template coefficients<Order>(t, y, c);
        const Value h = run.template step_size<Order>(c);
        Value dt = lanes::splat<Value>(0.0);  // the signed step of each trajectory (0 for those that are done)
        for (int l = 0; l < run.count(); ++l) {
            if (!run.active(l)) continue;
            const double tl = lane(t, l);
            if (!run.finite(l, c[Order], h)) {
                run.fail(l, Status::NonFiniteState,
                         "the Taylor coefficients became non-finite (inf/NaN) at t = " + format_number(tl, 17) +
                             ": the solution overflows or leaves the model's domain there",
                         tl, run.state(y, l), 0.0);
                continue;
            }
            const double remaining = std::abs(t1 - tl);
            const double step = std::min({lane(h, l), options.max_step, remaining});
            if (run.too_small(tl, step, remaining, direction)) {
                run.fail(l, Status::StepSizeUnderflow, underflow_message(tl, step), tl, run.state(y, l), 0.0);
                continue;
            }
            lane(dt, l) = direction * step;
        }
        run.template advance<Order>(t, y, c, dt, t1);
    }
};

/// Step<p>::run by order p = 0 … max_taylor_order; only the compiled orders are instantiated (the
/// others, which order_for never returns, share the next compiled one's entry).
template <class Run, int... Orders>
constexpr auto step_table(std::integer_sequence<int, Orders...>) {
    static_assert(Run::max_taylor_order % 2 == 0 && Run::max_taylor_order >= lowest_order,
                  "max_taylor_order must be a compiled order (even, 6 or more)");
    using Fn = decltype(&Step<lowest_order, Run>::run);
    return std::array<Fn, sizeof...(Orders)>{&Step<compiled_order(Orders, Run::max_taylor_order), Run>::run...};
}

}  // namespace taylor_detail

/// The Taylor step loop, for one trajectory (OneTaylorRun below) or the W lanes of a batch
/// (batch.hpp: LaneTaylorRuns) from (t0, y0) to t1. No step is rejected; the run chooses the
/// order and the step size rule (Run::prepare, Run::step_size).
template <class Run>
void taylor_steps(Run& run, double t0, typename Run::Vector y, double t1, const Options& options, const Control* control) {
    using Value = typename Run::Value;
    using lanes::lane;
    static constexpr auto steps =
        taylor_detail::step_table<Run>(std::make_integer_sequence<int, Run::max_taylor_order + 1>{});
    const double direction = t1 >= t0 ? 1.0 : -1.0;
    run.project(y);
    Value t = lanes::splat<Value>(t0);
    run.start(t0, y);
    for (int l = 0; l < run.count(); ++l)
        if (t0 == t1) run.empty_span(l, t0, y);
    Ticker ticker(control, t0, t1);

    while (run.any_active()) {
        if (!run.keep_going(ticker, t, y, lanes::splat<Value>(0.0))) return;
        for (int l = 0; l < run.count(); ++l)
            if (run.active(l) && run.stats(l).steps >= options.max_steps)
                run.fail(l, Status::MaxStepsReached,
                         "max_steps = " + std::to_string(options.max_steps) + " reached at t = " +
                             format_number(lane(t, l)) + " before t1 = " + format_number(t1) + ".",
                         lane(t, l), run.state(y, l), 0.0);
        if (!run.any_active()) break;
        steps[run.prepare(y, options)](run, t, y, t1, direction, options);
        run.fill_done_lanes(t, y);
    }
}

/// One trajectory for taylor_steps: the order follows the tolerance of the step's mode
/// (relative or absolute: it changes only when the mode switches), the step size the cheap
/// log2/exp2 (step_size), the new state Estrin's scheme or, below rtol 1e-12, the compensated
/// sum (advance_compensated); events and dense output.
template <class System>
class OneTaylorRun : public OneTrajectory<System> {
public:
    using typename OneTrajectory<System>::Vector;
    using typename OneTrajectory<System>::State;
    using Coefficient = State;
    static constexpr int max_taylor_order = System::max_taylor_order;

    OneTaylorRun(const System& system, Result& result, const Options& options, double t0, double t1)
        : OneTrajectory<System>(system, result), outputs_(output_times(options, t0, t1)),
          record_(system, result, outputs_.size(), options.only_measured_outputs),
          events_(system, options.events, result),
          t1_(t1),
          direction_(t1 >= t0 ? 1.0 : -1.0), every_step_(options.every_step) {
        result.dense = make_dense<System>(options);
    }

    /// The outputs at t0 and the events' values there.
    void start(double t0, const Vector& y) {
        while (next_ < outputs_.size() && outputs_[next_] == t0) record_.push(t0, y[0]), ++next_;
        events_.start(t0, y[0]);
    }
    void empty_span(int, double t0, const Vector& y) { this->finish(0, t0, y[0], 0.0); }

    /// The order of the next step, from the mode (relative: rtol·‖y‖∞ > atol) at y.
    int prepare(const Vector& y, const Options& options) {
        norm_ = y[0].cwiseAbs().maxCoeff();
        const bool relative = options.rtol * norm_ > options.atol;
        const double eps = std::max(relative ? options.rtol : options.atol, 1e-300);
        if (eps != eps_of_order_) {  // changes only when the mode (absolute/relative) switches
            order_ = taylor_detail::single_run_order(eps, max_taylor_order);
            safety_ = taylor_detail::safety_for(eps, order_);
            eps_of_order_ = eps;
            compensated_ = eps < taylor_detail::compensate_below;
            if (!compensated_) y_low_.setZero();  // (no stale low part if compensation resumes)
        }
        scale_ = relative ? norm_ : 1.0;
        return order_;
    }
    template <int Order>
    void coefficients(double t, const Vector& y, State* c) const {
        this->system_.template taylor_coefficients<Order>(t, y[0], c);
    }
    /// The step: the predicted one (predicted_step_) where it is within the step the coefficients
    /// allow, else the allowed one. Both are known only after the recursion, but the prediction
    /// comes from the previous step: with the comparison a branch (not a minimum), the processor
    /// goes on with the predicted step while the allowed one is computed (two logarithms and an
    /// exponential after the last coefficient: ~20 % of a step's chain at order 20), and only a
    /// wrong prediction waits for it. No step is larger than the rule allows, so the error per step
    /// is as before; the steps are ~5 % more. Not in the compensated mode (ε < compensate_below),
    /// where it was measured to gain nothing (its step is not bound by that chain).
    template <int Order>
    double step_size(const State* c) {
        allowed_ = taylor_detail::step_size(scale_, c[Order - 1].cwiseAbs().maxCoeff(), c[Order].cwiseAbs().maxCoeff(),
                                            Order, safety_);
        double h = predicted_step_;
        if (taylor_detail::rarely(compensated_ || !(predicted_step_ <= allowed_))) {
            taylor_detail::keep_branch();
            h = allowed_;
        }
        predicted_step_ = taylor_detail::predicted_step(allowed_, previous_allowed_);
        previous_allowed_ = allowed_;
        return h;
    }
    bool finite(int, const State& c_last, double) const { return all_finite(c_last) && !std::isnan(allowed_); }
    static bool too_small(double, double, double, double) { return false; }  // (checked after the step: advance)

    /// The new state over dt (events and outputs inside the step from its Taylor polynomial).
    template <int Order>
    void advance(double& t, Vector& yv, const State* c, double dt, double t1) {
        if (!this->active_) return;  // (failed before its step: Step::run)
        State& y = yv[0];
        const State y_before = y;
        const double direction = direction_;
        double t_new = (std::abs(t1 - t) <= std::abs(dt)) ? t1 : t + dt;
        // c[0] = y. Compensated: y + (Σ_{n≥1} c_n dtⁿ + y_low) with the sum's rounding error kept
        // in y_low; else Estrin's scheme over the whole polynomial (one chain, shortest).
        const State low_start = y_low_;
        auto evaluate = [&](double s) -> State {
            return taylor_detail::evaluate_step<Order>(c, s, compensated_, low_start);
        };
        if (compensated_) {
            if constexpr (model::system::has_taylor_rate_error<System>::value)
                y_low_ += this->system_.taylor_rate_error(c[0], y_low_, c[1]) * (t_new - t);
            taylor_detail::advance_compensated<Order>(y, y_low_, c, t_new - t);
        } else {
            y = taylor_detail::evaluate_polynomial<Order>(c, t_new - t);
        }
        const double t_stop = events_.active() ? events_.step(t, t_new, y, [&](double time) { return evaluate(time - t); })
                                               : std::numeric_limits<double>::quiet_NaN();
        const bool terminated = !std::isnan(t_stop);
        if (terminated) t_new = t_stop, y = evaluate(t_new - t), y_low_.setZero();
        if (this->result_.dense && t_new != t) {  // the Taylor polynomial in s = (t' − t)/h: coefficients c_n hⁿ
            const double step = t_new - t;
            State scaled[Order + 1];
            double power = 1.0;
            for (int n = 0; n <= Order; ++n, power *= step) scaled[n] = c[n] * power;
            this->result_.dense->add(t, t_new, t, step, Order, scaled[0].data());
        }
        while (next_ < outputs_.size() &&
               (direction * (outputs_[next_] - t_new) < 0.0 || (terminated && outputs_[next_] == t_new))) {
            record_.push(outputs_[next_], evaluate(outputs_[next_] - t));
            ++next_;
        }
        const double h = t_new - t;
        Stats& stats = this->result_.stats;
        ++stats.rhs_evals;  // one evaluation of the coefficient recursion per step
        if (terminated) {
            model::system::project(this->system_, y);
            ++stats.steps;
            stats.last_step = std::abs(h);
            mark_terminated(this->result_, t_stop);
            this->active_ = false;
            return;
        }
        if (taylor_detail::below_resolution(t, h, t1)) {
            y = y_before;
            this->fail(0, Status::StepSizeUnderflow, taylor_detail::underflow_message(t, std::abs(h)), t, y, 0.0);
            return;
        }
        taylor_detail::project_compensated(this->system_, y, y_low_);
        ++stats.steps;
        stats.last_step = std::abs(h);
        t = (std::abs(t1 - t) <= std::abs(h)) ? t1 : t + h;
        bool recorded = false;
        while (next_ < outputs_.size() && outputs_[next_] == t) record_.push(t, y), ++next_, recorded = true;
        if (every_step_ && !recorded) record_.push(t, y);
        if (direction * (t - t1_) >= 0.0) this->finish(0, t, y, 0.0);  // the Taylor step size follows from (t, y) alone
    }

private:
    std::vector<double> outputs_;
    std::size_t next_ = 0;
    Recorder<System> record_;
    EventLocator<System> events_;
    double t1_, direction_;
    bool every_step_;
    State y_low_ = State::Zero();  // the state's rounding error carried between steps (advance_compensated)
    int order_ = 0;
    double eps_of_order_ = -1.0, safety_ = 0.0, norm_ = 0.0, scale_ = 1.0;
    bool compensated_ = false;
    // the step predicted from the previous ones (step_size; +∞: none yet), the last allowed one
    double predicted_step_ = std::numeric_limits<double>::infinity(), previous_allowed_ = 0.0, allowed_ = 0.0;
};

template <class System>
Result taylor(const System& system, double t0, const typename System::State& y0, double t1, const Options& options,
              const Control* control = nullptr) {
    validate(options, t0, t1);
    require_finite(y0, "initial state y0");
    Result result;
    result.method = method_name(Method::Taylor);
    if constexpr (!model::system::has_taylor<System>::value) {
        (void)system, (void)control;
        throw std::invalid_argument("method 'taylor' needs a model with a polynomial right-hand side that provides "
                                    "Taylor coefficients; use dop853 for this model");
    } else {
        if (!system.supports_taylor())
            throw std::invalid_argument("method 'taylor' covers constant and linear torques only (a quadratic "
                                        "right-hand side); this model has other torques: use dop853");
        OneTaylorRun<System> run(system, result, options, t0, t1);
        taylor_steps(run, t0, {y0}, t1, options, control);
    }
    return result;
}

}  // namespace gyrostat::integrate
