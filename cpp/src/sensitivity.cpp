// The engine's forward sensitivities: a model's variational equations (model/variational.hpp)
// integrated on the augmented state by DOP853 (integrate/variational.hpp) or CVODE's BDF
// (integrate/variational_bdf.hpp), for every model that integrates (a closed form has no
// right-hand side to vary), or by the Taylor method (integrate/variational_taylor.hpp) for the
// gyrostat under constant and linear torques, whose variational equations are polynomial.
#include <cmath>
#include <cstdlib>
#include <algorithm>
#include <limits>
#include <memory>
#include <string>

#include "gyrostat/engine.hpp"
#include "gyrostat/ensemble.hpp"
#include "gyrostat/integrate/dense.hpp"
#include "gyrostat/integrate/recorder.hpp"
#include "gyrostat/integrate/variational.hpp"
#include "gyrostat/integrate/variational_bdf.hpp"
#include "gyrostat/integrate/variational_taylor.hpp"
#include "gyrostat/model/frame.hpp"
#include "gyrostat/model/variational.hpp"

namespace gyrostat {

namespace {

using model::frame::To;

constexpr double kRoot3Eps = 6.0554544523933395e-06;  // ε^{1/3}: a central difference's best step

/// The run of one model type.
template <class M>
SensitivityRun solve_variational(const M& m, const std::vector<SensitivityColumn>& columns, double t0,
                                 const Eigen::VectorXd& given, double t1, const integrate::Options& options,
                                 const integrate::Control* control) {
    constexpr int n = M::dim;
    const Eigen::Index width = static_cast<Eigen::Index>(columns.size());
    std::vector<model::Varied<M>> varied(columns.size());
    std::vector<double> atol{options.atol}, rtol{options.rtol};
    // A column whose rate is a difference quotient (a parameter's ∂f/∂p not declared affine, or
    // ∂f/∂y·S of a model without a Jacobian) has its relative error controlled to at least the
    // quotient's own accuracy: below it the steps would chase the quotient's rounding noise.
    const double floor = model::kDifferenceAccuracy;
    constexpr bool differenced_jacobian = !model::system::has_jacobian<M>::value && !model::system::has_rate_with_products<M>::value;
    Eigen::VectorXd start = Eigen::VectorXd::Zero(n * (1 + width));
    start.head<n>() = model::frame::initial_state(m, given);
    for (std::size_t j = 0; j < columns.size(); ++j) {
        const SensitivityColumn& c = columns[j];
        const std::string which = "sensitivity " + std::to_string(j) + ": ";
        if (c.component >= 0) {
            if (c.component >= n)
                throw std::invalid_argument(which + "state component " + std::to_string(c.component) + " of a state of " +
                                            std::to_string(n) + " (" + model::system::join_names(M::states) + ")");
            Eigen::Matrix<double, n, 1> unit = Eigen::Matrix<double, n, 1>::Unit(c.component);
            model::frame::convert(m, unit.data(), To::Principal);  // linear: a direction converts as a state
            // The run starts from the projection of the state given (|q| = 1): the column starts as
            // that projection's derivative along e_k (central difference; e_k where none).
            if constexpr (model::system::has_projection<M>::value) {
                const typename M::State y0 = start.head<n>();
                const double delta = kRoot3Eps * std::max(y0.norm(), 1.0);
                typename M::State plus = y0 + delta * unit, minus = y0 - delta * unit;
                m.project(plus);
                m.project(minus);
                unit = (plus - minus) / (2.0 * delta);
            }
            start.segment<n>(n * static_cast<Eigen::Index>(1 + j)) = unit;
        } else {
            const M* plus = c.plus ? std::get_if<M>(c.plus) : nullptr;
            const M* minus = c.minus ? std::get_if<M>(c.minus) : nullptr;
            if (!plus || !minus)
                throw std::invalid_argument(which + "the models with the parameter moved must be '" + M::family +
                                            "' models, as the run's");
            if (!(std::isfinite(c.step) && c.step > 0.0))
                throw std::invalid_argument(which + "the parameter's step must be finite and > 0, got " +
                                            integrate::format_number(c.step, 17));
            const M* far = c.far ? std::get_if<M>(c.far) : nullptr;
            if (c.far && !(far && std::isfinite(c.far_step) && c.far_step > 0.0))
                throw std::invalid_argument(which + "the model moved far must be a '" + std::string(M::family) +
                                            "' model with a finite step > 0");
            if (c.analytic >= 0 && static_cast<std::size_t>(c.analytic) >= model::system::analytic_in<M>().size())
                throw std::invalid_argument(which + "the model gives no closed-form derivative number " +
                                            std::to_string(c.analytic) + " (it gives " +
                                            std::to_string(model::system::analytic_in<M>().size()) + ")");
            varied[j] = {plus, minus, c.step, far, c.far_step, c.analytic};
            // The state the run starts from may depend on the parameter (an averaged model's slow
            // variables from the ω given): S_j(t0) = ∂y(t0)/∂p_j, by the same central difference.
            // (Each in this model's axes: a body's parameter turns the moved models' principal axes.)
            typename M::State y_plus = model::frame::initial_state(*plus, given), y_minus = model::frame::initial_state(*minus, given);
            model::frame::reframe(*plus, m, y_plus.data());
            model::frame::reframe(*minus, m, y_minus.data());
            start.segment<n>(n * static_cast<Eigen::Index>(1 + j)) = (y_plus - y_minus) / (2.0 * c.step);
        }
        if (!(std::isfinite(c.atol) && c.atol > 0.0))
            throw std::invalid_argument(which + "its absolute tolerance must be finite and > 0, got " +
                                        integrate::format_number(c.atol, 17));
        atol.push_back(c.atol);
        const bool differenced = differenced_jacobian || (c.component < 0 && !c.far && c.analytic < 0);
        rtol.push_back(differenced ? std::max(options.rtol, floor) : options.rtol);
    }
    const model::Variational<M> system(m, std::move(varied));
    const std::vector<double> times = integrate::output_times(options, t0, t1);
    auto rate = [&](double t, const Eigen::VectorXd& y, Eigen::VectorXd& dy) { system.rhs(t, y, dy); };
    // With dense output: the whole augmented state's, each block in the user's frame on evaluation
    // (a direction converts as a state: the map is linear).
    std::shared_ptr<integrate::DenseOutput> dense;
    if (options.dense_output) {
        dense = std::make_shared<integrate::DenseOutput>(static_cast<int>(start.size()), -1);
        if (model::frame::rotated(m))
            dense->set_transform([body = m.body(), blocks = 1 + width](double* y) {
                for (Eigen::Index b = 0; b < blocks; ++b) model::frame::convert_state<M>(body, y + b * n, To::User);
            });
    }
    integrate::VariationalRun run;
    if (options.method == integrate::Method::CvodeBdf) {
        // The run starts from the model's projection of the state given (|q| = 1), as DOP853's and
        // the Taylor method's do (CVODE takes its start as it is: a quaternion of norm 0.975 ran
        // as given, state and sensitivities off by 2e-2 against the normalised start's).
        system.project(start);
        // Newton's matrix from the model's analytic ∂f/∂y where it gives one (block diagonal)
        auto block_jacobian = [&](double t, const Eigen::Map<const Eigen::VectorXd>& y, Eigen::MatrixXd& J) {
            if constexpr (model::system::has_jacobian<M>::value) {
                model::system::Jacobian<M> j;
                m.jacobian(t, typename M::State(y.head<n>()), j);
                J = j;
            }
        };
        run = integrate::variational_bdf(rate, model::system::has_jacobian<M>::value ? &block_jacobian : nullptr, n, t0,
                                         start, t1, times, atol, options, control, dense.get());
    } else if (options.method == integrate::Method::Taylor) {
        if constexpr (model::system::has_affine_euler<M>::value) {
            // The moved models' coefficients are differenced in their own principal axes: a
            // parameter that turns them (an inertia tensor's entry) needs the rates' route.
            for (const model::Varied<M>& column : system.columns())
                if (column.plus && (column.plus->body().principal_axes() != m.body().principal_axes() ||
                                    column.minus->body().principal_axes() != m.body().principal_axes()))
                    throw std::invalid_argument("sensitivities by method 'taylor' to a parameter that turns the body's "
                                                "principal axes (an inertia tensor's entry): use dop853 or cvode_bdf");
            run = integrate::variational_taylor(m, system.columns(), t0, start, t1, times, atol, options, control,
                                                dense.get());
        } else {
            throw std::invalid_argument(std::string("sensitivities by method 'taylor' cover the gyrostat model "
                                                    "(gyrostat.Model, on an orbit too) under constant and linear "
                                                    "torques; the '") +
                                        M::family + "' model has no polynomial variational equations here: use "
                                        "dop853 or cvode_bdf");
        }
    } else {
        constexpr auto quadratures = model::system::quadratures<M>();
        run = integrate::variational_dop853(rate, [&](Eigen::VectorXd& y) { return system.project(y); }, n, t0, start,
                                            t1, times, atol, rtol, options, control, dense.get(),
                                            std::vector<int>(quadratures.begin(), quadratures.end()));
    }

    SensitivityRun out;
    integrate::Result& r = out.result;
    integrate::describe<M>(r, &m);
    r.method = integrate::method_name(options.method);
    r.methods_used = {r.method};
    r.options = options;
    r.stats = run.stats;
    r.status = run.status;
    r.message = run.message;
    r.dense = dense;  // (its first block is the state: Result::dense evaluates it; the rest, dense_whole)
    constexpr int n_out = model::system::n_outputs<M>();
    const std::size_t rows = run.t.size();
    r.t = run.t;
    r.y.reserve(rows * n);
    r.outputs.reserve(rows * n_out);
    out.state.reserve(rows * n * columns.size());
    out.outputs.reserve(rows * n_out * columns.size());
    for (std::size_t k = 0; k < rows; ++k) {
        const Eigen::VectorXd& Y = run.state[k];
        typename M::State y = Y.head<n>();
        // a recorded state on its manifold (a unit quaternion), as the plain run's recorder keeps it
        // (integrate/recorder.hpp): an output inside a step is the step's polynomial, off it by ~rtol
        model::system::project(m, y);
        double outputs[n_out > 0 ? n_out : 1], plus[n_out > 0 ? n_out : 1], minus[n_out > 0 ? n_out : 1];
        if constexpr (n_out > 0) model::system::outputs(m, run.t[k], y, outputs);
        typename M::State user = y;
        model::frame::convert(m, user.data(), To::User);
        r.y.insert(r.y.end(), user.data(), user.data() + n);
        r.outputs.insert(r.outputs.end(), outputs, outputs + n_out);
        // ∂y/∂p in the user's frame, [component][column].
        Eigen::Matrix<double, n, Eigen::Dynamic> S(n, width);
        for (Eigen::Index j = 0; j < width; ++j) {
            typename M::State s = Y.segment<n>(n * (1 + j));
            model::frame::convert(m, s.data(), To::User);
            S.col(j) = s;
        }
        for (int i = 0; i < n; ++i)
            for (Eigen::Index j = 0; j < width; ++j) out.state.push_back(S(i, j));
        if constexpr (n_out > 0) {
            // ∂out/∂p = ∂out/∂y · S_j (+ ∂out/∂p_j): central differences along S_j, and between the
            // models with p_j moved. Where the two parts cancel (their sum below a tenth of their
            // sizes), each part's own truncation would be amplified as much: that output's total
            // derivative is taken instead as one central difference along (S_j, 1), the state moved
            // by ±h S_j into the models moved by ±h (h the parameter's step). The averaged top's
            // roots u1, u2 near small nutation (parts +9.05 and −9.50) read 1e-3 off apart, 1e-8 so.
            Eigen::Matrix<double, n_out, Eigen::Dynamic> D(n_out, width);
            for (Eigen::Index j = 0; j < width; ++j) {
                const typename M::State s = Y.segment<n>(n * (1 + j));
                Eigen::Matrix<double, n_out, 1> d = Eigen::Matrix<double, n_out, 1>::Zero(), along = d;
                if (s.norm() > 0.0) {
                    const double delta = kRoot3Eps * std::max(y.norm(), 1e-300) / s.norm();
                    const typename M::State y_plus = y + delta * s, y_minus = y - delta * s;
                    model::system::outputs(m, run.t[k], y_plus, plus);
                    model::system::outputs(m, run.t[k], y_minus, minus);
                    for (int o = 0; o < n_out; ++o) along[o] = d[o] = (plus[o] - minus[o]) / (2.0 * delta);
                }
                const SensitivityColumn& c = columns[static_cast<std::size_t>(j)];
                if (c.component < 0) {
                    const M &moved_plus = *std::get_if<M>(c.plus), &moved_minus = *std::get_if<M>(c.minus);
                    auto moved_outputs = [&](const typename M::State& from_plus, const typename M::State& from_minus) {
                        typename M::State there_plus = from_plus, there_minus = from_minus;
                        model::frame::reframe(m, moved_plus, there_plus.data());
                        model::frame::reframe(m, moved_minus, there_minus.data());
                        model::system::outputs(moved_plus, run.t[k], there_plus, plus);
                        model::system::outputs(moved_minus, run.t[k], there_minus, minus);
                    };
                    moved_outputs(y, y);
                    bool cancelling = false;
                    for (int o = 0; o < n_out; ++o) {
                        const double explicit_part = (plus[o] - minus[o]) / (2.0 * c.step);
                        d[o] += explicit_part;
                        cancelling = cancelling || std::abs(d[o]) < 0.1 * (std::abs(along[o]) + std::abs(explicit_part));
                    }
                    if (cancelling) {
                        moved_outputs(y + c.step * s, y - c.step * s);
                        for (int o = 0; o < n_out; ++o) {
                            const double explicit_part = d[o] - along[o];
                            if (std::abs(d[o]) < 0.1 * (std::abs(along[o]) + std::abs(explicit_part)))
                                d[o] = (plus[o] - minus[o]) / (2.0 * c.step);
                        }
                    }
                }
                D.col(j) = d;
            }
            for (int o = 0; o < n_out; ++o)
                for (Eigen::Index j = 0; j < width; ++j) out.outputs.push_back(D(o, j));
        }
    }
    if (rows > 0) {
        r.t_last = r.t.back();
        r.y_last.assign(r.y.end() - n, r.y.end());
    }
    if (run.status == integrate::Status::Interrupted) r.notes.push_back(run.message);
    return out;
}

}  // namespace

SensitivityRun solve_sensitivities(const AnyModel& model, const std::vector<SensitivityColumn>& columns, double t0,
                                   const Eigen::VectorXd& y0, double t1, const integrate::Options& options,
                                   const integrate::Control* control) {
    integrate::validate(options, t0, t1);
    if (options.method != integrate::Method::Dop853 && options.method != integrate::Method::CvodeBdf &&
        options.method != integrate::Method::Taylor)
        throw std::invalid_argument(std::string("sensitivities are integrated by dop853, cvode_bdf or taylor (the "
                                                "variational equations on the whole augmented state), not by method '") +
                                    integrate::method_name(options.method) + "'");
    if (!options.events.empty() || options.every_step)
        throw std::invalid_argument("sensitivities are recorded at the output times (t_eval or n_out) and in the dense "
                                    "output: events and every_step are not offered with them here (the Python layer "
                                    "locates events on the plain run)");
    return std::visit(
        [&](const auto& m) -> SensitivityRun {
            using M = std::decay_t<decltype(m)>;
            if constexpr (model::system::is_closed_form<M>::value) {
                throw std::invalid_argument(std::string("the '") + M::family +
                                            "' closed form has no right-hand side to vary: its sensitivities are those "
                                            "of gyrostat.Model(body) (Euler's equations without torques)");
            } else {
                return solve_variational(m, columns, t0, y0, t1, options, control);
            }
        },
        model);
}

std::vector<SensitivityRun> solve_sensitivities_ensemble(const std::vector<const AnyModel*>& models,
                                                         const std::vector<std::vector<SensitivityColumn>>& columns,
                                                         const std::vector<Eigen::VectorXd>& y0s, double t0, double t1,
                                                         const integrate::Options& options, int threads,
                                                         const integrate::Control* control) {
    const std::size_t n = y0s.size();
    if (models.empty() || columns.empty()) throw std::invalid_argument("solve_sensitivities_ensemble: no model or no columns given");
    if ((models.size() != 1 && models.size() != n) || (columns.size() != 1 && columns.size() != n))
        throw std::invalid_argument("solve_sensitivities_ensemble: " + std::to_string(models.size()) + " models and " +
                                    std::to_string(columns.size()) + " column sets for " + std::to_string(n) +
                                    " initial states (give 1 or " + std::to_string(n) + " of each)");
    std::vector<SensitivityRun> runs(n);
    std::vector<integrate::Result> results = run_ensemble(
        n,
        [&](std::size_t i, const integrate::Control* member) {
            SensitivityRun run = solve_sensitivities(*models[models.size() == 1 ? 0 : i], columns[columns.size() == 1 ? 0 : i],
                                                     t0, y0s[i], t1, options, member);
            runs[i].state = std::move(run.state);
            runs[i].outputs = std::move(run.outputs);
            return std::move(run.result);
        },
        threads, control);
    for (std::size_t i = 0; i < n; ++i) runs[i].result = std::move(results[i]);
    return runs;
}

}  // namespace gyrostat
