// One entry point for every integrator, for any System of the model concept (model/system.hpp).
#pragma once

#include "gyrostat/integrate/arkode.hpp"
#include "gyrostat/integrate/cvode.hpp"
#include "gyrostat/integrate/dop853.hpp"
#include "gyrostat/integrate/taylor.hpp"

namespace gyrostat::integrate {

/// A system that needs no integration (model/system.hpp, `flow`): its closed form evaluated at
/// the output times. The method asked for is not used; the Result says "closed_form".
template <class System>
Result closed_form(const System& system, double t0, const typename System::State& y0, double t1, const Options& options) {
    validate(options, t0, t1);
    require_finite(y0, "initial state y0");
    Result result;
    result.method = "closed_form";
    const std::vector<double> outputs = output_times(options, t0, t1);
    Recorder<System> record(system, result, outputs.size());
    const auto exact = system.flow(t0, y0);
    for (double t : outputs) record.push(t, exact.at(t));
    return result;
}

/// Integrates `system` from (t0, y0) to t1 with options.method. Bad options or a non-finite y0
/// throw std::invalid_argument; a failing run returns its partial trajectory and the reason; a
/// run stopped through `control` returns what it computed with status Interrupted.
template <class System>
Result solve(const System& system, double t0, const typename System::State& y0, double t1, const Options& options,
             const Control* control = nullptr) {
    model::system::check_state(system, y0);
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
        }
        throw std::invalid_argument("unknown integration method");
    }
}

}  // namespace gyrostat::integrate
