// One interface for every integrator: its options, its result, its statuses.
#pragma once

#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace gyrostat::integrate {

class DenseOutput;  // dense.hpp

enum class Method {
    Dop853,          ///< fixed-size, allocation-free Dormand–Prince 8(5,3) with 7th-order dense output
    CvodeBdf,        ///< CVODE variable-order BDF (stiff), Newton with dense Jacobian
    CvodeAdams,      ///< CVODE variable-order Adams–Moulton (non-stiff), fixed-point iteration
    ArkodeVerner6,   ///< ARKODE ERK, Verner 8-stage 6(5) table ARKODE_VERNER_8_5_6
    ArkodeFehlberg8, ///< ARKODE ERK, Fehlberg 13-stage 8(7) table ARKODE_FEHLBERG_13_7_8
    Taylor,          ///< Taylor series of adaptive order (polynomial right-hand sides only)
    Splitting,       ///< exact free-body flow composed with the perturbation's flow, fixed step (splitting.hpp)
    Auto,            ///< DOP853 while the problem is not stiff, CVODE BDF while it is, switching along the run (auto_switch.hpp)
};

Method method_from_name(const std::string& name);  ///< throws std::invalid_argument listing the names
const char* method_name(Method m);
std::vector<std::string> method_names();
/// One line per method, in the order of method_names().
std::vector<std::string> method_descriptions();

/// An event: g(t, y) = quantity(t, y) − value crossing zero, where the quantity is a state
/// component, a named output of the model (evaluated in C++), or a function of (t, y) (a Python
/// callable: the slow path, one call into Python per evaluation).
struct Event {
    enum class Quantity { State, Output, Function };
    Quantity quantity = Quantity::State;
    int index = 0;        ///< the state component or output
    double value = 0.0;
    int direction = 0;    ///< +1: upward crossings only (g from < 0 to ≥ 0), −1: downward, 0: both (SciPy's sign)
    int terminal = 0;     ///< 0: record and go on; n ≥ 1: stop the run at the n-th crossing
    std::string name;
    std::function<double(double t, const double* y, int dim)> function;  ///< Quantity::Function
    /// > 0: g is evaluated only at step ends at least this far in t from its last evaluation, and
    /// a crossing is placed at the step end where it is seen (no refinement): for a watch whose g
    /// is costly and changes slowly against the steps (the model ladder's way back down, whose g is
    /// an averaged model's outputs, evaluated once per fast period instead of at every step).
    double sample_interval = 0.0;
};

/// The most memory one run's outputs may take (times, states and named outputs, 8 bytes each):
/// a run, a scene or an ensemble member asking for more is refused before it starts.
constexpr double kMaxOutputBytes = 2.0 * 1024 * 1024 * 1024;

/// Every option of every integrator, with its default: the one place where defaults live
/// (the Python layer reads them from here).
struct Options {
    Method method = Method::Dop853;
    double rtol = 1e-8;
    double atol = 1e-10;
    /// Output times (monotone in the direction of integration, inside [t0, t1]). When empty:
    /// n_out evenly spaced times from t0 to t1 (n_out = 0: t0 and t1 only).
    std::vector<double> t_eval;
    long n_out = 1001;
    /// Also record every accepted step (memory then grows with the steps: asked for explicitly).
    bool every_step = false;
    long max_steps = 1'000'000;                                   ///< over the whole run
    double first_step = 0.0;                                      ///< 0: chosen by the method
    double max_step = std::numeric_limits<double>::infinity();   ///< largest |h|
    /// Zero crossings to locate on each step's continuous extension (events.hpp).
    std::vector<Event> events;
    /// Keep every step's continuous extension (Result::dense): memory grows with the steps.
    bool dense_output = false;
    /// Fixed step of method 'splitting' (0: chosen from rtol by the splitting's own error
    /// estimate; unused by the other methods).
    double step = 0.0;
    /// Order of the splitting composition: 2 (Strang), 4 or 6 (Yoshida's triple jumps).
    int splitting_order = 4;
    /// Record only the named outputs a run's error is measured on, the others NaN where the model
    /// spares their cost (model/system.hpp: measured_outputs): a window estimate's companion
    /// (measure.cpp) and the accuracy contract's probes (python/gyrostat/contract.py), which
    /// compare no more.
    bool only_measured_outputs = false;
    /// A run with sensitivities (model/variational.hpp): whether each sensitivity's error joins the
    /// state's in the step-size control (CVODES's errconS). False (CVODES's default): the steps are
    /// the state's alone, those of the plain run, whose answer the sensitivities then leave as it
    /// was; their own error is measured and reported (gyrostat.sensitivity), not held. True: every
    /// sensitivity held to the tolerances too, at the cost of the steps it takes (1–1.6× the plain
    /// run's on bench/sensitivity_cost.py's cases). DOP853 and the Taylor method; CVODE's BDF holds
    /// them always (integrate/variational_bdf.hpp).
    bool sensitivity_error_control = false;
};

enum class Status {
    Success = 0,
    MaxStepsReached,     ///< the step budget ran out before t1
    StepSizeUnderflow,   ///< the step fell below the resolution of t (or the method's minimum)
    NonFiniteState,      ///< the state or its derivative became inf/NaN
    SolverFailure,       ///< any other failure reported by SUNDIALS (convergence, setup)
    InvalidInput,        ///< an ensemble member whose input was rejected (the others still run)
    Interrupted,         ///< stopped on request (Control::poll returned false, or Ctrl-C)
};
const char* status_name(Status s);

struct Stats {
    long steps = 0;
    long rhs_evals = 0;
    long rejected_steps = 0;   ///< error-test failures
    long jacobian_evals = 0;
    long nonlinear_conv_failures = 0;
    double last_step = 0.0;    ///< size of the last accepted step (0 when none)
};

/// The statistics of a run carried by two integrators in turn (`earlier`, then `later`): the
/// counts summed, the last step the later one's.
inline Stats operator+(const Stats& earlier, const Stats& later) {
    Stats s = later;
    s.steps += earlier.steps;
    s.rhs_evals += earlier.rhs_evals;
    s.rejected_steps += earlier.rejected_steps;
    s.jacobian_evals += earlier.jacobian_evals;
    s.nonlinear_conv_failures += earlier.nonlinear_conv_failures;
    return s;
}

/// Method 'auto' changed integrator at time t, to the method named `to`, for the reason given
/// (the measured h·|λ| against the explicit stability boundary).
struct MethodSwitch {
    double t = 0.0;
    std::string to;
    std::string reason;
};

/// A model type's declarations (model/system.hpp: Quantity, OutputInfo): names, SI units and one
/// line each for the state's components and the named outputs. Made once per model type
/// (recorder.hpp: declarations<System>) and shared by every Result of that type: a run copies a
/// pointer, not ~30 strings (most of a trivial run's allocations before).
struct Declarations {
    std::vector<std::string> state_names, state_units, state_descriptions;
    std::vector<std::string> output_names, output_units, output_descriptions;
    std::vector<bool> output_conserved;  ///< per output: a first integral of the unperturbed model
};

/// A trajectory: n output times, n×dim states and n×n_outputs named outputs (row-major).
/// A failed run keeps everything up to the failure and says why in `message`.
struct Result {
    std::string method;
    int dim = 0;
    /// The model's declarations (null until a model has described the Result: recorder.hpp).
    std::shared_ptr<const Declarations> declared;
    const std::vector<std::string>& state_names() const { return declarations().state_names; }
    const std::vector<std::string>& state_units() const { return declarations().state_units; }
    const std::vector<std::string>& state_descriptions() const { return declarations().state_descriptions; }
    const std::vector<std::string>& output_names() const { return declarations().output_names; }
    const std::vector<std::string>& output_units() const { return declarations().output_units; }
    const std::vector<std::string>& output_descriptions() const { return declarations().output_descriptions; }
    const std::vector<bool>& output_conserved() const { return declarations().output_conserved; }
    /// per output: conserved and kept by this model with its torques (a forced energy is not kept)
    std::vector<bool> output_kept;
    /// The options the run was made with (recorded(): every scalar option; t_eval and events are
    /// the outputs' times and event_names).
    Options options;
    std::vector<double> t;
    std::vector<double> y;
    std::vector<double> outputs;
    /// Per event: the times of its crossings and the states there (row-major, dim per crossing).
    std::vector<std::string> event_names;
    std::vector<std::vector<double>> t_events;
    std::vector<std::vector<double>> y_events;
    int terminal_event = -1;  ///< the event that ended the run (status Success), −1: none
    std::shared_ptr<DenseOutput> dense;  ///< with Options::dense_output: the solution between outputs
    Stats stats;
    /// The integrators that carried the run, in order of first use (one for every method but
    /// 'auto'), and where method 'auto' switched between them.
    std::vector<std::string> methods_used;
    std::vector<MethodSwitch> switches;
    Status status = Status::Success;
    std::string message;
    /// Where the run stopped, however it ended (t1, a terminal event, max_steps, a failure, an
    /// interruption): the last accepted time and state, and the step size the integrator would
    /// try next (0: it chooses its own), so that a run can be continued from there.
    double t_last = std::numeric_limits<double>::quiet_NaN();
    std::vector<double> y_last;
    double h_next = 0.0;
    /// What the run says about its own answer, one sentence each. `notes`: information (the
    /// splitting's chosen step and estimated error); `warnings`: doubts about the answer (that
    /// estimate above rtol, a step clamped to the span, BDF stepping over oscillations it damps).
    /// The status stays Success; Python warns with each warning (gyrostat.AccuracyWarning) and
    /// keeps both in Solution.notes and the scene's report.
    std::vector<std::string> notes;
    std::vector<std::string> warnings;
    /// The run's own estimate of its global error relative to max|y_i| (method 'splitting', from
    /// composite steps of h against two of h/2); NaN where the method gives none.
    double error_estimate = std::numeric_limits<double>::quiet_NaN();

    bool success() const { return status == Status::Success; }
    std::size_t size() const { return t.size(); }

private:
    const Declarations& declarations() const {
        static const Declarations none;
        return declared ? *declared : none;
    }
};

/// Checks rtol, atol, t0, t1, t_eval, max_steps, first_step, max_step; throws
/// std::invalid_argument naming the bad value.
void validate(const Options& options, double t0, double t1);

/// The rule of one scalar option ("rtol", "atol", "n_out", "max_steps", "first_step",
/// "max_step", "step", "splitting_order"): throws std::invalid_argument "<name> = <value> must
/// be …" when `value` breaks it. validate() and the scene schema both apply these rules.
void check_option(const std::string& name, double value);

/// Every scalar option of `options` (the method, tolerances, output count, step limits,
/// splitting, flags), without t_eval and events: what a Result records.
Options recorded(const Options& options);

/// The output times: t_eval, or n_out evenly spaced times, or {t0, t1}.
std::vector<double> output_times(const Options& options, double t0, double t1);

}  // namespace gyrostat::integrate
