// ARKODE ERKStep with the high-order explicit tables SUNDIALS 6.4 ships: Verner 8-stage 6(5) and
// Fehlberg 13-stage 8(7).
#pragma once

#include <arkode/arkode_erkstep.h>

#include "gyrostat/integrate/sundials_driver.hpp"

namespace gyrostat::integrate {

namespace arkode_detail {

struct ErkDeleter {
    void operator()(void* mem) const { ERKStepFree(&mem); }
};

/// Owns the ERKStep memory (released even when set-up throws).
template <class System>
class ErkStepper {
public:
    // ARKODE's Hermite interpolant (degree <= 5) is of lower order than these tables: step to each
    // output time instead of interpolating, so outputs carry the method's accuracy.
    static constexpr bool exact_outputs = true;

    ErkStepper(ARKODE_ERKTableID table, SUNContext ctx, N_Vector y, double t0, const Options& o,
               sundials::CallbackData<System>& data, sundials::ErrorLog& log)
        : mem_(sundials::created(ERKStepCreate(&sundials::rhs_callback<System>, t0, y, ctx), "ERKStepCreate")) {
        using namespace sundials;
        void* mem = mem_.get();
        check(ERKStepSetErrHandlerFn(mem, &ErrorLog::handler, &log), "ERKStepSetErrHandlerFn");
        check(ERKStepSetTableNum(mem, table), "ERKStepSetTableNum");
        check(ERKStepSStolerances(mem, o.rtol, o.atol), "ERKStepSStolerances");
        check(ERKStepSetUserData(mem, &data), "ERKStepSetUserData");
        check(ERKStepSetMaxHnilWarns(mem, 1), "ERKStepSetMaxHnilWarns");
        check(ERKStepSetMaxNumSteps(mem, -1), "ERKStepSetMaxNumSteps");  // the driver counts steps over the whole run
        if (o.first_step > 0.0) check(ERKStepSetInitStep(mem, o.first_step), "ERKStepSetInitStep");
        if (std::isfinite(o.max_step)) check(ERKStepSetMaxStep(mem, o.max_step), "ERKStepSetMaxStep");
        if constexpr (model::system::has_projection<System>::value)
            check(ERKStepSetPostprocessStepFn(mem, &project_callback<System>), "ERKStepSetPostprocessStepFn");
    }

    int evolve(double tout, N_Vector y, double* t) { return ERKStepEvolve(mem_.get(), tout, y, t, ARK_ONE_STEP); }
    bool suggest_stiff() const { return true; }
    void set_stop_time(double t) { sundials::check(ERKStepSetStopTime(mem_.get(), t), "ERKStepSetStopTime"); }
    void interpolate(double t, N_Vector y) { sundials::check(ERKStepGetDky(mem_.get(), t, 0, y), "ERKStepGetDky"); }
    int derivative(double t, int k, N_Vector d) { return ERKStepGetDky(mem_.get(), t, k, d); }
    int degree() const { return 5; }  // ARKODE's Hermite interpolant has degree ≤ 5; past it GetDky fails

    Stats stats() const {
        void* mem = mem_.get();
        Stats s;
        ERKStepGetNumSteps(mem, &s.steps);
        ERKStepGetNumRhsEvals(mem, &s.rhs_evals);
        ERKStepGetNumErrTestFails(mem, &s.rejected_steps);
        ERKStepGetLastStep(mem, &s.last_step);
        return s;
    }
    static Status classify(int flag) {
        switch (flag) {
            case -1000:
            case ARK_TOO_MUCH_WORK: return Status::MaxStepsReached;
            case ARK_TOO_CLOSE:
            case ARK_ERR_FAILURE:  // error test failed repeatedly or at the smallest step
            case ARK_TOO_MUCH_ACC: return Status::StepSizeUnderflow;
            case ARK_RHSFUNC_FAIL:
            case ARK_FIRST_RHSFUNC_ERR:
            case ARK_REPTD_RHSFUNC_ERR:
            case ARK_UNREC_RHSFUNC_ERR: return Status::NonFiniteState;
            default: return Status::SolverFailure;
        }
    }
    std::string flag_name(int flag) const {
        if (flag == -1000) return "max_steps";
        char* name = ERKStepGetReturnFlagName(flag);
        std::string s = name ? name : "ARK_UNKNOWN";
        free(name);
        return s;
    }

private:
    std::unique_ptr<void, ErkDeleter> mem_;
};

}  // namespace arkode_detail

/// Integrates with ARKODE's explicit Runge–Kutta stepper and the given Butcher table.
template <class System>
Result arkode_erk(const System& system, double t0, const typename System::State& y0, double t1, const Options& options,
                  ARKODE_ERKTableID table, Method method, const Control* control = nullptr) {
    return sundials::run(system, t0, y0, t1, options, method, control,
                         [&](double t, SUNContext ctx, N_Vector y, sundials::CallbackData<System>& data,
                             sundials::ErrorLog& log) {
                             return arkode_detail::ErkStepper<System>(table, ctx, y, t, options, data, log);
                         });
}

}  // namespace gyrostat::integrate
