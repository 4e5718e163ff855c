// What CVODE and ARKODE share: RAII ownership of SUNDIALS objects, the right-hand-side and
// Jacobian adapters, an error handler that keeps SUNDIALS's messages, one flag checker.
#pragma once

#include <exception>

#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_nonlinearsolver.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "gyrostat/integrate/recorder.hpp"

namespace gyrostat::integrate::sundials {

/// Throws std::runtime_error("<call> failed with flag <flag>") when a set-up call fails.
void check(int flag, const char* call);

/// Owns a SUNContext.
class Context {
public:
    Context();
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;
    operator SUNContext() const { return ctx_; }

private:
    SUNContext ctx_ = nullptr;
};

struct VectorDeleter {
    void operator()(_generic_N_Vector* v) const { N_VDestroy(v); }
};
using Vector = std::unique_ptr<_generic_N_Vector, VectorDeleter>;
Vector make_vector(int n, SUNContext ctx);

/// Collects SUNDIALS's error and warning messages instead of letting them reach stderr.
struct ErrorLog {
    std::string last_error;
    bool step_below_resolution = false;  ///< SUNDIALS warned "t + h = t"
    static void handler(int error_code, const char* module, const char* function, char* msg, void* data);
};

/// Owners of the SUNDIALS objects a stepper creates, released in reverse order of creation even
/// when a later set-up call throws.
struct MatrixDeleter {
    void operator()(_generic_SUNMatrix* m) const { SUNMatDestroy(m); }
};
struct LinearSolverDeleter {
    void operator()(_generic_SUNLinearSolver* s) const { SUNLinSolFree(s); }
};
struct NonlinearSolverDeleter {
    void operator()(_generic_SUNNonlinearSolver* s) const { SUNNonlinSolFree(s); }
};
using Matrix = std::unique_ptr<_generic_SUNMatrix, MatrixDeleter>;
using LinearSolver = std::unique_ptr<_generic_SUNLinearSolver, LinearSolverDeleter>;
using NonlinearSolver = std::unique_ptr<_generic_SUNNonlinearSolver, NonlinearSolverDeleter>;

/// The interpolant of a step that ended at t, h long, as monomials in s = (t' − t)/h for a
/// DenseOutput: c_k = y⁽ᵏ⁾(t) hᵏ/k!, k = 0 … degree, `derivative(k)` giving y⁽ᵏ⁾(t) (null where the
/// solver cannot: the polynomial stops there). Returns its degree.
template <class Derivative>
int step_polynomial(const Derivative& derivative, int degree, double h, std::size_t size, std::vector<double>& coefficients) {
    coefficients.clear();
    double factor = 1.0;
    int k = 0;
    for (; k <= degree; ++k) {
        const double* d = derivative(k);
        if (d == nullptr) break;
        for (std::size_t i = 0; i < size; ++i) coefficients.push_back(d[i] * factor);
        factor *= h / (k + 1);
    }
    return k - 1;
}

/// Throws std::runtime_error("<what> failed") when a SUNDIALS constructor returned null.
template <class Pointer>
Pointer created(Pointer p, const char* what) {
    if (p == nullptr) throw std::runtime_error(std::string(what) + " failed");
    return p;
}

/// What the C callbacks see: the system, whether a non-finite derivative was met, and an
/// exception the system threw (a user's torque function): no exception crosses SUNDIALS' C
/// frames; the callback returns an unrecoverable failure and the driver rethrows it.
template <class System>
struct CallbackData {
    const System* system = nullptr;
    bool non_finite = false;
    double t_non_finite = 0.0;
    std::exception_ptr error;
};

template <class System>
using StateMap = Eigen::Map<const typename System::State>;

/// y' = f(t, y) for SUNDIALS. A non-finite derivative is a recoverable failure (the solver retries
/// with a smaller step); if it persists, the run ends with NonFiniteState.
template <class System>
int rhs_callback(double t, N_Vector y, N_Vector ydot, void* user_data) {
    auto* data = static_cast<CallbackData<System>*>(user_data);
    typename System::State dy;
    try {
        data->system->rhs(t, StateMap<System>(N_VGetArrayPointer(y)), dy);
    } catch (...) {
        data->error = std::current_exception();
        return -1;
    }
    Eigen::Map<typename System::State>(N_VGetArrayPointer(ydot)) = dy;
    if (!all_finite(dy)) {
        data->non_finite = true;
        data->t_non_finite = t;
        return 1;
    }
    return 0;
}

/// Dense ∂f/∂y for CVODE's Newton iteration (SUNDenseMatrix is column-major, like Eigen).
template <class System>
int jacobian_callback(double t, N_Vector y, N_Vector /*fy*/, SUNMatrix jac, void* user_data, N_Vector, N_Vector,
                      N_Vector) {
    auto* data = static_cast<CallbackData<System>*>(user_data);
    model::system::Jacobian<System> j;
    try {
        data->system->jacobian(t, StateMap<System>(N_VGetArrayPointer(y)), j);
    } catch (...) {
        data->error = std::current_exception();
        return -1;
    }
    Eigen::Map<model::system::Jacobian<System>>(SM_DATA_D(jac)) = j;
    if (all_finite(Eigen::Map<const Eigen::VectorXd>(j.data(), j.size()))) return 0;
    // A non-finite ∂f/∂y (an attitude torque of 1e308: its ∂M/∂q overflows before f does) is a
    // non-finite derivative too: retried, and reported so if it persists.
    data->non_finite = true;
    data->t_non_finite = t;
    return 1;
}

/// Post-step projection (ARKODE): keeps constrained parts (a quaternion) on their manifold.
template <class System>
int project_callback(double /*t*/, N_Vector y, void* user_data) {
    auto* data = static_cast<CallbackData<System>*>(user_data);
    Eigen::Map<typename System::State> state(N_VGetArrayPointer(y));
    typename System::State projected = state;
    model::system::project(*data->system, projected);
    state = projected;
    return 0;
}

}  // namespace gyrostat::integrate::sundials
