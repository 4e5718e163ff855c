// The engine: every model family behind one variant, one solve and one ensemble. The bindings
// and any other front end call these; they never see an integrator or a model template.
#pragma once

#include <Eigen/Core>
#include <string>
#include <variant>
#include <vector>

#include "gyrostat/integrate/control.hpp"
#include "gyrostat/integrate/options.hpp"
#include "gyrostat/model/averaged.hpp"
#include "gyrostat/model/averaged_triaxial.hpp"
#include "gyrostat/model/gyrostat.hpp"
#include "gyrostat/model/lagrange_averaged.hpp"
#include "gyrostat/model/lagrange_top.hpp"
#include "gyrostat/model/moving_mass.hpp"
#include "gyrostat/model/orbiting.hpp"
#include "gyrostat/model/orthogonal.hpp"
#include "gyrostat/model/torque_free.hpp"

namespace gyrostat {

/// Every model the library integrates (each implements model/system.hpp). Adding a model: its
/// header (included above), one alternative here, and its constructor in the bindings
/// (cpp/bindings/expose_models.cpp), and one line in GYROSTAT_SOLVED_MODELS below (which
/// src/solve_models.cpp compiles the solve of).
using AnyModel = std::variant<model::Gyrostat<false>, model::Gyrostat<true>, model::AveragedSymmetric,
                              model::MovingMass, model::LagrangeTop, model::LagrangeAveraged,
                              model::OrthogonalTorque<false>, model::OrthogonalTorque<true>, model::TorqueFree,
                              model::TorqueFreeAttitude, model::AveragedTriaxial, model::OrbitingGyrostat>;

/// Every alternative of AnyModel as X(Model): src/solve_models.cpp compiles their integration. A
/// new model: one line here, beside its alternative above (solve_system.hpp's static_assert says
/// when AnyModel has one not listed).
#define GYROSTAT_SOLVED_MODELS(X)                                                      \
    X(model::Gyrostat<false>) X(model::Gyrostat<true>) X(model::AveragedSymmetric)     \
    X(model::MovingMass) X(model::LagrangeTop) X(model::LagrangeAveraged)              \
    X(model::OrthogonalTorque<false>) X(model::OrthogonalTorque<true>)                 \
    X(model::TorqueFree) X(model::TorqueFreeAttitude) X(model::AveragedTriaxial)       \
    X(model::OrbitingGyrostat)

/// The family of a model: "gyrostat", "averaged_symmetric", "averaged_triaxial", "moving_mass",
/// "lagrange_top", "lagrange_averaged", "orthogonal_torque", "torque_free".
const char* family(const AnyModel& model);
int dim(const AnyModel& model);
std::vector<std::string> state_names(const AnyModel& model);
std::vector<std::string> output_names(const AnyModel& model);
/// A quantity a run's error is measured on (the accuracy contract, python/gyrostat/accuracy.py):
/// the state components of one vector (ω, the quaternion, a moving mass's displacement and velocity:
/// model::Quantity::vector; one norm), a scalar state (not a label), or an output the model
/// declares measured (model::OutputInfo::measured; not when a state has its name). In the order of
/// the state, then of the outputs.
struct MeasuredQuantity {
    std::string name;
    bool output = false;       ///< columns index the outputs (else the state)
    std::vector<int> columns;  ///< the components, in order
};
const std::vector<MeasuredQuantity>& measured_quantities(const AnyModel& model);
/// How far two runs of `model` are apart on each measured quantity, at each pair of rows
/// (`reference_rows[k]` of `reference` against `other_rows[k]` of `other`; empty: every row, the
/// runs having as many): row q of the result is quantity q's |Δ| (a vector's norm) over its largest
/// size in `reference` (that of a vector's norm). A quantity's values are first divided by their
/// largest magnitude (1 when that is 0, infinite or NaN), so that huge states do not overflow; a
/// NaN difference stays NaN.
Eigen::MatrixXd measured_differences(const AnyModel& model, const integrate::Result& reference,
                                     const integrate::Result& other, const std::vector<std::size_t>& reference_rows,
                                     const std::vector<std::size_t>& other_rows);
/// The model's signed distance to a separatrix (model/system.hpp: separatrix) at each state (rows,
/// in the user's frame); NaN for a model that declares none.
Eigen::VectorXd separatrix(const AnyModel& model, const Eigen::MatrixXd& states);
/// The first output time of `run` past `after` (in the run's direction) at which the state has
/// crossed a separatrix of the model (the sign of `separatrix` changed since the output before);
/// NaN when it does not, or when the model declares none.
double first_crossing(const AnyModel& model, const integrate::Result& run, double after);
/// An empty Result that says what a run of `model` holds: the names, units and descriptions of
/// its state and outputs (model/system.hpp's declarations).
integrate::Result described(const AnyModel& model);
/// f(t, y) (for checks, not for speed).
Eigen::VectorXd rhs(const AnyModel& model, double t, const Eigen::VectorXd& y);
/// The full initial state from what was given (e.g. ω alone for a model with attitude).
Eigen::VectorXd initial_state(const AnyModel& model, const Eigen::VectorXd& given);
/// States (rows, dim each) in the user's body frame written in the model's principal axes
/// (model/frame.hpp; unchanged for a body given by its principal moments): what the model's own
/// checks look at.
Eigen::MatrixXd principal_states(const AnyModel& model, const Eigen::MatrixXd& states);
/// An averaged model's state lifted to the model it averages, at the fast phase given
/// (model/system.hpp: full_state); std::invalid_argument for a model that averages nothing.
Eigen::VectorXd full_state(const AnyModel& model, const Eigen::VectorXd& slow, double phase);
/// The model's named outputs at (t, y), as the engine records them (NaN where undefined).
Eigen::VectorXd outputs_at(const AnyModel& model, double t, const Eigen::VectorXd& y);

/// Every function here takes and returns states in the user's body frame: for a body given by its
/// inertia tensor (Body::from_inertia) the model runs in the principal axes and the engine
/// converts at its edges (model/frame.hpp); the named outputs are the model's, in principal axes
/// (the Euler angles are those of the principal axes, body z the third principal axis).
///
/// Solves `model` from (t0, y0) to t1 (y0 may be short: see initial_state). Bad input throws
/// std::invalid_argument naming the value (method 'splitting' for a model that does not split
/// names the model); a failing run returns its partial trajectory.
integrate::Result solve(const AnyModel& model, double t0, const Eigen::Ref<const Eigen::VectorXd>& y0, double t1,
                        const integrate::Options& options, const integrate::Control* control = nullptr);

/// Member i solves models[i] (or models[0] for all when one is given) from (t0, y0s[i]) to t1;
/// models may differ in parameters and in family. Results in index order; a member with bad
/// input gets status InvalidInput without touching the others.
/// With `batch` (the default), members that a SIMD batch covers (integrate/batch.hpp: the
/// gyrostat with constant and linear torques under taylor or dop853, the averaged symmetric
/// system under dop853; no events, dense output or every_step) run lanes::width at a time, and
/// equal their single runs to the tolerance, not bit for bit; every other member, and every
/// member with batch = false, equals its single run bit for bit.
std::vector<integrate::Result> solve_ensemble(const std::vector<const AnyModel*>& models,
                                              const std::vector<Eigen::VectorXd>& y0s, double t0, double t1,
                                              const integrate::Options& options, int threads = 0,
                                              const integrate::Control* control = nullptr, bool batch = true);

/// One sensitivity asked of a run (solve_sensitivities): the derivative of the solution with
/// respect to the initial state's component `component` (in the user's frame), or, with
/// `component` < 0, to a parameter, given as the model built with it moved by +step (`plus`) and
/// by −step (`minus`), models of the same type as the run's.
struct SensitivityColumn {
    int component = -1;
    const AnyModel* plus = nullptr;
    const AnyModel* minus = nullptr;
    double step = 0.0;
    /// The absolute tolerance of this column's error control (the run's atol over the parameter's
    /// size: CVODES's p̄ scaling; the run's atol for an initial component).
    double atol = 0.0;
    /// Where the right-hand side is affine in the parameter (its torque or model declares so:
    /// affine_in, torque/set.hpp), or its torque inversely proportional to it (inverse_in), the
    /// model `far` with it moved by its own size, and ∂f/∂p = (f_far − f)/far_step: far_step the
    /// move where affine, p/2 where M ∝ 1/p (the move doubles p), exact up to rounding (that large
    /// a move keeps the difference far above f's rounding), one moved right-hand side per stage
    /// instead of two.
    const AnyModel* far = nullptr;
    double far_step = 0.0;
    /// Where the model gives ∂f/∂p in closed form (model::system::has_parameter_rate: the averaged
    /// top's μ), its index in the model's analytic_in; −1: none. The moved models still give the
    /// start's derivative and the outputs'.
    int analytic = -1;
};
/// A run with its sensitivities: `result` as `solve` gives it at the output times (states in the
/// user's frame, the outputs, statistics, status and message), `state` the sensitivities of the
/// state, `outputs` those of the named outputs, each row-major [time][component][column].
struct SensitivityRun {
    integrate::Result result;
    std::vector<double> state;
    std::vector<double> outputs;
};
/// Solves `model` from (t0, y0) to t1 together with its variational equations for each column
/// (model/variational.hpp) on the whole augmented state by DOP853, CVODE's BDF or, for the
/// gyrostat under constant and linear torques (polynomial variational equations), the Taylor
/// method (integrate/variational.hpp, variational_bdf.hpp, variational_taylor.hpp; options.method
/// dop853, cvode_bdf or taylor: taylor refuses the other models and torques by name; events and
/// every_step are not offered: the Python layer runs them on the plain run). The
/// outputs' sensitivities: central differences of the model's outputs along each column at each
/// output time. Bad input throws std::invalid_argument naming it (a closed-form model, a column's
/// model of another type, a component outside the state, a step that is not finite and > 0).
SensitivityRun solve_sensitivities(const AnyModel& model, const std::vector<SensitivityColumn>& columns, double t0,
                                   const Eigen::VectorXd& y0, double t1, const integrate::Options& options,
                                   const integrate::Control* control = nullptr);

/// Member i solves models[i] (or models[0]) with columns[i] (or columns[0]) from (t0, y0s[i]) to t1
/// as solve_sensitivities does, on `threads` threads (ensemble.hpp: run_ensemble; a member with bad
/// input gets status InvalidInput and empty sensitivities, the others run).
std::vector<SensitivityRun> solve_sensitivities_ensemble(const std::vector<const AnyModel*>& models,
                                                         const std::vector<std::vector<SensitivityColumn>>& columns,
                                                         const std::vector<Eigen::VectorXd>& y0s, double t0, double t1,
                                                         const integrate::Options& options, int threads = 0,
                                                         const integrate::Control* control = nullptr);

/// The integration of one model type: the whole engine (every method) instantiated for it. Each
/// alternative of AnyModel is instantiated in the translation unit src/solve_models.cpp
/// (solve_system.hpp: GYROSTAT_SOLVED_MODELS).
template <class Model>
integrate::Result solve_system(const Model& model, double t0, const Eigen::VectorXd& y0, double t1,
                               const integrate::Options& options, const integrate::Control* control);
#undef GYROSTAT_DECLARE_SOLVE

}  // namespace gyrostat
