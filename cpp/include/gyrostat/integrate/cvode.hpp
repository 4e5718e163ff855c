// CVODE: variable-order BDF with Newton iteration and a dense Jacobian (stiff problems), and
// variable-order Adams–Moulton with fixed-point iteration (non-stiff problems).
#pragma once

#include <cvode/cvode.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include "gyrostat/integrate/sundials_driver.hpp"

namespace gyrostat::integrate {

namespace cvode_detail {

/// Owns the CVODE memory and its linear/nonlinear solvers.
template <class System>
class CvodeStepper {
public:
    static constexpr bool exact_outputs = false;  // CVODE's interpolant has the method's order

    CvodeStepper(bool bdf, const sundials::Context& ctx, N_Vector y, double t0, const Options& o,
                 sundials::CallbackData<System>& data, sundials::ErrorLog& log)
        : bdf_(bdf) {
        using namespace sundials;
        mem_ = CVodeCreate(bdf ? CV_BDF : CV_ADAMS, ctx);
        if (mem_ == nullptr) throw std::runtime_error("CVodeCreate failed");
        check(CVodeSetErrHandlerFn(mem_, &ErrorLog::handler, &log), "CVodeSetErrHandlerFn");
        check(CVodeInit(mem_, &rhs_callback<System>, t0, y), "CVodeInit");
        check(CVodeSStolerances(mem_, o.rtol, o.atol), "CVodeSStolerances");
        check(CVodeSetUserData(mem_, &data), "CVodeSetUserData");
        check(CVodeSetMaxHnilWarns(mem_, 1), "CVodeSetMaxHnilWarns");
        if (o.first_step > 0.0) check(CVodeSetInitStep(mem_, o.first_step), "CVodeSetInitStep");
        if (std::isfinite(o.max_step)) check(CVodeSetMaxStep(mem_, o.max_step), "CVodeSetMaxStep");
        if (bdf) {
            matrix_ = SUNDenseMatrix(System::dim, System::dim, ctx);
            linear_solver_ = SUNLinSol_Dense(y, matrix_, ctx);
            if (matrix_ == nullptr || linear_solver_ == nullptr) throw std::runtime_error("SUNDIALS dense solver creation failed");
            check(CVodeSetLinearSolver(mem_, linear_solver_, matrix_), "CVodeSetLinearSolver");
            if constexpr (System::has_jacobian)
                check(CVodeSetJacFn(mem_, &jacobian_callback<System>), "CVodeSetJacFn");
        } else {
            nonlinear_solver_ = SUNNonlinSol_FixedPoint(y, 0, ctx);
            if (nonlinear_solver_ == nullptr) throw std::runtime_error("SUNNonlinSol_FixedPoint failed");
            check(CVodeSetNonlinearSolver(mem_, nonlinear_solver_), "CVodeSetNonlinearSolver");
        }
    }
    ~CvodeStepper() {
        CVodeFree(&mem_);
        if (linear_solver_) SUNLinSolFree(linear_solver_);
        if (matrix_) SUNMatDestroy(matrix_);
        if (nonlinear_solver_) SUNNonlinSolFree(nonlinear_solver_);
    }
    CvodeStepper(const CvodeStepper&) = delete;
    CvodeStepper& operator=(const CvodeStepper&) = delete;

    int evolve(double tout, N_Vector y, double* t, bool one_step) {
        return CVode(mem_, tout, y, t, one_step ? CV_ONE_STEP : CV_NORMAL);
    }
    void set_stop_time(double t) { sundials::check(CVodeSetStopTime(mem_, t), "CVodeSetStopTime"); }
    void set_max_steps(long n) { sundials::check(CVodeSetMaxNumSteps(mem_, n), "CVodeSetMaxNumSteps"); }
    void interpolate(double t, N_Vector y) { sundials::check(CVodeGetDky(mem_, t, 0, y), "CVodeGetDky"); }

    Stats stats() const {
        Stats s;
        long lin_rhs = 0;
        CVodeGetNumSteps(mem_, &s.steps);
        CVodeGetNumRhsEvals(mem_, &s.rhs_evals);
        CVodeGetNumErrTestFails(mem_, &s.rejected_steps);
        CVodeGetNumNonlinSolvConvFails(mem_, &s.nonlinear_conv_failures);
        if (bdf_) {
            CVodeGetNumJacEvals(mem_, &s.jacobian_evals);
            CVodeGetNumLinRhsEvals(mem_, &lin_rhs);  // f evaluations of a difference-quotient Jacobian
        }
        s.rhs_evals += lin_rhs;
        CVodeGetLastStep(mem_, &s.last_step);
        return s;
    }
    static Status classify(int flag) {
        switch (flag) {
            case -1000:
            case CV_TOO_MUCH_WORK: return Status::MaxStepsReached;
            case CV_TOO_CLOSE:
            case CV_ERR_FAILURE:  // error test failed repeatedly or at the smallest step
            case CV_TOO_MUCH_ACC: return Status::StepSizeUnderflow;
            case CV_RHSFUNC_FAIL:
            case CV_FIRST_RHSFUNC_ERR:
            case CV_REPTD_RHSFUNC_ERR:
            case CV_UNREC_RHSFUNC_ERR: return Status::NonFiniteState;
            default: return Status::SolverFailure;
        }
    }
    std::string flag_name(int flag) const {
        if (flag == -1000) return "max_steps";
        char* name = CVodeGetReturnFlagName(flag);
        std::string s = name ? name : "CV_UNKNOWN";
        free(name);
        return s;
    }
    bool suggest_stiff() const { return !bdf_; }  // Adams is a non-stiff method
    double current_step() const {
        double h = 0.0;
        CVodeGetCurrentStep(mem_, &h);
        return h;
    }

private:
    bool bdf_;
    void* mem_ = nullptr;
    SUNMatrix matrix_ = nullptr;
    SUNLinearSolver linear_solver_ = nullptr;
    SUNNonlinearSolver nonlinear_solver_ = nullptr;
};

}  // namespace cvode_detail

/// Integrates with CVODE (bdf = true: BDF + Newton + dense Jacobian, analytic where the system
/// has one; false: Adams + fixed point). Failing runs return their partial trajectory.
template <class System>
Result cvode(const System& system, double t0, const typename System::State& y0, double t1, const Options& options,
             bool bdf) {
    validate(options, t0, t1);
    require_finite(y0, "initial state y0");
    Result result;
    result.method = method_name(bdf ? Method::CvodeBdf : Method::CvodeAdams);
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
    cvode_detail::CvodeStepper<System> stepper(bdf, ctx, y.get(), t0, options, data, log);
    sundials::drive(system, stepper, y.get(), t0, t1, options, data, log, result);
    return result;
}

}  // namespace gyrostat::integrate
