// CVODE's BDF on a state whose size is known only at run time: the variational equations of a
// stiff model (model/variational.hpp) integrated together with its state, as variational.hpp does
// with DOP853. Newton's matrix is the block diagonal of the augmented Jacobian (the model's ∂f/∂y
// on every block: CVODES's simultaneous corrector makes the same approximation, the blocks below
// the diagonal left out; Newton still converges, and the error test is on the whole state), from
// the model's analytic Jacobian, or CVODE's difference quotients where the model has none. Each
// block's absolute tolerance as in variational.hpp (CVodeSVtolerances). The error test covers
// every block whatever Options::sensitivity_error_control says: CVODE's one weighted norm serves
// its error test and Newton's convergence test alike, and a block left out of it would leave
// Newton's iterates on the sensitivities unchecked. Outputs from CVODE's own interpolant
// (CVodeGetDky) inside each step.
#pragma once

#include <cvode/cvode.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "gyrostat/integrate/control.hpp"
#include "gyrostat/integrate/dense.hpp"
#include "gyrostat/integrate/options.hpp"
#include "gyrostat/integrate/recorder.hpp"
#include "gyrostat/integrate/sundials.hpp"
#include "gyrostat/integrate/variational.hpp"

namespace gyrostat::integrate {

namespace variational_bdf_detail {

/// What the C callbacks see: the augmented right-hand side, the block Jacobian (or none), the
/// block size, a working vector, and an exception a callback kept.
template <class Rhs, class BlockJacobian>
struct Callbacks {
    const Rhs& rhs;
    const BlockJacobian* jacobian;  ///< fills the model's ∂f/∂y (block × block, column-major) at y
    Eigen::Index block;
    Eigen::VectorXd y, dy;
    std::exception_ptr error;

    static int rate(double t, N_Vector y, N_Vector ydot, void* user) {
        auto* self = static_cast<Callbacks*>(user);
        self->y = Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(y), self->y.size());
        try {
            self->rhs(t, self->y, self->dy);
        } catch (...) {
            self->error = std::current_exception();
            return -1;
        }
        Eigen::Map<Eigen::VectorXd>(N_VGetArrayPointer(ydot), self->dy.size()) = self->dy;
        return self->dy.allFinite() ? 0 : 1;
    }
    static int newton(double t, N_Vector y, N_Vector, SUNMatrix jac, void* user, N_Vector, N_Vector, N_Vector) {
        auto* self = static_cast<Callbacks*>(user);
        const Eigen::Index n = self->block, size = self->y.size();
        Eigen::MatrixXd J(n, n);
        try {
            (*self->jacobian)(t, Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(y), size), J);
        } catch (...) {
            self->error = std::current_exception();
            return -1;
        }
        Eigen::Map<Eigen::MatrixXd> whole(SM_DATA_D(jac), size, size);
        whole.setZero();
        for (Eigen::Index b = 0; b < size / n; ++b) whole.block(b * n, b * n, n, n) = J;
        return J.allFinite() ? 0 : 1;
    }
};

struct CvodeDeleter {
    void operator()(void* mem) const { CVodeFree(&mem); }
};

}  // namespace variational_bdf_detail

/// Integrates Y' = rhs(t, Y) by CVODE's BDF from (t0, Y0) to t1, recording Y at `times` (as
/// variational_dop853). `jacobian(t, Y, J)`, when not null, gives the model's ∂f/∂y at Y's first
/// block (block × block). With a `dense` output, every step's interpolant goes into it (CVODE's
/// Nordsieck polynomial, as sundials_driver.hpp keeps it).
template <class Rhs, class BlockJacobian>
VariationalRun variational_bdf(const Rhs& rhs, const BlockJacobian* jacobian, Eigen::Index block, double t0,
                               const Eigen::VectorXd& y0, double t1, const std::vector<double>& times,
                               const std::vector<double>& atol, const Options& options, const Control* control,
                               DenseOutput* dense = nullptr) {
    using namespace sundials;
    const Eigen::Index size = y0.size();
    const double direction = t1 >= t0 ? 1.0 : -1.0;
    VariationalRun run;
    std::size_t next = 0;
    while (next < times.size() && times[next] == t0) run.t.push_back(t0), run.state.push_back(y0), ++next;
    if (t0 == t1) return run;

    Context ctx;
    Vector y = make_vector(static_cast<int>(size), ctx), tolerances = make_vector(static_cast<int>(size), ctx),
           at = make_vector(static_cast<int>(size), ctx);
    Eigen::Map<Eigen::VectorXd>(N_VGetArrayPointer(y.get()), size) = y0;
    for (Eigen::Index i = 0; i < size; ++i) NV_Ith_S(tolerances.get(), i) = atol[static_cast<std::size_t>(i / block)];
    variational_bdf_detail::Callbacks<Rhs, BlockJacobian> callbacks{rhs, jacobian, block, Eigen::VectorXd(size),
                                                                     Eigen::VectorXd(size), nullptr};
    ErrorLog log;
    std::unique_ptr<void, variational_bdf_detail::CvodeDeleter> memory(created(CVodeCreate(CV_BDF, ctx), "CVodeCreate"));
    void* mem = memory.get();
    check(CVodeSetErrHandlerFn(mem, &ErrorLog::handler, &log), "CVodeSetErrHandlerFn");
    check(CVodeInit(mem, &decltype(callbacks)::rate, t0, y.get()), "CVodeInit");
    check(CVodeSVtolerances(mem, options.rtol, tolerances.get()), "CVodeSVtolerances");
    check(CVodeSetUserData(mem, &callbacks), "CVodeSetUserData");
    check(CVodeSetMaxHnilWarns(mem, 1), "CVodeSetMaxHnilWarns");
    check(CVodeSetMaxNumSteps(mem, -1), "CVodeSetMaxNumSteps");  // counted here over the whole run
    check(CVodeSetStopTime(mem, t1), "CVodeSetStopTime");
    if (options.first_step > 0.0) check(CVodeSetInitStep(mem, options.first_step), "CVodeSetInitStep");
    if (std::isfinite(options.max_step)) check(CVodeSetMaxStep(mem, options.max_step), "CVodeSetMaxStep");
    Matrix matrix(created(SUNDenseMatrix(size, size, ctx), "SUNDenseMatrix"));
    LinearSolver solver(created(SUNLinSol_Dense(y.get(), matrix.get(), ctx), "SUNLinSol_Dense"));
    check(CVodeSetLinearSolver(mem, solver.get(), matrix.get()), "CVodeSetLinearSolver");
    if (jacobian) check(CVodeSetJacFn(mem, &decltype(callbacks)::newton), "CVodeSetJacFn");

    auto statistics = [&] {
        long lin_rhs = 0;
        CVodeGetNumSteps(mem, &run.stats.steps);
        CVodeGetNumRhsEvals(mem, &run.stats.rhs_evals);
        CVodeGetNumErrTestFails(mem, &run.stats.rejected_steps);
        CVodeGetNumNonlinSolvConvFails(mem, &run.stats.nonlinear_conv_failures);
        CVodeGetNumJacEvals(mem, &run.stats.jacobian_evals);
        CVodeGetNumLinRhsEvals(mem, &lin_rhs);
        run.stats.rhs_evals += lin_rhs;
        CVodeGetLastStep(mem, &run.stats.last_step);
    };
    Ticker ticker(control, t0, t1);
    double t = t0;
    std::vector<double> coefficients;
    while (true) {
        if (!ticker.keep_going(t)) {
            statistics();
            run.status = Status::Interrupted;
            run.message = interrupted_message(t);
            return run;
        }
        long steps = 0;
        CVodeGetNumSteps(mem, &steps);
        if (steps >= options.max_steps) {
            statistics();
            run.status = Status::MaxStepsReached;
            run.message = "max_steps = " + std::to_string(options.max_steps) + " reached at t = " + format_number(t) +
                          " before t1 = " + format_number(t1);
            return run;
        }
        const double t_before = t;
        const int flag = CVode(mem, t1, y.get(), &t, CV_ONE_STEP);
        if (callbacks.error) std::rethrow_exception(callbacks.error);
        if (flag < 0) {
            statistics();
            run.status = flag == CV_TOO_CLOSE || flag == CV_ERR_FAILURE || flag == CV_TOO_MUCH_ACC
                             ? Status::StepSizeUnderflow
                             : flag == CV_RHSFUNC_FAIL || flag == CV_REPTD_RHSFUNC_ERR || flag == CV_UNREC_RHSFUNC_ERR ||
                                       flag == CV_FIRST_RHSFUNC_ERR
                                   ? Status::NonFiniteState
                                   : Status::SolverFailure;
            run.message = "CVODE (BDF, with the sensitivities) failed at t = " + format_number(t) + ": " +
                          (log.last_error.empty() ? std::string("flag ") + std::to_string(flag) : log.last_error);
            return run;
        }
        if (dense && t != t_before) {  // y(t') = Σ y⁽ᵏ⁾(t) (t' − t)ᵏ/k!, in s = (t' − t)/h
            int order = 0;
            CVodeGetLastOrder(mem, &order);
            const int degree = step_polynomial(
                [&](int k) { return CVodeGetDky(mem, t, k, at.get()) < 0 ? nullptr : N_VGetArrayPointer(at.get()); }, order,
                t - t_before, static_cast<std::size_t>(size), coefficients);
            dense->add(t_before, t, t, t - t_before, degree, coefficients.data());
        }
        while (next < times.size() && direction * (times[next] - t) <= 0.0) {
            check(CVodeGetDky(mem, times[next], 0, at.get()), "CVodeGetDky");
            run.t.push_back(times[next]);
            run.state.emplace_back(Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(at.get()), size));
            ++next;
        }
        if (t == t1 || next == times.size()) break;
    }
    statistics();
    return run;
}

}  // namespace gyrostat::integrate
