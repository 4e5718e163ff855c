// ARKODE ERKStep with the high-order explicit tables SUNDIALS 6.4 ships: Verner 8-stage 6(5) and
// Fehlberg 13-stage 8(7).
#pragma once

#include <arkode/arkode_erkstep.h>

#include "gyrostat/integrate/sundials_driver.hpp"

namespace gyrostat::integrate {

namespace arkode_detail {

template <class System>
class ErkStepper {
public:
    // ARKODE's Hermite interpolant (degree <= 5) is of lower order than these tables: step to each
    // output time instead of interpolating, so outputs carry the method's accuracy.
    static constexpr bool exact_outputs = true;

    ErkStepper(ARKODE_ERKTableID table, const sundials::Context& ctx, N_Vector y, double t0, const Options& o,
               sundials::CallbackData<System>& data, sundials::ErrorLog& log) {
        using namespace sundials;
        mem_ = ERKStepCreate(&rhs_callback<System>, t0, y, ctx);
        if (mem_ == nullptr) throw std::runtime_error("ERKStepCreate failed");
        check(ERKStepSetErrHandlerFn(mem_, &ErrorLog::handler, &log), "ERKStepSetErrHandlerFn");
        check(ERKStepSetTableNum(mem_, table), "ERKStepSetTableNum");
        check(ERKStepSStolerances(mem_, o.rtol, o.atol), "ERKStepSStolerances");
        check(ERKStepSetUserData(mem_, &data), "ERKStepSetUserData");
        check(ERKStepSetMaxHnilWarns(mem_, 1), "ERKStepSetMaxHnilWarns");
        if (o.first_step > 0.0) check(ERKStepSetInitStep(mem_, o.first_step), "ERKStepSetInitStep");
        if (std::isfinite(o.max_step)) check(ERKStepSetMaxStep(mem_, o.max_step), "ERKStepSetMaxStep");
        if constexpr (System::has_projection)
            check(ERKStepSetPostprocessStepFn(mem_, &project_callback<System>), "ERKStepSetPostprocessStepFn");
    }
    ~ErkStepper() { ERKStepFree(&mem_); }
    ErkStepper(const ErkStepper&) = delete;
    ErkStepper& operator=(const ErkStepper&) = delete;

    int evolve(double tout, N_Vector y, double* t, bool one_step) {
        return ERKStepEvolve(mem_, tout, y, t, one_step ? ARK_ONE_STEP : ARK_NORMAL);
    }
    bool suggest_stiff() const { return true; }
    void set_stop_time(double t) { sundials::check(ERKStepSetStopTime(mem_, t), "ERKStepSetStopTime"); }
    void set_max_steps(long n) { sundials::check(ERKStepSetMaxNumSteps(mem_, n), "ERKStepSetMaxNumSteps"); }
    void interpolate(double t, N_Vector y) { sundials::check(ERKStepGetDky(mem_, t, 0, y), "ERKStepGetDky"); }

    Stats stats() const {
        Stats s;
        ERKStepGetNumSteps(mem_, &s.steps);
        ERKStepGetNumRhsEvals(mem_, &s.rhs_evals);
        ERKStepGetNumErrTestFails(mem_, &s.rejected_steps);
        ERKStepGetLastStep(mem_, &s.last_step);
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
    void* mem_ = nullptr;
};

}  // namespace arkode_detail

/// Integrates with ARKODE's explicit Runge–Kutta stepper and the given Butcher table.
template <class System>
Result arkode_erk(const System& system, double t0, const typename System::State& y0, double t1, const Options& options,
                  ARKODE_ERKTableID table, Method method) {
    validate(options, t0, t1);
    require_finite(y0, "initial state y0");
    Result result;
    result.method = method_name(method);
    sundials::Context ctx;
    sundials::Vector y = sundials::make_vector(System::dim, ctx);
    typename System::State start = y0;
    system.project(start);
    Eigen::Map<typename System::State>(N_VGetArrayPointer(y.get())) = start;
    sundials::CallbackData<System> data{&system};
    sundials::ErrorLog log;
    if (t0 == t1) {  // nothing to integrate: every output time is t0
        Recorder<System> record(system, result, 1);
        for (double t : output_times(options, t0, t1)) record.push(t, start);
        return result;
    }
    arkode_detail::ErkStepper<System> stepper(table, ctx, y.get(), t0, options, data, log);
    sundials::drive(system, stepper, y.get(), t0, t1, options, data, log, result);
    return result;
}

}  // namespace gyrostat::integrate
