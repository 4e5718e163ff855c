// One entry point for every integrator.
#pragma once

#include "gyrostat/integrate/arkode.hpp"
#include "gyrostat/integrate/cvode.hpp"
#include "gyrostat/integrate/dop853.hpp"
#include "gyrostat/integrate/taylor.hpp"

namespace gyrostat::integrate {

/// Integrates `system` from (t0, y0) to t1 with options.method. Bad options or a non-finite y0
/// throw std::invalid_argument; a failing run returns its partial trajectory and the reason.
template <class System>
Result solve(const System& system, double t0, const typename System::State& y0, double t1, const Options& options) {
    switch (options.method) {
        case Method::Dop853: return dop853(system, t0, y0, t1, options);
        case Method::CvodeBdf: return cvode(system, t0, y0, t1, options, true);
        case Method::CvodeAdams: return cvode(system, t0, y0, t1, options, false);
        case Method::ArkodeVerner6: return arkode_erk(system, t0, y0, t1, options, ARKODE_VERNER_8_5_6, options.method);
        case Method::ArkodeFehlberg8:
            return arkode_erk(system, t0, y0, t1, options, ARKODE_FEHLBERG_13_7_8, options.method);
        case Method::Taylor: return taylor(system, t0, y0, t1, options);
    }
    throw std::invalid_argument("unknown integration method");
}

}  // namespace gyrostat::integrate
