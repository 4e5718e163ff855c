// The engine's dispatch over AnyModel: names, right-hand side, solve and ensemble.
#include "gyrostat/engine.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "gyrostat/ensemble.hpp"
#include "ensemble_batch.hpp"
#include "gyrostat/integrate/dense.hpp"
#include "gyrostat/integrate/splitting.hpp"
#include "gyrostat/model/frame.hpp"

namespace gyrostat {

namespace {

template <class Visitor>
decltype(auto) visit(const AnyModel& model, Visitor&& visitor) {
    return std::visit(std::forward<Visitor>(visitor), model);
}

using model::frame::To;

/// Every state a run of `m` holds, from its principal axes to the user's frame
/// (model/frame.hpp): the outputs' states, the events' states, the last state and the dense output.
template <class S>
void to_user_frame(const S& m, integrate::Result& r) {
    if (!model::frame::rotated(m)) return;
    const auto convert_rows = [&](std::vector<double>& rows) {
        for (std::size_t i = 0; i + S::dim <= rows.size(); i += S::dim) model::frame::convert(m, rows.data() + i, To::User);
    };
    convert_rows(r.y);
    for (auto& rows : r.y_events) convert_rows(rows);
    if (r.y_last.size() == static_cast<std::size_t>(S::dim)) convert_rows(r.y_last);
    if (r.dense)
        r.dense->set_transform([body = m.body()](double* y) { model::frame::convert_state<S>(body, y, To::User); });
}

/// The options of a run of `m` in its principal axes: an event on a state component or a function
/// of the state sees the state in the user's frame.
template <class S>
integrate::Options with_events_in_user_frame(const S& m, const integrate::Options& options) {
    integrate::Options converted = options;
    if (!model::frame::rotated(m)) return converted;
    for (integrate::Event& e : converted.events) {
        using Quantity = integrate::Event::Quantity;
        if (e.quantity == Quantity::State && e.index >= 0 && e.index < S::dim) {
            const int index = e.index;
            e.quantity = Quantity::Function;
            e.function = [body = m.body(), index](double, const double* y, int) {
                typename S::State user = Eigen::Map<const typename S::State>(y);
                model::frame::convert_state<S>(body, user.data(), To::User);
                return user[index];
            };
        } else if (e.quantity == Quantity::Function && e.function) {
            e.function = [body = m.body(), f = e.function](double t, const double* y, int dim) {
                typename S::State user = Eigen::Map<const typename S::State>(y);
                model::frame::convert_state<S>(body, user.data(), To::User);
                return f(t, user.data(), dim);
            };
        }
    }
    return converted;
}

template <class S, class = void>
struct has_torques : std::false_type {};
template <class S>
struct has_torques<S, std::void_t<decltype(std::declval<const S&>().torques())>> : std::true_type {};

/// Whether a member's torques run one call at a time (TorqueSet::serialised).
bool serialised(const AnyModel& model) {
    return visit(model, [](const auto& m) {
        if constexpr (has_torques<std::decay_t<decltype(m)>>::value)
            return m.torques().serialised();
        else
            return false;
    });
}

/// A run of `m` from `start`, its full initial state in principal axes, given and returned in the
/// user's frame.
template <class S>
integrate::Result solve_from_principal(const S& m, double t0, const Eigen::VectorXd& start, double t1,
                                       const integrate::Options& options, const integrate::Control* control) {
    if constexpr (!integrate::has_splitting<S>::value && !model::system::is_closed_form<S>::value) {
        if (options.method == integrate::Method::Splitting)
            throw std::invalid_argument(std::string("method 'splitting': the '") + S::family +
                                        "' model does not split into the exact free-body flow and a perturbation "
                                        "(splitting is offered for the gyrostat Model, the Lagrange top and the orthogonal-torque model); "
                                        "choose another method");
    }
    if (!model::frame::rotated(m)) return solve_system(m, t0, start, t1, options, control);
    integrate::Result r = solve_system(m, t0, start, t1, with_events_in_user_frame(m, options), control);
    to_user_frame(m, r);
    return r;
}

}  // namespace

const char* family(const AnyModel& model) {
    return visit(model, [](const auto& m) { return std::decay_t<decltype(m)>::family; });
}

int dim(const AnyModel& model) {
    return visit(model, [](const auto& m) { return std::decay_t<decltype(m)>::dim; });
}

std::vector<std::string> state_names(const AnyModel& model) {
    return visit(model, [](const auto& m) {
        using S = std::decay_t<decltype(m)>;
        std::vector<std::string> names;
        for (const auto& q : S::states) names.emplace_back(q.name);
        return names;
    });
}

integrate::Result described(const AnyModel& model) {
    return visit(model, [](const auto& m) {
        integrate::Result r;
        integrate::describe<std::decay_t<decltype(m)>>(r, &m);
        return r;
    });
}

std::vector<std::string> output_names(const AnyModel& model) { return described(model).output_names(); }

const std::vector<MeasuredQuantity>& measured_quantities(const AnyModel& model) {
    return visit(model, [](const auto& m) -> const std::vector<MeasuredQuantity>& {
        using S = std::decay_t<decltype(m)>;
        // (the type's declarations alone decide them: made once per model type, ~1 µs a window estimate saved)
        static const std::vector<MeasuredQuantity> made = [] {
            std::vector<MeasuredQuantity> found;
            std::vector<std::string> taken;
            for (int i = 0; i < S::dim; ++i) {
                const model::Quantity& q = S::states[i];
                taken.emplace_back(q.name);
                if (q.label) continue;
                const std::string name = q.vector ? q.vector : q.name;
                auto same = std::find_if(found.begin(), found.end(),
                                         [&](const MeasuredQuantity& x) { return !x.output && x.name == name; });
                if (q.vector && same != found.end())
                    same->columns.push_back(i);
                else
                    found.push_back({name, false, {i}});
            }
            if constexpr (model::system::has_outputs<S>::value) {
                int column = 0;
                for (const model::OutputInfo& info : S::outputs_info) {
                    if (info.measured && std::find(taken.begin(), taken.end(), info.name) == taken.end())
                        found.push_back({info.name, true, {column}});
                    ++column;
                }
            }
            return found;
        }();
        return made;
    });
}

namespace {

/// NaN anywhere makes a largest size NaN (as NumPy's maximum), which then counts as no size at all: 1.
double unit_of(double top, bool nan) { return nan || !(top > 0.0 && std::isfinite(top)) ? 1.0 : top; }

/// One measured quantity's row of measured_differences: `a` and `b` the runs' arrays (states or
/// outputs), `row_a(k)` and `row_b(k)` the offsets of the k-th compared row in each.
template <class RowA, class RowB>
void differences_of(const MeasuredQuantity& quantity, const double* a, const double* b, std::size_t n, RowA row_a,
                    RowB row_b, Eigen::MatrixXd& made, Eigen::Index row) {
    double top = 0.0;
    bool nan = false;
    for (std::size_t k = 0; k < n; ++k)
        for (int c : quantity.columns) {
            const double v = std::abs(a[row_a(k) + c]);
            nan = nan || std::isnan(v);
            top = std::max(top, v);
        }
    const double unit = unit_of(top, nan);
    if (quantity.columns.size() == 1) {
        // One column: its largest |x|/unit is 1 exactly (|x| <= top, and division is monotone), or
        // the unit is 1 and so is the scale below (a column of zeros, NaN or infinity): the
        // differences relative to the unit are the answer.
        const int c = quantity.columns[0];
        for (std::size_t k = 0; k < n; ++k)
            made(row, static_cast<Eigen::Index>(k)) = std::abs((a[row_a(k) + c] - b[row_b(k) + c]) / unit);
        return;
    }
    double largest = 0.0;  // the norm of the columns relative to the unit
    bool largest_nan = false;
    for (std::size_t k = 0; k < n; ++k) {
        const double* x = a + row_a(k);
        const double* z = b + row_b(k);
        double size = 0.0, distance = 0.0;
        for (int c : quantity.columns) {
            const double s = x[c] / unit, d = (x[c] - z[c]) / unit;
            size += s * s;
            distance += d * d;
        }
        size = std::sqrt(size);
        largest_nan = largest_nan || std::isnan(size);
        largest = std::max(largest, size);
        made(row, static_cast<Eigen::Index>(k)) = std::sqrt(distance);
    }
    made.row(row) /= unit_of(largest, largest_nan);
}

}  // namespace

Eigen::MatrixXd measured_differences(const AnyModel& model, const integrate::Result& reference,
                                     const integrate::Result& other, const std::vector<std::size_t>& reference_rows,
                                     const std::vector<std::size_t>& other_rows) {
    auto rows = [](const integrate::Result& r, const std::vector<std::size_t>& given) {
        for (std::size_t k : given)
            if (k >= r.t.size()) throw std::invalid_argument("measured_differences: row " + std::to_string(k) + " of a run with " +
                                                             std::to_string(r.t.size()));
        return given.empty() ? r.t.size() : given.size();
    };
    const std::size_t n = rows(reference, reference_rows), n_other = rows(other, other_rows);
    // (runs of one model type share their declarations: the names compared only when they do not)
    const bool alike = reference.declared == other.declared || reference.output_names() == other.output_names();
    if (n != n_other || reference.dim != other.dim || !alike)
        throw std::invalid_argument("measured_differences: the runs compare " + std::to_string(n) + " and " +
                                    std::to_string(n_other) + " rows of states of " + std::to_string(reference.dim) +
                                    " and " + std::to_string(other.dim) + " components: they must be alike");
    const std::vector<MeasuredQuantity>& quantities = measured_quantities(model);
    const std::size_t dim = static_cast<std::size_t>(reference.dim), width = reference.output_names().size();
    Eigen::MatrixXd made(static_cast<Eigen::Index>(quantities.size()), static_cast<Eigen::Index>(n));
    for (std::size_t q = 0; q < quantities.size(); ++q) {
        const MeasuredQuantity& quantity = quantities[q];
        const std::size_t stride = quantity.output ? width : dim;
        const double* a = quantity.output ? reference.outputs.data() : reference.y.data();
        const double* b = quantity.output ? other.outputs.data() : other.y.data();
        // row k of each run: every row (a whole span's measurement) by its stride, else the rows listed
        auto every = [stride](std::size_t k) { return k * stride; };
        auto listed = [stride](const std::vector<std::size_t>& given) {
            return [stride, &given](std::size_t k) { return given[k] * stride; };
        };
        const Eigen::Index row = static_cast<Eigen::Index>(q);
        if (reference_rows.empty() && other_rows.empty())
            differences_of(quantity, a, b, n, every, every, made, row);
        else if (reference_rows.empty())
            differences_of(quantity, a, b, n, every, listed(other_rows), made, row);
        else if (other_rows.empty())
            differences_of(quantity, a, b, n, listed(reference_rows), every, made, row);
        else
            differences_of(quantity, a, b, n, listed(reference_rows), listed(other_rows), made, row);
    }
    return made;
}

double first_crossing(const AnyModel& model, const integrate::Result& run, double after) {
    const double none = std::numeric_limits<double>::quiet_NaN();
    return visit(model, [&](const auto& m) -> double {
        using S = std::decay_t<decltype(m)>;
        if constexpr (model::system::has_separatrix<S>::value) {
            const std::size_t n = run.t.size();
            if (n < 2 || run.dim != S::dim) return none;
            const double forward = run.t[n - 1] >= run.t[0] ? 1.0 : -1.0;
            double side = 0.0;
            for (std::size_t k = 0; k < n; ++k) {
                typename S::State y = Eigen::Map<const typename S::State>(run.y.data() + k * S::dim);
                model::frame::convert(m, y.data(), To::Principal);
                const double now = m.separatrix(y);
                const double sign = now > 0.0 ? 1.0 : now < 0.0 ? -1.0 : 0.0;  // (NaN: 0, as no side)
                if (k > 0 && side * sign < 0.0 && (run.t[k] - after) * forward > 0.0) return run.t[k];
                side = sign;
            }
            return none;
        } else {
            (void)m, (void)run, (void)after;
            return none;
        }
    });
}

Eigen::VectorXd rhs(const AnyModel& model, double t, const Eigen::VectorXd& y) {
    return visit(model, [&](const auto& m) -> Eigen::VectorXd {
        using S = std::decay_t<decltype(m)>;
        if (y.size() != S::dim)
            throw std::invalid_argument("rhs: the state has " + std::to_string(y.size()) + " components; this model needs " +
                                        std::to_string(S::dim) + " (" +
                                        model::system::join_names(S::states) + ")");
        typename S::State principal = model::frame::initial_state(m, y), dy;
        m.rhs(t, principal, dy);
        model::frame::convert(m, dy.data(), To::User);  // the map is linear: it takes rates as it takes states
        return dy;
    });
}

Eigen::VectorXd initial_state(const AnyModel& model, const Eigen::VectorXd& given) {
    return visit(model, [&](const auto& m) -> Eigen::VectorXd {
        auto y = model::frame::initial_state(m, given);
        model::frame::convert(m, y.data(), To::User);
        return y;
    });
}

Eigen::MatrixXd principal_states(const AnyModel& model, const Eigen::MatrixXd& states) {
    return visit(model, [&](const auto& m) -> Eigen::MatrixXd {
        using S = std::decay_t<decltype(m)>;
        if (states.cols() != S::dim)
            throw std::invalid_argument("principal_states: a state has " + std::to_string(states.cols()) +
                                        " components; this model's have " + std::to_string(S::dim));
        Eigen::MatrixXd principal = states;
        for (Eigen::Index i = 0; i < principal.rows(); ++i) {
            typename S::State y = principal.row(i).transpose();
            model::frame::convert(m, y.data(), To::Principal);
            principal.row(i) = y.transpose();
        }
        return principal;
    });
}

Eigen::VectorXd separatrix(const AnyModel& model, const Eigen::MatrixXd& states) {
    const Eigen::MatrixXd principal = principal_states(model, states);
    return visit(model, [&](const auto& m) -> Eigen::VectorXd {
        using S = std::decay_t<decltype(m)>;
        Eigen::VectorXd made = Eigen::VectorXd::Constant(principal.rows(), std::numeric_limits<double>::quiet_NaN());
        if constexpr (model::system::has_separatrix<S>::value)
            for (Eigen::Index i = 0; i < principal.rows(); ++i) made[i] = m.separatrix(typename S::State(principal.row(i).transpose()));
        return made;
    });
}

Eigen::VectorXd full_state(const AnyModel& model, const Eigen::VectorXd& slow, double phase) {
    return visit(model, [&](const auto& m) -> Eigen::VectorXd {
        using S = std::decay_t<decltype(m)>;
        if constexpr (model::system::has_full_state<S>::value) {
            if (slow.size() != S::dim)
                throw std::invalid_argument("full_state: the slow state has " + std::to_string(slow.size()) +
                                            " components; this model needs " + std::to_string(S::dim) + " (" +
                                            model::system::join_names(S::states) + ")");
            if (!std::isfinite(phase)) throw std::invalid_argument("full_state: the phase must be finite");
            Eigen::VectorXd lifted = m.full_state(typename S::State(slow), phase);
            model::frame::convert_rate_state(m.body(), lifted.data(), lifted.size(), To::User);
            return lifted;
        } else {
            (void)phase;
            throw std::invalid_argument(std::string("full_state: the '") + S::family +
                                        "' model is not an averaged model (it has no full state to lift to)");
        }
    });
}

Eigen::VectorXd outputs_at(const AnyModel& model, double t, const Eigen::VectorXd& y) {
    return visit(model, [&](const auto& m) -> Eigen::VectorXd {
        using S = std::decay_t<decltype(m)>;
        const typename S::State state = model::frame::initial_state(m, y);
        Eigen::VectorXd out(model::system::n_outputs<S>());
        model::system::outputs(m, t, state, out.data());
        return out;
    });
}

integrate::Result solve(const AnyModel& model, double t0, const Eigen::Ref<const Eigen::VectorXd>& y0, double t1,
                        const integrate::Options& options, const integrate::Control* control) {
    const Eigen::VectorXd given = y0;
    return visit(model, [&](const auto& m) {
        if (!model::frame::rotated(m)) return solve_from_principal(m, t0, given, t1, options, control);
        return solve_from_principal(m, t0, model::frame::initial_state(m, given), t1, options, control);
    });
}

namespace {
/// "member <task>: …" from run_ensemble, where the task is not the member's index (batches and
/// single members are tasks of their own): the message names the member.
void name_member(integrate::Result& r, std::size_t task, std::size_t member) {
    const std::string prefix = "member " + std::to_string(task) + ": ";
    if (r.message.rfind(prefix, 0) == 0) r.message = "member " + std::to_string(member) + ": " + r.message.substr(prefix.size());
}
}  // namespace

std::vector<integrate::Result> solve_ensemble(const std::vector<const AnyModel*>& models,
                                              const std::vector<Eigen::VectorXd>& y0s, double t0, double t1,
                                              const integrate::Options& options, int threads,
                                              const integrate::Control* control, bool batch) {
    const std::size_t n = y0s.size();
    if (models.empty()) throw std::invalid_argument("solve_ensemble: no model given");
    if (models.size() != 1 && models.size() != n)
        throw std::invalid_argument("solve_ensemble: " + std::to_string(models.size()) + " models for " +
                                    std::to_string(n) + " initial states (give 1 or " + std::to_string(n) + ")");
    integrate::validate(options, t0, t1);
    // Members with a Python torque serialise on the GIL: more threads only pass it back and forth
    // (2 threads: 18.7 µs a call against 1.0 µs on one), so they run on one.
    for (const AnyModel* m : models)
        if (serialised(*m)) threads = 1;
    const auto model_of = [&](std::size_t i) -> const AnyModel& { return *(models.size() == 1 ? models[0] : models[i]); };
    // Members on a body given by its inertia tensor start from their state in principal axes
    // (a start that cannot be converted stays as given: its run then reports why).
    std::vector<Eigen::VectorXd> starts = y0s;
    std::vector<char> rotated(n, 0);
    for (std::size_t i = 0; i < n; ++i)
        visit(model_of(i), [&](const auto& m) {
            if (!model::frame::rotated(m)) return;
            rotated[i] = 1;
            try {
                starts[i] = model::frame::initial_state(m, y0s[i]);
            } catch (const std::exception&) {
            }
        });
    const ensemble_batch::Implementation& kernels = ensemble_batch::current();
    ensemble_batch::Plan plan;
    if (batch)
        plan = kernels.plan(models, starts, options);
    else
        for (std::size_t i = 0; i < n; ++i) plan.single.push_back(i);
    // Tasks: the batches first, then the members that run alone; each task on one thread.
    std::vector<integrate::Result> results(n);
    const std::size_t n_batches = plan.batches.size();
    auto tasks = run_ensemble(
        n_batches + plan.single.size(),
        [&](std::size_t task, const integrate::Control* member) {
            if (task < n_batches) {
                kernels.solve(plan.batches[task], models, starts, t0, t1, options, member, results);
                integrate::Result task_result;  // Interrupted when the caller stopped the batch: no task starts after it
                for (std::size_t i : plan.batches[task]) {
                    if (rotated[i]) visit(model_of(i), [&](const auto& m) { to_user_frame(m, results[i]); });
                    if (results[i].status == integrate::Status::Interrupted) task_result.status = integrate::Status::Interrupted;
                }
                return task_result;
            }
            const std::size_t i = plan.single[task - n_batches];
            return visit(model_of(i), [&](const auto& m) {
                return solve_from_principal(m, t0, starts[i], t1, options, member);
            });
        },
        threads, control);
    for (std::size_t task = 0; task < tasks.size(); ++task) {
        if (task >= n_batches) {
            const std::size_t i = plan.single[task - n_batches];
            results[i] = std::move(tasks[task]);
            name_member(results[i], task, i);
        } else if (!tasks[task].success()) {  // the batch threw or never started: each member says so
            for (std::size_t i : plan.batches[task]) {
                results[i] = tasks[task];
                name_member(results[i], task, i);
            }
        }
    }
    for (std::size_t i = 0; i < n; ++i) {  // members that never ran still say what they would hold
        auto& r = results[i];
        r.options = integrate::recorded(options);
        if (r.declared) continue;
        visit(model_of(i),
              [&](const auto& m) { integrate::describe<std::decay_t<decltype(m)>>(r, &m); });
        r.method = integrate::method_name(options.method);
    }
    return results;
}

}  // namespace gyrostat
