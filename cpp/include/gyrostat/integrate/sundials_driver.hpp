// The output loop shared by the CVODE and ARKODE integrators.
#pragma once

#include "gyrostat/integrate/diagnose.hpp"
#include "gyrostat/integrate/sundials.hpp"

namespace gyrostat::integrate::sundials {

/// A SUNDIALS stepper as the driver sees it (see CvodeStepper, ErkStepper):
///   int evolve(double tout, N_Vector y, double* t, bool one_step);
///   void set_stop_time(double); void set_max_steps(long);
///   void interpolate(double t, N_Vector y);   // dense output inside the last step
///   Stats stats(); Status classify(int flag); std::string flag_name(int flag);
///   static constexpr bool exact_outputs;      // step to each output time instead of interpolating
///   bool suggest_stiff() const;                // non-stiff method: diagnose stiffness on failure
template <class System, class Stepper>
void drive(const System& system, Stepper& stepper, N_Vector y, double t0, double t1, const Options& options,
           CallbackData<System>& data, const ErrorLog& log, Result& result) {
    using State = typename System::State;
    const std::vector<double> outputs = output_times(options, t0, t1);
    Recorder<System> record(system, result, outputs.size());
    const double direction = t1 >= t0 ? 1.0 : -1.0;
    auto state = [&]() { return State(StateMap<System>(N_VGetArrayPointer(y))); };

    std::size_t next = 0;
    while (next < outputs.size() && outputs[next] == t0) record.push(t0, state()), ++next;

    double t = t0;
    int flag = 0;
    stepper.set_stop_time(t1);
    auto finish = [&](int failed_flag) {
        result.stats = stepper.stats();
        result.status = stepper.classify(failed_flag);
        if (data.non_finite && result.status != Status::MaxStepsReached) result.status = Status::NonFiniteState;
        result.message = stepper.flag_name(failed_flag) + " at t = " + format_number(t, 17) + ": ";
        switch (result.status) {
            case Status::MaxStepsReached:
                result.message += "max_steps = " + std::to_string(options.max_steps) + " reached before t1 = " +
                                  format_number(t1) + ".";
                break;
            case Status::NonFiniteState:
                result.message += "the derivative became non-finite (inf/NaN) at t = " + format_number(data.t_non_finite, 17) +
                                  " and stayed so on retries: the solution overflows or leaves the model's domain.";
                break;
            case Status::StepSizeUnderflow:
                result.message += "the step size fell below the resolution of t.";
                break;
            default:
                result.message += "the solver failed.";
        }
        if (!log.last_error.empty()) result.message += " SUNDIALS: " + log.last_error;
        if (log.step_below_resolution && result.status != Status::NonFiniteState) {
            result.status = Status::StepSizeUnderflow;
            result.message += " The step size fell below the resolution of t (SUNDIALS warned 't + h = t').";
        }
        if (stepper.suggest_stiff() &&
            (result.status == Status::MaxStepsReached || result.status == Status::StepSizeUnderflow))
            result.message += stiffness_hint(system, t, state(), result.stats.last_step, std::abs(t1 - t0));
    };
    auto budget_left = [&]() { return options.max_steps - stepper.stats().steps; };

    if (options.every_step) {
        while (direction * (t - t1) < 0.0) {
            if (budget_left() <= 0) return finish(-1000);
            stepper.set_max_steps(budget_left());
            const double t_before = t;
            flag = stepper.evolve(t1, y, &t, true);
            if (flag < 0) return finish(flag);
            if (next < outputs.size() && direction * (outputs[next] - t) < 0.0) {
                Vector tmp(N_VClone(y));
                while (next < outputs.size() && direction * (outputs[next] - t) < 0.0) {
                    if (direction * (outputs[next] - t_before) > 0.0) {
                        stepper.interpolate(outputs[next], tmp.get());
                        record.push(outputs[next], State(StateMap<System>(N_VGetArrayPointer(tmp.get()))));
                    }
                    ++next;
                }
            }
            const State y_now = state();
            bool recorded = false;
            while (next < outputs.size() && outputs[next] == t) record.push(t, y_now), ++next, recorded = true;
            if (!recorded) record.push(t, y_now);
        }
    } else {
        for (; next < outputs.size(); ++next) {
            const double tout = outputs[next];
            if (budget_left() <= 0) return finish(-1000);
            stepper.set_max_steps(budget_left());
            if constexpr (Stepper::exact_outputs) stepper.set_stop_time(tout);
            flag = stepper.evolve(tout, y, &t, false);
            if (flag < 0) return finish(flag);
            record.push(tout, state());
        }
    }
    result.stats = stepper.stats();
}

}  // namespace gyrostat::integrate::sundials
