// Method 'auto': the integrator chosen by the problem's stiffness, measured along the run, and
// changed when the stiffness changes (as LSODA does between Adams and BDF).
#pragma once

#include <algorithm>

#include "gyrostat/integrate/cvode.hpp"
#include "gyrostat/integrate/dop853.hpp"

namespace gyrostat::integrate {

/// Integrates `system` from (t0, y0) to t1 in segments, each carried by one integrator:
///   1. DOP853 (the non-stiff path: cheap steps, 8th order) from t0, with Hairer's stiffness
///      test after every accepted step, confirmed by the Jacobian's dominant eigenvalue;
///   2. when DOP853's step is held at its stability boundary, CVODE BDF from DOP853's last
///      accepted state, the dominant eigenvalue checked every 50 BDF steps;
///   3. when BDF's step times that eigenvalue falls well inside DOP853's stability region,
///      DOP853 again from BDF's last state; and so on.
/// The thresholds and their reasons are in stiffness.hpp (StiffnessMonitor). The segments share
/// one Recording: every output time is recorded once and in order, an event crossing at or near
/// a switch is located once (the event values and terminal counts carry over), the dense output
/// covers the span, the statistics are summed (the eigenvalue checks counted as Jacobian
/// evaluations) and max_steps counts the steps of all segments. Result::switches lists each
/// switch (time, method, the measured h·|λ|); Result::methods_used the integrators that took
/// part; a failure's message names the segment's method. Each new segment picks its own first
/// step (options.first_step applies to the first).
template <class System>
Result auto_switch(const System& system, double t0, const typename System::State& y0, double t1, const Options& options,
                   const Control* control = nullptr) {
    using State = typename System::State;
    validate(options, t0, t1);
    require_finite(y0, "initial state y0");
    Result result;
    result.method = method_name(Method::Auto);
    Recording<System> run(system, options, t0, t1, result);
    State y = y0;
    model::system::project(system, y);
    run.start(y);

    StiffnessMonitor<System> monitor(system, t1);
    Options later = options;
    later.first_step = 0.0;
    Method method = Method::Dop853;
    double t = t0;
    result.methods_used.push_back(method_name(method));
    for (;;) {
        const Options& o = result.switches.empty() ? options : later;
        const bool handed_over =
            method == Method::CvodeBdf ? sundials::segment(system, run, t, y, o, control, cvode_maker<System>(true, o), &monitor)
                                       : dop853_segment(system, run, t, y, o, control, &monitor);
        if (!handed_over) break;
        t = result.t_last;
        y = Eigen::Map<const State>(result.y_last.data());
        method = method == Method::CvodeBdf ? Method::Dop853 : Method::CvodeBdf;
        const std::string to = method_name(method);
        result.switches.push_back({t, to, monitor.reason()});
        if (std::find(result.methods_used.begin(), result.methods_used.end(), to) == result.methods_used.end())
            result.methods_used.push_back(to);
    }
    result.stats.jacobian_evals += monitor.evaluations();
    if (!result.success() && result.status != Status::Interrupted)
        result.message = "method 'auto', " + std::string(method_name(method)) + " segment from t = " + format_number(t, 17) +
                         ": " + result.message;
    return result;
}

}  // namespace gyrostat::integrate
