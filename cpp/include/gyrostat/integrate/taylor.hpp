// Taylor-series integrator for systems whose right-hand side is polynomial, so that the Taylor
// coefficients of the solution follow from a recursion (automatic differentiation) instead of
// stage evaluations. Step size after Jorba & Zou (2005), "A software package for the numerical
// integration of ODEs by means of high-order Taylor methods", §3.2:
//   ρ_m = (1/‖y[m]‖∞)^{1/m}       (absolute mode, rtol·‖y‖∞ ≤ atol, ε = atol),
//   ρ_m = (‖y‖∞/‖y[m]‖∞)^{1/m}    (relative mode, ε = rtol),
//   p = ⌈−½ ln ε⌉ + 6,
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
// state Estrin's scheme (increment, evaluate_polynomial). No step is rejected; outputs inside a
// step evaluate the step's Taylor polynomial.
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
#include <utility>

#include "gyrostat/integrate/control.hpp"
#include "gyrostat/integrate/events.hpp"
#include "gyrostat/integrate/options.hpp"
#include "gyrostat/integrate/recorder.hpp"
#include "gyrostat/model/double_double.hpp"

namespace gyrostat::integrate {

namespace taylor_detail {

/// log2 of a positive x to 1.4e-3 (the exponent's bits plus a cubic fit of log2 on the mantissa in
/// [1, 2), Chebyshev nodes). The step size needs ρ to a few digits only: this error moves h by
/// ≤ 1e-4 (it is divided by the order), while libm's log2 on the step's critical path (recursion →
/// step size → new state → next recursion) would cost more than the rest of the step-size logic.
/// Subnormal x, read as 2^−1023·(1 + mantissa), are overestimated: a smaller step (the safe side).
inline double fast_log2(double x) {
    std::uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    const double exponent = static_cast<double>(static_cast<int>(bits >> 52) - 1023);
    bits = (bits & 0x000fffffffffffffULL) | 0x3ff0000000000000ULL;
    double mantissa;
    std::memcpy(&mantissa, &bits, sizeof mantissa);
    const double u = mantissa - 1.0;
    return exponent + ((1.33453924e-03 + 1.41348539 * u) + u * u * (-5.67752150e-01 + 1.53913535e-01 * u));
}

/// 2^y to 1.9e-4 relative (a cubic fit of 2^f on f ∈ [0, 1), scaled by 2^⌊y⌋ in the exponent's
/// bits); +∞ for y ≥ 1023 (NaN for NaN), 0 below −1022.
inline double fast_exp2(double y) {
    if (!(y < 1023.0)) return y + std::numeric_limits<double>::infinity();
    if (y < -1022.0) return 0.0;
    int n = static_cast<int>(y);
    n -= (n > y);  // ⌊y⌋
    const double f = y - n;
    const double fraction = (0.99981196 + 0.69683858 * f) + f * f * (0.22412644 + 0.07901994 * f);
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

/// The tolerances (ε = rtol, or atol in absolute mode) below which the state is carried with its
/// rounding error (advance_compensated). From 1e-12 up the truncation error per step (ε/10 ≥ 1e-13,
/// ~450 ulp of a state ~1) outweighs the state's rounding (the error at rtol 1e-12 on free_2000 is
/// the same either way, 1.37e-10 and 1.39e-10), and the compensated sum's bookkeeping (~15 ns, 6 %
/// of a step at order 20, measured with --taylor-profile) buys nothing.
inline constexpr double compensate_below = 1e-12;

/// The order for a local error target ε (rtol in relative mode, atol in absolute mode):
/// p = ⌈−½ ln ε⌉ + 6, five above Jorba & Zou's (see the comment at the top of this file).
inline int order_for(double eps, int max_order) {
    return std::clamp(static_cast<int>(std::ceil(-0.5 * std::log(eps))) + 6, 2, max_order);
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

/// One step of fixed order: coefficients, step size, events and outputs inside the step, the new
/// state. Returns false when the coefficients are not finite (h then holds NaN); `t_stop` is the
/// time of a terminal event inside the step (NaN when none: the step goes to its end).
template <int Order, class System>
struct Step {
    using State = typename System::State;
    static bool run(const System& system, double t, State& y, State& y_low, bool compensated, double t1,
                    double direction, double scale, double safety, double max_step, double& h,
                    const std::vector<double>& outputs, std::size_t& next, Recorder<System>& record,
                    EventLocator<System>& events, double& t_stop, DenseOutput* dense) {
        State c[Order + 1];
        system.template taylor_coefficients<Order>(t, y, c);
        h = step_size(scale, c[Order - 1].cwiseAbs().maxCoeff(), c[Order].cwiseAbs().maxCoeff(), Order, safety);
        if (!all_finite(c[Order]) || std::isnan(h)) {
            h = std::numeric_limits<double>::quiet_NaN();
            return false;
        }
        h = std::min({h, max_step, std::abs(t1 - t)});
        // c[0] = y. Compensated: y + (Σ_{n≥1} c_n dtⁿ + y_low) with the sum's rounding error kept
        // in y_low; else Estrin's scheme over the whole polynomial (one chain, shortest).
        const State low_start = y_low;
        auto evaluate = [&](double dt) -> State {
            if (compensated) return c[0] + (increment<Order>(c, dt) + low_start);
            return evaluate_polynomial<Order>(c, dt);
        };
        double t_new = (std::abs(t1 - t) <= h) ? t1 : t + direction * h;
        if (compensated) {
            if constexpr (model::system::has_taylor_rate_error<System>::value)
                y_low += system.taylor_rate_error(c[0], y_low, c[1]) * (t_new - t);
            advance_compensated<Order>(y, y_low, c, t_new - t);
        } else {
            y = evaluate_polynomial<Order>(c, t_new - t);
        }
        t_stop = events.active() ? events.step(t, t_new, y, [&](double time) { return evaluate(time - t); })
                                 : std::numeric_limits<double>::quiet_NaN();
        const bool terminated = !std::isnan(t_stop);
        if (terminated) t_new = t_stop, y = evaluate(t_new - t), y_low.setZero();
        if (dense && t_new != t) {  // the Taylor polynomial in s = (t' − t)/h: coefficients c_n hⁿ
            const double step = t_new - t;
            State scaled[Order + 1];
            double power = 1.0;
            for (int n = 0; n <= Order; ++n, power *= step) scaled[n] = c[n] * power;
            dense->add(t, t_new, t, step, Order, scaled[0].data());
        }
        while (next < outputs.size() &&
               (direction * (outputs[next] - t_new) < 0.0 || (terminated && outputs[next] == t_new))) {
            record.push(outputs[next], evaluate(outputs[next] - t));
            ++next;
        }
        h = t_new - t;
        return true;
    }
};

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

template <class System, int... Orders>
constexpr auto step_table(std::integer_sequence<int, Orders...>) {
    using Fn = decltype(&Step<2, System>::run);
    return std::array<Fn, sizeof...(Orders)>{&Step<(Orders < 2 ? 2 : Orders), System>::run...};
}

}  // namespace taylor_detail

template <class System>
Result taylor(const System& system, double t0, const typename System::State& y0, double t1, const Options& options,
              const Control* control = nullptr) {
    using State = typename System::State;
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
        constexpr int max_order = System::max_taylor_order;
        static constexpr auto steps =
            taylor_detail::step_table<System>(std::make_integer_sequence<int, max_order + 1>{});
        const std::vector<double> outputs = output_times(options, t0, t1);
        Recorder<System> record(system, result, outputs.size());
        EventLocator<System> events(system, options.events, result);
        result.dense = make_dense<System>(options);
        std::size_t next = 0;
        const double direction = t1 >= t0 ? 1.0 : -1.0;
        Stats& stats = result.stats;
        double t = t0;
        State y = y0;
        State y_low = State::Zero();  // the state's rounding error carried between steps (advance_compensated)
        model::system::project(system, y);
        while (next < outputs.size() && outputs[next] == t0) record.push(t0, y), ++next;
        events.start(t0, y);
        int order = 0;
        double eps_of_order = -1.0, safety = 0.0;
        bool compensated = false;
        Ticker ticker(control, t0, t1);

        while (direction * (t - t1) < 0.0) {
            if (!ticker.keep_going(t)) {
                mark_interrupted(result, t);
                keep_last(result, t, y, 0.0);
                return result;
            }
            if (stats.steps >= options.max_steps) {
                result.status = Status::MaxStepsReached;
                result.message = "max_steps = " + std::to_string(options.max_steps) + " reached at t = " + format_number(t) +
                                 " before t1 = " + format_number(t1) + ".";
                keep_last(result, t, y, 0.0);
                return result;
            }
            const double norm = y.cwiseAbs().maxCoeff();
            const bool relative = options.rtol * norm > options.atol;
            const double eps = std::max(relative ? options.rtol : options.atol, 1e-300);
            if (eps != eps_of_order) {  // changes only when the mode (absolute/relative) switches
                order = taylor_detail::order_for(eps, max_order);
                safety = taylor_detail::safety_for(eps, order);
                eps_of_order = eps;
                compensated = eps < taylor_detail::compensate_below;
                if (!compensated) y_low.setZero();  // (no stale low part if compensation resumes)
            }
            const double t_before = t;
            const State y_before = y;
            double h = 0.0, t_stop = 0.0;
            if (!steps[order](system, t, y, y_low, compensated, t1, direction, relative ? norm : 1.0, safety, options.max_step, h, outputs,
                              next, record, events, t_stop, result.dense.get())) {
                result.status = Status::NonFiniteState;
                result.message = "the Taylor coefficients became non-finite (inf/NaN) at t = " + format_number(t, 17) +
                                 ": the solution overflows or leaves the model's domain there";
                keep_last(result, t_before, y_before, 0.0);
                return result;
            }
            ++stats.rhs_evals;  // one evaluation of the coefficient recursion per step
            if (!std::isnan(t_stop)) {
                model::system::project(system, y);
                ++stats.steps;
                stats.last_step = std::abs(h);
                mark_terminated(result, t_stop);
                return result;
            }
            // 10 to 20 units in the last place of t (no nextafter call on every step)
            const double min_step = 10.0 * (std::numeric_limits<double>::epsilon() * std::abs(t) +
                                            std::numeric_limits<double>::denorm_min());
            if (std::abs(h) < min_step && t + h != t1) {
                y = y_before;
                result.status = Status::StepSizeUnderflow;
                result.message = "step size underflow at t = " + format_number(t_before, 17) + ": the step needed (" +
                                 format_number(std::abs(h)) + ") is below the resolution of t.";
                keep_last(result, t, y, 0.0);
                return result;
            }
            taylor_detail::project_compensated(system, y, y_low);
            ++stats.steps;
            stats.last_step = std::abs(h);
            t = (std::abs(t1 - t) <= std::abs(h)) ? t1 : t + h;
            bool recorded = false;
            while (next < outputs.size() && outputs[next] == t) record.push(t, y), ++next, recorded = true;
            if (options.every_step && !recorded) record.push(t, y);
        }
        keep_last(result, t, y, 0.0);  // the Taylor step size follows from (t, y) alone
    }
    return result;
}

}  // namespace gyrostat::integrate
