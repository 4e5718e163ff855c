// Taylor-series integrator for systems whose right-hand side is polynomial, so that the Taylor
// coefficients of the solution follow from a recursion (automatic differentiation) instead of
// stage evaluations. Step size after Jorba & Zou (2005), "A software package for the numerical
// integration of ODEs by means of high-order Taylor methods", §3.2:
//   ρ_m = (1/‖y[m]‖∞)^{1/m}       (absolute mode, rtol·‖y‖∞ ≤ atol, ε = atol),
//   ρ_m = (‖y‖∞/‖y[m]‖∞)^{1/m}    (relative mode, ε = rtol),
//   h = min(ρ_{p−1}, ρ_p) · ε^{1/p} · exp(−0.7/(p − 1)),
// so that the truncation term (h/ρ)^p ≈ ε·e^{−0.7} per step. Jorba & Zou (and heyoka) take
// p = ⌈−½ ln ε⌉ + 1 and h = ρ/e², a local error of about e^{−2p} ≪ ε; here the order is two
// higher, p = ⌈−½ ln ε⌉ + 3, with the step for a local error of ε: fewer, larger steps, whose
// fixed cost per step (step-size logic, Horner evaluation) weighs more than the O(p²) recursion
// for small systems. Measured on the torque-free body: 40 % fewer steps, the same work-precision
// front shifted by about −25 % in time (bench/README.md).
// No step is rejected; outputs inside a step evaluate the Taylor polynomial (Horner).
// A system opts in with `max_taylor_order`, `supports_taylor()` and
//   template <int Order> void taylor_coefficients(double t, const State& y, State* c) const;
// (model/system.hpp).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "gyrostat/integrate/control.hpp"
#include "gyrostat/integrate/events.hpp"
#include "gyrostat/integrate/options.hpp"
#include "gyrostat/integrate/recorder.hpp"

namespace gyrostat::integrate {

namespace taylor_detail {

/// min(ρ_{p−1}, ρ_p)·safety with ρ_m = (s/c_m)^{1/m}, in base-2 logarithms (log2 and exp2 are
/// several times cheaper than pow, which otherwise dominates a step of a small system).
inline double step_size(double scale, double c_low, double c_high, int order, double safety) {
    constexpr double inf = std::numeric_limits<double>::infinity();
    const double log_scale = std::log2(scale);
    const double low = c_low == 0.0 ? inf : (log_scale - std::log2(c_low)) / (order - 1);
    const double high = c_high == 0.0 ? inf : (log_scale - std::log2(c_high)) / order;
    return safety * std::exp2(std::min(low, high));
}

/// The order for a local error target ε (the rule in the comment at the top), within [2, max].
inline int order_for(double eps, int max_order) {
    return std::clamp(static_cast<int>(std::ceil(-0.5 * std::log(eps))) + 3, 2, max_order);
}
/// The factor ε^{1/p}·exp(−0.7/(p − 1)) that multiplies min(ρ_{p−1}, ρ_p).
inline double safety_for(double eps, int order) { return std::exp(-0.7 / (order - 1)) * std::exp(std::log(eps) / order); }

/// One step of fixed order: coefficients, step size, events and outputs inside the step, the new
/// state. Returns false when the coefficients are not finite (h then holds NaN); `t_stop` is the
/// time of a terminal event inside the step (NaN when none: the step goes to its end).
template <int Order, class System>
struct Step {
    using State = typename System::State;
    static bool run(const System& system, double t, State& y, double t1, double direction, double scale,
                    double safety, double max_step, double& h, const std::vector<double>& outputs, std::size_t& next,
                    Recorder<System>& record, EventLocator<System>& events, double& t_stop, DenseOutput* dense) {
        State c[Order + 1];
        system.template taylor_coefficients<Order>(t, y, c);
        h = step_size(scale, c[Order - 1].cwiseAbs().maxCoeff(), c[Order].cwiseAbs().maxCoeff(), Order, safety);
        if (!all_finite(c[Order]) || std::isnan(h)) {
            h = std::numeric_limits<double>::quiet_NaN();
            return false;
        }
        h = std::min({h, max_step, std::abs(t1 - t)});
        auto evaluate = [&](double dt) {
            State value = c[Order];
#pragma GCC unroll 32
            for (int n = Order - 1; n >= 0; --n) value = value * dt + c[n];
            return value;
        };
        double t_new = (std::abs(t1 - t) <= h) ? t1 : t + direction * h;
        State y_new = evaluate(t_new - t);
        t_stop = events.active() ? events.step(t, t_new, y_new, [&](double time) { return evaluate(time - t); })
                                 : std::numeric_limits<double>::quiet_NaN();
        const bool terminated = !std::isnan(t_stop);
        if (terminated) t_new = t_stop, y_new = evaluate(t_new - t);
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
        y = y_new;
        h = t_new - t;
        return true;
    }
};

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
        model::system::project(system, y);
        while (next < outputs.size() && outputs[next] == t0) record.push(t0, y), ++next;
        events.start(t0, y);
        int order = 0;
        double eps_of_order = -1.0, safety = 0.0;
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
            }
            const double t_before = t;
            const State y_before = y;
            double h = 0.0, t_stop = 0.0;
            if (!steps[order](system, t, y, t1, direction, relative ? norm : 1.0, safety, options.max_step, h, outputs,
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
            const double min_step = 10.0 * std::abs(std::nextafter(t, direction * std::numeric_limits<double>::infinity()) - t);
            if (std::abs(h) < min_step && t + h != t1) {
                y = y_before;
                result.status = Status::StepSizeUnderflow;
                result.message = "step size underflow at t = " + format_number(t_before, 17) + ": the step needed (" +
                                 format_number(std::abs(h)) + ") is below the resolution of t.";
                keep_last(result, t, y, 0.0);
                return result;
            }
            model::system::project(system, y);
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
