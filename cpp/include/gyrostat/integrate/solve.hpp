// One entry point for every integrator, for any System of the model concept (model/system.hpp).
#pragma once

#include "gyrostat/integrate/arkode.hpp"
#include "gyrostat/integrate/auto_switch.hpp"
#include "gyrostat/integrate/cvode.hpp"
#include "gyrostat/integrate/dop853.hpp"
#include "gyrostat/integrate/splitting.hpp"
#include "gyrostat/integrate/taylor.hpp"

namespace gyrostat::integrate {

/// A system that needs no integration (model/system.hpp, `flow`): its closed form evaluated at
/// the output times. The method asked for is not used; the Result says "closed_form". Events are
/// located on the flow itself, scanned in pieces of at most the flow's `event_step()` (a fraction
/// of its period) and 1/64 of the span.
template <class System>
Result closed_form(const System& system, double t0, const typename System::State& y0, double t1, const Options& options) {
    validate(options, t0, t1);
    require_finite(y0, "initial state y0");
    Result result;
    result.method = "closed_form";
    const std::vector<double> outputs = output_times(options, t0, t1);
    Recorder<System> record(system, result, outputs.size(), options.only_measured_outputs);
    EventLocator<System> events(system, options.events, result);
    const auto exact = system.flow(t0, y0);
    if (options.dense_output) {
        result.dense = make_dense<System>(options);
        result.dense->set_exact(t0, t1, [exact](double t) { return Eigen::VectorXd(exact.at(t)); });
    }
    double end = t1;
    const double direction = t1 >= t0 ? 1.0 : -1.0;
    if (events.active() && t1 != t0) {
        events.start(t0, exact.at(t0));
        const double piece = std::min(std::abs(t1 - t0) / 64.0, exact.event_step());
        auto at = [&](double time) { return exact.at(time); };
        for (double t = t0; direction * (t - t1) < 0.0;) {
            const double t_next = direction * (t1 - t) <= piece ? t1 : t + direction * piece;
            const double t_stop = events.step(t, t_next, exact.at(t_next), at);
            if (!std::isnan(t_stop)) {
                end = t_stop;
                mark_terminated(result, t_stop);
                break;
            }
            t = t_next;
        }
    }
    for (double t : outputs)
        if (direction * (t - end) <= 0.0) record.push(t, exact.at(t));
    return result;
}

/// Result::t_last / y_last where the integrator did not set them: the crossing of a terminal event,
/// else the last output (a closed form, or a run that ended before its first step), else (t0, y0);
/// the state projected like a recorded one (a unit quaternion).
template <class System>
void complete_last(const System& system, Result& result, double t0, const typename System::State& y0) {
    if (result.terminal_event >= 0 && !result.t_events[result.terminal_event].empty()) {
        const auto& times = result.t_events[result.terminal_event];
        const auto& states = result.y_events[result.terminal_event];
        result.t_last = times.back();
        result.y_last.assign(states.end() - result.dim, states.end());
    } else if (std::isnan(result.t_last)) {
        if (result.t.empty()) {
            keep_last(result, t0, y0, 0.0);
        } else {
            result.t_last = result.t.back();
            result.y_last.assign(result.y.end() - result.dim, result.y.end());
        }
    }
    if (static_cast<int>(result.y_last.size()) == System::dim) {
        typename System::State last = Eigen::Map<const typename System::State>(result.y_last.data());
        model::system::project(system, last);
        result.y_last.assign(last.data(), last.data() + System::dim);
    }
}

/// Integrates `system` from (t0, y0) to t1 with options.method. Bad options or a non-finite y0
/// throw std::invalid_argument; a failing run returns its partial trajectory and the reason; a
/// run stopped through `control` returns what it computed with status Interrupted.
template <class System>
Result solve(const System& system, double t0, const typename System::State& y0, double t1, const Options& options,
             const Control* control = nullptr) {
    model::system::check_state(system, y0);
    Result result = [&]() -> Result {
        if constexpr (model::system::is_closed_form<System>::value) {
            (void)control;
            return closed_form(system, t0, y0, t1, options);
        } else {
            switch (options.method) {
                case Method::Dop853: return dop853(system, t0, y0, t1, options, control);
                case Method::CvodeBdf: return cvode(system, t0, y0, t1, options, true, control);
                case Method::CvodeAdams: return cvode(system, t0, y0, t1, options, false, control);
                case Method::ArkodeVerner6:
                    return arkode_erk(system, t0, y0, t1, options, ARKODE_VERNER_8_5_6, options.method, control);
                case Method::ArkodeFehlberg8:
                    return arkode_erk(system, t0, y0, t1, options, ARKODE_FEHLBERG_13_7_8, options.method, control);
                case Method::Taylor: return taylor(system, t0, y0, t1, options, control);
                case Method::Auto: return auto_switch(system, t0, y0, t1, options, control);
                case Method::Splitting:
                    if constexpr (has_splitting<System>::value)
                        return splitting(system, t0, y0, t1, options, control);
                    else
                        throw std::invalid_argument(
                            "method 'splitting' needs a model that splits into the exact free-body flow and a "
                            "perturbation (the gyrostat Model, the Lagrange top, the orthogonal-torque model); this model (state " +
                            model::system::join_names(System::states) + ") does not");
            }
            throw std::invalid_argument("unknown integration method");
        }
    }();
    complete_last(system, result, t0, y0);
    if (result.methods_used.empty()) result.methods_used.push_back(result.method);
    result.options = recorded(options);
    return result;
}

}  // namespace gyrostat::integrate
