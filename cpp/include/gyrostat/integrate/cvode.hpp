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

struct CvodeDeleter {
    void operator()(void* mem) const { CVodeFree(&mem); }
};

/// Owns the CVODE memory and its linear/nonlinear solvers (released even when set-up throws).
template <class System>
class CvodeStepper {
public:
    static constexpr bool exact_outputs = false;  // CVODE's interpolant has the method's order

    CvodeStepper(bool bdf, SUNContext ctx, N_Vector y, double t0, const Options& o, sundials::CallbackData<System>& data,
                 sundials::ErrorLog& log)
        : bdf_(bdf), mem_(sundials::created(CVodeCreate(bdf ? CV_BDF : CV_ADAMS, ctx), "CVodeCreate")) {
        using namespace sundials;
        void* mem = mem_.get();
        check(CVodeSetErrHandlerFn(mem, &ErrorLog::handler, &log), "CVodeSetErrHandlerFn");
        check(CVodeInit(mem, &rhs_callback<System>, t0, y), "CVodeInit");
        check(CVodeSStolerances(mem, o.rtol, o.atol), "CVodeSStolerances");
        check(CVodeSetUserData(mem, &data), "CVodeSetUserData");
        check(CVodeSetMaxHnilWarns(mem, 1), "CVodeSetMaxHnilWarns");
        check(CVodeSetMaxNumSteps(mem, -1), "CVodeSetMaxNumSteps");  // the driver counts steps over the whole run
        if (o.first_step > 0.0) check(CVodeSetInitStep(mem, o.first_step), "CVodeSetInitStep");
        if (std::isfinite(o.max_step)) check(CVodeSetMaxStep(mem, o.max_step), "CVodeSetMaxStep");
        if (bdf) {
            matrix_.reset(created(SUNDenseMatrix(System::dim, System::dim, ctx), "SUNDenseMatrix"));
            linear_solver_.reset(created(SUNLinSol_Dense(y, matrix_.get(), ctx), "SUNLinSol_Dense"));
            check(CVodeSetLinearSolver(mem, linear_solver_.get(), matrix_.get()), "CVodeSetLinearSolver");
            if constexpr (model::system::has_jacobian<System>::value)
                check(CVodeSetJacFn(mem, &jacobian_callback<System>), "CVodeSetJacFn");
        } else {
            nonlinear_solver_.reset(created(SUNNonlinSol_FixedPoint(y, 0, ctx), "SUNNonlinSol_FixedPoint"));
            check(CVodeSetNonlinearSolver(mem, nonlinear_solver_.get()), "CVodeSetNonlinearSolver");
        }
    }

    int evolve(double tout, N_Vector y, double* t) { return CVode(mem_.get(), tout, y, t, CV_ONE_STEP); }
    void set_stop_time(double t) { sundials::check(CVodeSetStopTime(mem_.get(), t), "CVodeSetStopTime"); }
    void interpolate(double t, N_Vector y) { sundials::check(CVodeGetDky(mem_.get(), t, 0, y), "CVodeGetDky"); }
    int derivative(double t, int k, N_Vector d) { return CVodeGetDky(mem_.get(), t, k, d); }
    int degree() const {
        int q = 0;
        CVodeGetLastOrder(mem_.get(), &q);
        return q;
    }

    Stats stats() const {
        void* mem = mem_.get();
        Stats s;
        long lin_rhs = 0;
        CVodeGetNumSteps(mem, &s.steps);
        CVodeGetNumRhsEvals(mem, &s.rhs_evals);
        CVodeGetNumErrTestFails(mem, &s.rejected_steps);
        CVodeGetNumNonlinSolvConvFails(mem, &s.nonlinear_conv_failures);
        if (bdf_) {
            CVodeGetNumJacEvals(mem, &s.jacobian_evals);
            CVodeGetNumLinRhsEvals(mem, &lin_rhs);  // f evaluations of a difference-quotient Jacobian
        }
        s.rhs_evals += lin_rhs;
        CVodeGetLastStep(mem, &s.last_step);
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

private:
    bool bdf_;
    std::unique_ptr<void, CvodeDeleter> mem_;
    sundials::Matrix matrix_;
    sundials::LinearSolver linear_solver_;
    sundials::NonlinearSolver nonlinear_solver_;
};

}  // namespace cvode_detail

/// Makes the CVODE stepper of a segment that starts at t (see sundials::segment).
template <class System>
auto cvode_maker(bool bdf, const Options& options) {
    return [bdf, &options](double t, SUNContext ctx, N_Vector y, sundials::CallbackData<System>& data,
                           sundials::ErrorLog& log) {
        return cvode_detail::CvodeStepper<System>(bdf, ctx, y, t, options, data, log);
    };
}

/// Integrates with CVODE (bdf = true: BDF + Newton + dense Jacobian, analytic where the system
/// has one; false: Adams + fixed point). Failing runs return their partial trajectory.
template <class System>
Result cvode(const System& system, double t0, const typename System::State& y0, double t1, const Options& options,
             bool bdf, const Control* control = nullptr) {
    return sundials::run(system, t0, y0, t1, options, bdf ? Method::CvodeBdf : Method::CvodeAdams, control,
                         cvode_maker<System>(bdf, options));
}

}  // namespace gyrostat::integrate
