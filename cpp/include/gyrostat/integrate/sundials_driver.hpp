// What CVODE and ARKODE runs share: the set-up of a run (checks, context, state vector), and the
// loop that steps, records the outputs and reports failures.
#pragma once

#include <optional>

#include "gyrostat/integrate/control.hpp"
#include "gyrostat/integrate/diagnose.hpp"
#include "gyrostat/integrate/recording.hpp"
#include "gyrostat/integrate/stiffness.hpp"
#include "gyrostat/integrate/sundials.hpp"

namespace gyrostat::integrate::sundials {

/// A SUNDIALS stepper as the driver sees it (see CvodeStepper, ErkStepper):
///   int evolve(double tout, N_Vector y, double* t);   // one step (ONE_STEP mode)
///   void set_stop_time(double);
///   void interpolate(double t, N_Vector y);           // dense output inside the last step
///   int derivative(double t, int k, N_Vector d);      // its k-th derivative (a flag < 0 past its degree)
///   int degree() const;                               // the degree of the last step's interpolant
///   Stats stats(); Status classify(int flag); std::string flag_name(int flag);
///   static constexpr bool exact_outputs;              // step to each output time instead of interpolating
///   bool suggest_stiff() const;                       // non-stiff method: diagnose stiffness on failure
///
/// The driver always takes one step per call, so that it can record every step on request and
/// be stopped between two steps; the step sequence is the one CVODE/ARKODE take in NORMAL mode
/// towards t1 (with the stop time at t1, or at each output for exact_outputs).
///
/// One segment of `run` from t0 (the stepper initialised there with y) to run.t1: outputs,
/// events, dense output and statistics continue those already in run.result, and max_steps
/// counts the steps of every segment. With a `monitor`, the segment stops where the monitor
/// asks for the explicit method (method 'auto'): returns true then, with Result::t_last,
/// y_last, h_next at the hand-over; false when the run ended (the Result says how).
template <class System, class Stepper>
bool drive(const System& system, Stepper& stepper, N_Vector y, double t0, Recording<System>& run, const Options& options,
           const CallbackData<System>& data, const ErrorLog& log, const Control* control,
           StiffnessMonitor<System>* monitor = nullptr) {
    using State = typename System::State;
    Result& result = run.result;
    OutputCursor<System>& cursor = run.cursor;
    const double t1 = run.t1, direction = run.direction;
    const Stats before = result.stats;  // of the earlier segments
    auto state = [&]() { return State(StateMap<System>(N_VGetArrayPointer(y))); };
    auto stats = [&]() { return before + stepper.stats(); };

    double t = t0;
    long steps = 0;
    auto finish = [&](int failed_flag) {
        result.stats = stats();
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
        keep_last(result, t, state(), result.stats.last_step);
        return false;
    };
    auto stop_time = [&]() { return Stepper::exact_outputs && cursor.pending() ? cursor.next_time() : t1; };

    // An implicit stepper (CVODE BDF) is watched for stepping over oscillations (stiffness.hpp).
    std::optional<OscillationWatch<System>> oscillations;
    if (!stepper.suggest_stiff()) oscillations.emplace(system);
    double stop = stop_time();
    stepper.set_stop_time(stop);
    Vector interpolated(N_VClone(y));
    Ticker ticker(control, run.t0, t1);
    // Stopped (Ctrl-C, or a user's function that saw it): the outputs up to the last step kept,
    // and where that step ended (a step that failed on the exception may leave y as a stage's).
    double t_done = t;
    State y_done = state();
    auto interrupted = [&]() {
        result.stats = stats();
        mark_interrupted(result, t_done);
        keep_last(result, t_done, y_done, result.stats.last_step);
        return false;
    };
    try {
        while (direction * (t - t1) < 0.0) {
            if (!ticker.keep_going(t)) return interrupted();
            if (before.steps + steps >= options.max_steps) return finish(-1000);
            const double t_before = t;
            // tout matters on the first call only (the initial step is sized against it): the first output
            const int flag = stepper.evolve(cursor.pending() ? cursor.next_time() : t1, y, &t);
            if (flag < 0 && data.error) std::rethrow_exception(data.error);  // as thrown (an Interruption: below)
            if (flag < 0) return finish(flag);
            ++steps;
            auto dense = [&](double time) {
                stepper.interpolate(time, interpolated.get());
                return State(StateMap<System>(N_VGetArrayPointer(interpolated.get())));
            };
            const double t_stop = run.events.step(t_before, t, state(), dense);
            if (result.dense && t != t_before) {  // y(t') = Σ y⁽ᵏ⁾(t) (t' − t)ᵏ/k!, in s = (t' − t)/h
                const double h = t - t_before;
                std::vector<double> coefficients;
                const int degree = step_polynomial(
                    [&](int k) {
                        return stepper.derivative(t, k, interpolated.get()) < 0 ? nullptr
                                                                                 : N_VGetArrayPointer(interpolated.get());
                    },
                    stepper.degree(), h, System::dim, coefficients);
                result.dense->add(t_before, std::isnan(t_stop) ? t : t_stop, t, h, degree, coefficients.data());
            }
            if (cursor.inside(t, t_stop, dense)) {  // a terminal event inside the step: outputs up to it, then stop
                result.stats = stats();
                mark_terminated(result, t_stop);
                return false;
            }
            cursor.at_end(t, state(), options.every_step);
            t_done = t, y_done = state();
            if (oscillations) oscillations->after_step(t, state(), std::abs(t - t_before), !(direction * (t - t1) < 0.0), result);
            if (monitor && direction * (t - t1) < 0.0 && monitor->implicit_step(t, state(), stepper.stats().last_step)) {
                result.stats = stats();
                keep_last(result, t, state(), result.stats.last_step);
                return true;
            }
            if (stop != stop_time() && direction * (t - t1) < 0.0) stepper.set_stop_time(stop = stop_time());
        }
    } catch (const Interruption&) {  // thrown in a right-hand side, a Jacobian or a check after a step
        return interrupted();
    }
    result.stats = stats();
    keep_last(result, t, state(), result.stats.last_step);
    return false;
}

/// A segment of `run` with a CVODE or ARKODE stepper from (t0, y0): sets up the context and the
/// state vector, makes the stepper with `make(t0, context, y, data, log)` and drives it (see drive).
template <class System, class MakeStepper>
bool segment(const System& system, Recording<System>& run, double t0, const typename System::State& y0,
             const Options& options, const Control* control, MakeStepper&& make,
             StiffnessMonitor<System>* monitor = nullptr) {
    Context context;
    Vector y = make_vector(System::dim, context);
    typename System::State start = y0;
    model::system::project(system, start);
    Eigen::Map<typename System::State>(N_VGetArrayPointer(y.get())) = start;
    CallbackData<System> data;
    data.system = &system;
    ErrorLog log;
    auto stepper = make(t0, context, y.get(), data, log);
    return drive(system, stepper, y.get(), t0, run, options, data, log, control, monitor);
}

/// A CVODE or ARKODE run from (t0, y0) to t1: checks the input and runs one segment.
template <class System, class MakeStepper>
Result run(const System& system, double t0, const typename System::State& y0, double t1, const Options& options,
           Method method, const Control* control, MakeStepper&& make) {
    validate(options, t0, t1);
    require_finite(y0, "initial state y0");
    Result result;
    result.method = method_name(method);
    typename System::State start = y0;
    model::system::project(system, start);
    Recording<System> recording(system, options, t0, t1, result);
    recording.start(start);
    if (t0 != t1) segment(system, recording, t0, start, options, control, make);  // t0 == t1: every output is t0
    return result;
}

}  // namespace gyrostat::integrate::sundials
