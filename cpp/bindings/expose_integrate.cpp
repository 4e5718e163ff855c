// Bindings of the engine's entry points: Options, Stats, Result, solve, solve_ensemble.
// Translation of types only; the GIL is released around every integration, and Ctrl-C reaches
// the run through the engine's Control (polled at a bounded rate, results unchanged).
#include <Python.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>

#include "convert.hpp"
#include "expose.hpp"
#include "gyrostat/engine.hpp"
#include "gyrostat/measure.hpp"
#include "gyrostat/integrate/dense.hpp"
#include "gyrostat/numeric/lanes.hpp"
#include "gyrostat/model/affine_euler_avx2.hpp"
#include "../src/ensemble_batch.hpp"

namespace gyrostat::bindings {

namespace {

/// The engine's Control for a call from Python: polls Ctrl-C (the signal handlers run on the
/// main thread) and calls the optional progress callback with the fraction done.
class PythonControl {
public:
    PythonControl(py::object progress, double interval) : progress_(std::move(progress)) {
        control_.interval = interval;
        control_.poll = [this](double fraction) {
            py::gil_scoped_acquire gil;
            if (PyErr_CheckSignals() != 0) {  // KeyboardInterrupt: stop and keep what was computed
                PyErr_Clear();
                return false;
            }
            if (progress_.is_none()) return true;
            try {
                progress_(fraction);
            } catch (py::error_already_set& e) {
                error_ = std::make_unique<py::error_already_set>(std::move(e));
                return false;
            }
            return true;
        };
    }
    const integrate::Control* get() const { return &control_; }
    /// Re-raises an exception of the progress callback (with the GIL held).
    void rethrow() {
        if (error_) throw std::move(*error_);
    }

private:
    py::object progress_;
    integrate::Control control_;
    std::unique_ptr<py::error_already_set> error_;
};

/// The options of an ensemble whose Python event functions keep the first exception they raise:
/// the engine turns an exception into its member's status, but the user's own exception must
/// reach the caller as it was raised (solve_ensemble raises it once every member has finished).
class CallbackErrors {
public:
    integrate::Options watch(const integrate::Options& options) {
        integrate::Options watched = options;
        for (auto& e : watched.events) {
            if (e.quantity != integrate::Event::Quantity::Function || !e.function) continue;
            e.function = [this, inner = e.function](double t, const double* y, int dim) {
                try {
                    return inner(t, y, dim);
                } catch (py::error_already_set& error) {
                    py::gil_scoped_acquire gil;
                    if (!first_) first_ = std::make_unique<py::error_already_set>(error);
                    throw;
                }
            };
        }
        return watched;
    }
    /// Re-raises the first exception of an event function (with the GIL held).
    void rethrow() {
        if (first_) throw std::move(*first_);
    }

private:
    std::unique_ptr<py::error_already_set> first_;
};

std::vector<Eigen::VectorXd> initial_states(const py::object& y0s) {
    std::vector<Eigen::VectorXd> states;
    if (py::isinstance<py::array>(y0s) && py::array(y0s.cast<py::array>()).ndim() == 2) {
        const auto rows = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(y0s);
        if (!rows) throw py::value_error("y0s must hold numbers");
        const auto r = rows.unchecked<2>();
        states.reserve(static_cast<std::size_t>(r.shape(0)));
        for (py::ssize_t i = 0; i < r.shape(0); ++i) states.emplace_back(Eigen::Map<const Eigen::VectorXd>(r.data(i, 0), r.shape(1)));
        return states;
    }
    for (const py::handle& row : y0s) states.push_back(row.cast<Eigen::VectorXd>());
    return states;
}

}  // namespace

namespace {
/// The engine's sensitivity columns from Python's tuples: (component, None, None, 0, atol) or
/// (-1, model with the parameter + step, model with it − step, step, atol[, model with it + far_step
/// (an affine parameter) or None, far_step]).
std::vector<SensitivityColumn> sensitivity_columns(const std::vector<py::tuple>& given) {
    std::vector<SensitivityColumn> columns;
    for (const py::tuple& c : given) {
        if (c.size() != 5 && c.size() != 7 && c.size() != 8)
            throw std::invalid_argument("a sensitivity column is (component, plus, minus, step, atol[, far, far_step[, analytic]])");
        SensitivityColumn column;
        column.component = c[0].cast<int>();
        if (!c[1].is_none()) column.plus = &c[1].cast<const BoundModel&>().model;
        if (!c[2].is_none()) column.minus = &c[2].cast<const BoundModel&>().model;
        column.step = c[3].cast<double>();
        column.atol = c[4].cast<double>();
        if (c.size() == 7 && !c[5].is_none()) {
            column.far = &c[5].cast<const BoundModel&>().model;
            column.far_step = c[6].cast<double>();
        }
        if (c.size() == 8) column.analytic = c[7].cast<int>();
        columns.push_back(column);
    }
    return columns;
}
using Times = py::array_t<double, py::array::c_style | py::array::forcecast>;
/// The first `width` components of what a run's dense output keeps, at the times t: [time, width].
py::array_t<double> dense_at(const integrate::Result& r, const Times& t, int width) {
    if (!r.dense) throw py::value_error("this solution keeps no dense output: solve with dense_output=True");
    py::array_t<double> out({static_cast<py::ssize_t>(t.size()), static_cast<py::ssize_t>(width)});
    double* data = out.mutable_data();
    const double* times = t.data();
    {
        py::gil_scoped_release release;
        for (py::ssize_t i = 0; i < t.size(); ++i) {
            const Eigen::VectorXd y = (*r.dense)(times[i]);
            std::copy(y.data(), y.data() + width, data + i * width);
        }
    }
    return out;
}
/// (Result, d state [time, component, column], d outputs [time, output, column]).
py::tuple sensitivity_tuple(SensitivityRun run, std::size_t width) {
    const auto rows = static_cast<py::ssize_t>(run.result.t.size()), m = static_cast<py::ssize_t>(width);
    const auto n = static_cast<py::ssize_t>(run.result.dim), n_out = static_cast<py::ssize_t>(run.result.output_names().size());
    const bool whole = run.state.size() == static_cast<std::size_t>(rows * n * m);  // (a failed member has none)
    py::array_t<double> state({whole ? rows : 0, n, m}), outputs({whole ? rows : 0, n_out, m});
    if (whole) {
        std::copy(run.state.begin(), run.state.end(), state.mutable_data());
        std::copy(run.outputs.begin(), run.outputs.end(), outputs.mutable_data());
    }
    return py::make_tuple(std::move(run.result), state, outputs);
}
/// `call(control)` on one model without the GIL, under a progress control (PythonControl), the
/// Python torques' exceptions and the progress callable's raised after it.
template <class Call>
auto with_progress(const BoundModel& model, py::object progress, double interval, Call&& call) {
    PythonControl control(std::move(progress), interval);
    reset_python_torques(model.model);
    decltype(call(control.get())) made;
    {
        py::gil_scoped_release release;
        made = call(control.get());
    }
    control.rethrow();
    rethrow_python_torques(model.model);
    return made;
}
}  // namespace

void expose_integrate(py::module_& m) {
    // An Interruption that leaves the core (a user's torque that saw Ctrl-C, called outside a run:
    // Model.rhs, the torque itself) is the KeyboardInterrupt it came from.
    py::register_exception_translator([](std::exception_ptr error) {
        try {
            if (error) std::rethrow_exception(error);
        } catch (const integrate::Interruption&) {
            PyErr_SetNone(PyExc_KeyboardInterrupt);
        }
    });
    using integrate::Event;
    py::class_<Event>(m, "Event", "A zero crossing g(t, y) = quantity - value, located by the engine.")
        .def(py::init([](const std::string& quantity, int index, double value, int direction, int terminal,
                         std::string name, py::object function) {
                 Event e;
                 if (quantity == "state") e.quantity = Event::Quantity::State;
                 else if (quantity == "output") e.quantity = Event::Quantity::Output;
                 else if (quantity == "function") e.quantity = Event::Quantity::Function;
                 else throw py::value_error("event quantity '" + quantity + "': choose state, output or function");
                 e.index = index, e.value = value, e.direction = direction, e.terminal = terminal, e.name = std::move(name);
                 if (!function.is_none()) {
                     // the slow path: one call into Python (GIL held) per evaluation; an exception
                     // of the function propagates as it was raised, a value that is not a number
                     // is a ValueError naming the event (index: its place in the list given)
                     const std::string what = "event " + std::to_string(index) + " ('" + e.name + "') returned a value that";
                     e.function = [function, what](double t, const double* y, int dim) {
                         py::gil_scoped_acquire gil;
                         py::array_t<double> state(dim, y);
                         const py::object value = function(t, state);
                         return PyFloat_CheckExact(value.ptr()) ? PyFloat_AS_DOUBLE(value.ptr()) : scalar(value, what);
                     };
                 }
                 return e;
             }),
             py::arg("quantity"), py::arg("index"), py::arg("value"), py::arg("direction"), py::arg("terminal"),
             py::arg("name"), py::arg("function") = py::none())
        .def_readonly("index", &Event::index)
        .def_readonly("value", &Event::value)
        .def_readonly("direction", &Event::direction)
        .def_readonly("terminal", &Event::terminal)
        .def_readonly("name", &Event::name)
        .def_readonly("sample_interval", &Event::sample_interval,
                      "> 0: g evaluated only at step ends this far apart, a crossing placed where it is seen "
                      "(a costly watch; 0: every step, crossings located on the step's continuous extension).");

    using integrate::Options;
    py::class_<Options>(m, "Options", R"doc(Every integrator option with its default (the one place where defaults live).

:func:`gyrostat.solve` makes one from its keywords; pass one as ``options=`` to reuse it. The
attributes are the options (each one documented below).

Examples
--------
>>> import gyrostat
>>> options = gyrostat.Options()
>>> options.rtol = 1e-10
>>> options.rtol, options.method
(1e-10, 'dop853')
)doc")
        .def(py::init<>())
        .def("__copy__", [](const Options& o) { return Options(o); }, "A copy of every option (events included).")
        .def_property(
            "method", [](const Options& o) { return std::string(integrate::method_name(o.method)); },
            [](Options& o, const std::string& name) { o.method = integrate::method_from_name(name); },
            "The integrator (one of :data:`gyrostat.METHODS`, or ``\"auto\"``).\n\nExamples\n--------\n>>> import gyrostat\n>>> gyrostat.Options().method\n'dop853'\n")
        .def_readwrite("rtol", &Options::rtol, "Relative tolerance of the adaptive methods (1: dimensionless).\n\nExamples\n--------\n>>> import gyrostat\n>>> gyrostat.Options().rtol\n1e-08\n")
        .def_readwrite("atol", &Options::atol, "Absolute tolerance of the adaptive methods, in the units of each state component.\n\nExamples\n--------\n>>> import gyrostat\n>>> gyrostat.Options().atol\n1e-10\n")
        .def_property(
            "t_eval",
            [](const Options& o) { return py::array_t<double>(static_cast<py::ssize_t>(o.t_eval.size()), o.t_eval.data()); },
            [](Options& o, py::array_t<double, py::array::c_style | py::array::forcecast> t) {
                if (t.ndim() != 1) throw py::value_error("t_eval must be one-dimensional, got " + std::to_string(t.ndim()) + " dimensions");
                o.t_eval.assign(t.data(), t.data() + t.size());
            },
            "Output times, in s (empty: n_out equally spaced times).\n\nExamples\n--------\n>>> import gyrostat\n>>> gyrostat.Options().t_eval\narray([], dtype=float64)\n")
        .def_readwrite("n_out", &Options::n_out, "Number of equally spaced output times over the span when t_eval is empty.\n\nExamples\n--------\n>>> import gyrostat\n>>> gyrostat.Options().n_out\n1001\n")
        .def_readwrite("every_step", &Options::every_step, "Record every accepted step instead of the output times.\n\nExamples\n--------\n>>> import gyrostat\n>>> gyrostat.Options().every_step\nFalse\n")
        .def_readwrite("max_steps", &Options::max_steps, "Most steps a run may take before it stops with status max_steps_reached.\n\nExamples\n--------\n>>> import gyrostat\n>>> gyrostat.Options().max_steps\n1000000\n")
        .def_readwrite("first_step", &Options::first_step, "Size of the first step, in s (0: the method picks it).\n\nExamples\n--------\n>>> import gyrostat\n>>> gyrostat.Options().first_step\n0.0\n")
        .def_readwrite("max_step", &Options::max_step, "Largest step, in s (inf: no limit).\n\nExamples\n--------\n>>> import gyrostat\n>>> gyrostat.Options().max_step\ninf\n")
        .def_readwrite("events", &Options::events, "The engine's events of a run (made by :func:`gyrostat.solve` from :class:`gyrostat.events.Event`).\n\nExamples\n--------\n>>> import gyrostat\n>>> gyrostat.Options().events\n[]\n")
        .def_readwrite("dense_output", &Options::dense_output, "Keep each step's continuous extension, for ``solution(t)``.\n\nExamples\n--------\n>>> import gyrostat\n>>> gyrostat.Options().dense_output\nFalse\n")
        .def_readwrite("only_measured_outputs", &Options::only_measured_outputs, "Record only the outputs a run's error is measured on (:func:`gyrostat.accuracy.quantities`), NaN in the others: what the accuracy contract's probes and companions record.\n\nExamples\n--------\n>>> import gyrostat\n>>> gyrostat.Options().only_measured_outputs\nFalse\n")
        .def_readwrite("sensitivity_error_control", &Options::sensitivity_error_control, "A run with sensitivities: whether each sensitivity's error joins the state's in the step-size control (CVODES's errconS). False: the plain run's steps, the sensitivities' errors measured and reported but not held; True: held to the tolerances too, at the cost of more steps (dop853 and taylor; cvode_bdf holds them always).\n\nExamples\n--------\n>>> import gyrostat\n>>> gyrostat.Options().sensitivity_error_control\nFalse\n")
        .def_readwrite("step", &Options::step, "Fixed step of method ``splitting``, in s (0: none given).\n\nExamples\n--------\n>>> import gyrostat\n>>> gyrostat.Options().step\n0.0\n")
        .def_readwrite("splitting_order", &Options::splitting_order, "Order of method ``splitting``: 2, 4 or 6.\n\nExamples\n--------\n>>> import gyrostat\n>>> gyrostat.Options().splitting_order\n4\n")
        .def(
            "to_dict",
            [](const Options& o) {
                py::dict d;
                d["method"] = std::string(integrate::method_name(o.method)), d["rtol"] = o.rtol, d["atol"] = o.atol;
                d["n_out"] = o.n_out, d["every_step"] = o.every_step, d["max_steps"] = o.max_steps;
                d["first_step"] = o.first_step, d["max_step"] = o.max_step, d["dense_output"] = o.dense_output;
                d["step"] = o.step, d["splitting_order"] = o.splitting_order;
                d["sensitivity_error_control"] = o.sensitivity_error_control;
                return d;
            },
            "Every scalar option by name (not t_eval and events): what report.json records of a run."
            "\n\nExamples\n--------\n>>> import gyrostat\n>>> gyrostat.Options().to_dict()['rtol']\n1e-08\n")
        .def_static("check", &integrate::check_option, py::arg("name"), py::arg("value"),
                    "The engine's rule for one scalar option (rtol, atol, n_out, max_steps, first_step, max_step, step, "
                    "splitting_order): ValueError naming the value when it breaks it. The scene schema applies it too.\n\n"
                    "Parameters\n----------\nname : str\n    The option.\nvalue : float\n    Its value, in its unit."
                    "\n\nExamples\n--------\n>>> import gyrostat\n>>> gyrostat.Options.check('rtol', 1e-9)\n")
        .def(
            "validate", [](const Options& o, double t0, double t1) { integrate::validate(o, t0, t1); }, py::arg("t0"),
            py::arg("t1"), "The engine's checks of these options for a run over (t0, t1), without running: ValueError naming the value."
            "\n\nParameters\n----------\nt0, t1 : float\n    The span of the run, in s.\n\nExamples\n--------\n"
            ">>> import gyrostat\n>>> gyrostat.Options().validate(0.0, 10.0)\n")
        .def("__repr__", [](const Options& o) {
            return "Options(method='" + std::string(integrate::method_name(o.method)) + "', rtol=" + format_value(o.rtol) +
                   ", atol=" + format_value(o.atol) + ", n_out=" + std::to_string(o.n_out) + ", t_eval=<" +
                   std::to_string(o.t_eval.size()) + " times>, every_step=" + (o.every_step ? "True" : "False") +
                   ", max_steps=" + std::to_string(o.max_steps) + ", first_step=" + format_value(o.first_step) +
                   ", max_step=" + format_value(o.max_step) + ", events=<" + std::to_string(o.events.size()) +
                   ">, dense_output=" + (o.dense_output ? "True" : "False") + ", step=" + format_value(o.step) +
                   ", splitting_order=" + std::to_string(o.splitting_order) +
                   ", sensitivity_error_control=" + (o.sensitivity_error_control ? "True" : "False") + ")";
        });

    py::class_<integrate::Stats>(m, "Stats")
        .def_readonly("steps", &integrate::Stats::steps)
        .def_readonly("rhs_evals", &integrate::Stats::rhs_evals)
        .def_readonly("rejected_steps", &integrate::Stats::rejected_steps)
        .def_readonly("jacobian_evals", &integrate::Stats::jacobian_evals)
        .def_readonly("nonlinear_conv_failures", &integrate::Stats::nonlinear_conv_failures)
        .def_readonly("last_step", &integrate::Stats::last_step);

    using integrate::Result;
    py::class_<Result>(m, "Result", "A trajectory as the engine returns it; the arrays are views of its memory.")
        .def_readonly("method", &Result::method)
        .def_readonly("dim", &Result::dim)
        .def_property_readonly("state_names", &Result::state_names)
        .def_property_readonly("state_units", &Result::state_units)
        .def_property_readonly("state_descriptions", &Result::state_descriptions)
        .def_property_readonly("output_names", &Result::output_names)
        .def_property_readonly("output_units", &Result::output_units)
        .def_property_readonly("output_descriptions", &Result::output_descriptions)
        .def_property_readonly("output_conserved", &Result::output_conserved)
        .def_readonly("output_kept", &Result::output_kept)
        .def_readonly("options", &Result::options, "The options the run was made with (without t_eval and events).")
        .def_property_readonly("t",
                               [](py::object self) {
                                   const auto& r = self.cast<const Result&>();
                                   return py::array_t<double>(static_cast<py::ssize_t>(r.t.size()), r.t.data(), self);
                               })
        .def_property_readonly("y",
                               [](py::object self) {
                                   const auto& r = self.cast<const Result&>();
                                   return view(r.y, static_cast<py::ssize_t>(r.t.size()), r.dim, self);
                               })
        .def_property_readonly("outputs",
                               [](py::object self) {
                                   const auto& r = self.cast<const Result&>();
                                   return view(r.outputs, static_cast<py::ssize_t>(r.t.size()),
                                               static_cast<py::ssize_t>(r.output_names().size()), self);
                               })
        .def_readonly("event_names", &Result::event_names)
        .def_property_readonly("t_events",
                               [](const Result& r) {
                                   py::list out;
                                   for (const auto& t : r.t_events) out.append(py::array_t<double>(static_cast<py::ssize_t>(t.size()), t.data()));
                                   return out;
                               })
        .def_property_readonly("y_events",
                               [](const Result& r) {
                                   py::list out;
                                   for (const auto& y : r.y_events) {
                                       const py::ssize_t n = r.dim ? static_cast<py::ssize_t>(y.size()) / r.dim : 0;
                                       py::array_t<double> a({n, static_cast<py::ssize_t>(r.dim)});
                                       std::copy(y.begin(), y.end(), a.mutable_data());
                                       out.append(a);
                                   }
                                   return out;
                               })
        .def_readonly("terminal_event", &Result::terminal_event)
        .def_property_readonly("has_dense", [](const Result& r) { return static_cast<bool>(r.dense); })
        .def("dense",
             [](const Result& r, const Times& t) { return dense_at(r, t, r.dim); },
             py::arg("t"), "The solution at the times t (1-D), from each step's continuous extension.")
        .def("dense_whole",
             [](const Result& r, const Times& t) { return dense_at(r, t, r.dense ? r.dense->dim() : r.dim); },
             py::arg("t"),
             "Everything the dense output keeps at the times t: the state, then what a run integrated beside it "
             "(a run with sensitivities: each sensitivity's column after the state, [time, (1 + columns) * dim]).")
        .def_readonly("stats", &Result::stats)
        .def_readonly("methods_used", &Result::methods_used,
                      "The integrators that carried the run, in order of first use.")
        .def_property_readonly(
            "switches",
            [](const Result& r) {
                py::list switches;
                for (const auto& s : r.switches) switches.append(py::make_tuple(s.t, s.to, s.reason));
                return switches;
            },
            "Method 'auto': each switch as (t, method switched to, reason).")
        .def_property_readonly("status", [](const Result& r) { return integrate::status_name(r.status); })
        .def_readonly("message", &Result::message)
        .def_readonly("notes", &Result::notes, "What the run says about its own answer (information).")
        .def_readonly("warnings", &Result::warnings, "What the run doubts about its own answer (warned in Python).")
        .def_property_readonly(
            "remarked", [](const Result& r) { return !r.notes.empty() || !r.warnings.empty(); },
            "Whether the run left notes or warnings (one test, where reading them converts their strings).")
        .def_readonly("error_estimate", &Result::error_estimate,
                      "The run's own global error estimate relative to max|y_i| (splitting); NaN: none.")
        .def_readonly("t_last", &Result::t_last, "Where the run stopped: the last accepted time.")
        .def_property_readonly(
            "y_last", [](const Result& r) { return py::array_t<double>(static_cast<py::ssize_t>(r.y_last.size()), r.y_last.data()); },
            "The state at t_last.")
        .def_readonly("h_next", &Result::h_next, "The step size the integrator would try next (0: its own choice).")
        .def_property_readonly("success", &Result::success);

    m.def(
        "solve",
        [](const BoundModel& model, const Eigen::Ref<const Eigen::VectorXd>& y0, double t0, double t1, const Options& options,
           py::object progress, double interval) {
            return with_progress(model, std::move(progress), interval, [&](const integrate::Control* control) {
                return solve(model.model, t0, y0, t1, options, control);
            });
        },
        py::arg("model"), py::arg("y0"), py::arg("t0"), py::arg("t1"), py::arg("options"), py::arg("progress") = py::none(),
        py::arg("interval") = 0.1);

    py::class_<WindowRule>(m, "WindowRule", "The numbers a window estimate is made with (gyrostat/measure.hpp).")
        .def(py::init([](double fraction, std::size_t least_times, double safety, double floor, double gain,
                         long fit_steps) { return WindowRule{fraction, least_times, safety, floor, gain, fit_steps}; }),
             py::arg("fraction"), py::arg("least_times"), py::arg("safety"), py::arg("floor"), py::arg("gain"),
             py::arg("fit_steps"))
        .def_readonly("fraction", &WindowRule::fraction)
        .def_readonly("gain", &WindowRule::gain);
    // (values per quantity, largest k, grown, window's end, times compared, failure[, the companion: a whole
    // span's Result, which the contract may take as the answer; a window's statistics alone, ~0.5 µs less, and
    // the companion's step limit], whether k was fitted)
    auto window_tuple = [](WindowEstimate& w, bool with_companion, bool whole_span) -> py::tuple {
        if (!with_companion)
            return py::make_tuple(w.per_quantity, w.k, w.grown, w.window_end, w.times, w.failure, w.fitted);
        if (!whole_span)
            return py::make_tuple(w.per_quantity, w.k, w.grown, w.window_end, w.times, w.failure, w.companion.stats,
                                  w.companion_max_step, w.fitted);
        return py::make_tuple(w.per_quantity, w.k, w.grown, w.window_end, w.times, w.failure, std::move(w.companion),
                              w.companion_max_step, w.fitted);
    };
    m.def(
        "window_estimate",
        [window_tuple](const BoundModel& model, const Result& answer, double t0, const Eigen::Ref<const Eigen::VectorXd>& y0,
                       double t1, const Options& companion, const WindowRule& rule, py::object progress,
                       bool whole_span) -> py::object {
            WindowEstimate made = with_progress(model, std::move(progress), 0.1, [&](const integrate::Control* control) {
                return window_estimate(model.model, answer, t0, y0, t1, companion, rule, control, whole_span);
            });
            if (!made.made) return py::none();
            return window_tuple(made, true, whole_span);
        },
        py::arg("model"), py::arg("answer"), py::arg("t0"), py::arg("y0"), py::arg("t1"), py::arg("companion"),
        py::arg("rule"), py::arg("progress") = py::none(), py::arg("whole_span") = false,
        "The window estimate of a run (gyrostat/measure.hpp), or with ``whole_span`` its measurement over every "
        "output time: (each measured quantity's estimate, the largest growth exponent, whether grown to the "
        "horizon, the window's end, the times compared, why there is none or '', the companion's Result with "
        "``whole_span``, else its Stats, the largest step the companion was allowed (infinity: no limit; "
        "``companion_step_limit``)); None "
        "where the window cannot be measured here (too few output times in it, a separatrix crossed).");
    m.def(
        "solve_measured",
        [window_tuple](const BoundModel& model, const Eigen::Ref<const Eigen::VectorXd>& y0, double t0, double t1,
                       const Options& options, const Options& companion, const WindowRule& rule, py::object progress,
                       bool whole_span, bool measured_only) {
            MeasuredRun made = with_progress(model, std::move(progress), 0.1, [&](const integrate::Control* control) {
                return solve_measured(model.model, t0, y0, t1, options, companion, rule, control, whole_span,
                                      measured_only);
            });
            py::object estimate =
                made.estimate.made ? py::object(window_tuple(made.estimate, true, whole_span && !measured_only)) : py::none();
            return py::make_tuple(std::move(made.answer), std::move(estimate));
        },
        py::arg("model"), py::arg("y0"), py::arg("t0"), py::arg("t1"), py::arg("options"), py::arg("companion"),
        py::arg("rule"), py::arg("progress") = py::none(), py::arg("whole_span") = false,
        py::arg("measured_only") = false,
        "A run and its window estimate in one call (gyrostat/measure.hpp: solve_measured): (the Result, "
        "window_estimate's tuple or None where none is made here; with ``measured_only``, a whole span's "
        "companion records only the measured outputs and the tuple ends with its Stats).");
    m.def(
        "window_estimates",
        [window_tuple](const std::vector<const BoundModel*>& bound, const std::vector<const Result*>& answers, double t0,
                       const py::object& y0s, double t1, const Options& companion, const WindowRule& rule, int threads,
                       py::object progress, bool batch, bool whole_span) {
            const auto starts = initial_states(y0s);
            std::vector<const AnyModel*> models;
            for (const BoundModel* b : bound) models.push_back(&b->model), reset_python_torques(b->model);
            PythonControl control(std::move(progress), 0.1);
            std::vector<WindowEstimate> made;
            {
                py::gil_scoped_release release;
                made = window_estimates(models, answers, t0, starts, t1, companion, rule, threads, control.get(), batch,
                                        whole_span);
            }
            control.rethrow();
            for (const BoundModel* b : bound) rethrow_python_torques(b->model);
            py::list out;
            for (WindowEstimate& w : made)
                out.append(w.made ? py::object(window_tuple(w, true, whole_span)) : py::object(py::none()));
            return out;
        },
        py::arg("models"), py::arg("answers"), py::arg("t0"), py::arg("y0s"), py::arg("t1"), py::arg("companion"),
        py::arg("rule"), py::arg("threads") = 0, py::arg("progress") = py::none(), py::arg("batch") = true,
        py::arg("whole_span") = false,
        "Each member's window_estimate (or whole-span measurement), the companions run as one ensemble "
        "(gyrostat/measure.hpp): a list of window_estimate's tuples, None for a member left to the caller.");
    m.def(
        "companion_step_limit",
        [](const Result& answer, double t0, const std::optional<integrate::Stats>& first) {
            return companion_step_limit(answer, t0, first ? &*first : nullptr);
        },
        py::arg("answer"), py::arg("t0"), py::arg("first") = py::none(),
        "The largest step a companion measuring ``answer`` (a run from t0) may take: half the answer's mean step "
        "where it took fewer than 4 steps, or where ``first`` (a companion's Stats, run without the limit) took "
        "fewer than 1.05 times its steps for a Runge-Kutta pair of one order (its steps not its tolerance's); "
        "infinity otherwise (gyrostat/measure.hpp).");
    m.def(
        "window_from_differences",
        [window_tuple](const Eigen::Ref<const Eigen::MatrixXd>& apart, const std::vector<double>& times, double t0,
                       double horizon, const WindowRule& rule, bool to_horizon, std::optional<long> companion_steps) {
            WindowEstimate made = window_from_differences(apart, times, t0, horizon, rule, to_horizon,
                                                          companion_steps.value_or(std::numeric_limits<long>::max()));
            return window_tuple(made, false, false);
        },
        py::arg("apart"), py::arg("times"), py::arg("t0"), py::arg("horizon"), py::arg("rule"), py::arg("to_horizon") = true,
        py::arg("companion_steps") = py::none(),
        "A window estimate from the quantities' differences (quantities x times) at the window's times, as "
        "window_estimate's tuple without the companion; ``companion_steps``: the companion's steps over the window "
        "(fewer than ``rule``'s fit_steps: k = 1, not fitted; None: fitted).");
    m.def(
        "grow",
        [](double last, double half, double end, double middle, double far, double least) {
            const Grown g = grow(last, half, end, middle, far, least);
            return py::make_tuple(g.value, g.k);
        },
        py::arg("last"), py::arg("half"), py::arg("end"), py::arg("middle"), py::arg("far"), py::arg("least") = 1.0,
        "A difference's running maximum over a window (``last`` at its end, ``half`` at its middle output time) "
        "grown to the horizon as t^k, k fitted over the window's second half and kept within [least, 2]; "
        "(value, k). ``end``, ``middle``, ``far``: the distances from t0 of the window's end, its middle output "
        "time and the horizon.");

    m.def(
        "solve_sensitivities",
        [](const BoundModel& model, const std::vector<py::tuple>& given, const Eigen::VectorXd& y0, double t0, double t1,
           const Options& options, py::object progress, double interval) {
            const std::vector<SensitivityColumn> columns = sensitivity_columns(given);
            PythonControl control(std::move(progress), interval);
            reset_python_torques(model.model);
            SensitivityRun run;
            {
                py::gil_scoped_release release;
                run = solve_sensitivities(model.model, columns, t0, y0, t1, options, control.get());
            }
            control.rethrow();
            rethrow_python_torques(model.model);
            return sensitivity_tuple(std::move(run), columns.size());
        },
        py::arg("model"), py::arg("columns"), py::arg("y0"), py::arg("t0"), py::arg("t1"), py::arg("options"),
        py::arg("progress") = py::none(), py::arg("interval") = 0.1,
        "The run with its forward sensitivities (the variational equations by DOP853): (Result, d state / d column "
        "[time, component, column], d outputs / d column [time, output, column]). A column is (component, None, None, "
        "0, atol) for an initial component, (-1, model with the parameter + step, model with it - step, step, atol) for a "
        "parameter.");

    m.def(
        "solve_sensitivities_ensemble",
        [](const std::vector<const BoundModel*>& bound, const std::vector<std::vector<py::tuple>>& given, const py::object& y0s,
           double t0, double t1, const Options& options, int threads, py::object progress, double interval) {
            const auto starts = initial_states(y0s);
            std::vector<const AnyModel*> models;
            for (const BoundModel* b : bound) models.push_back(&b->model), reset_python_torques(b->model);
            std::vector<std::vector<SensitivityColumn>> columns;
            for (const auto& member : given) columns.push_back(sensitivity_columns(member));
            PythonControl control(std::move(progress), interval);
            std::vector<SensitivityRun> runs;
            {
                py::gil_scoped_release release;
                runs = solve_sensitivities_ensemble(models, columns, starts, t0, t1, options, threads, control.get());
            }
            control.rethrow();
            for (const BoundModel* b : bound) rethrow_python_torques(b->model);
            py::list made;
            for (std::size_t i = 0; i < runs.size(); ++i)
                made.append(sensitivity_tuple(std::move(runs[i]), columns[columns.size() == 1 ? 0 : i].size()));
            return made;
        },
        py::arg("models"), py::arg("columns"), py::arg("y0s"), py::arg("t0"), py::arg("t1"), py::arg("options"),
        py::arg("threads") = 0, py::arg("progress") = py::none(), py::arg("interval") = 0.1,
        "solve_sensitivities for every member on a pool of threads (models and column sets: one, or one per member); "
        "a list of (Result, d state, d outputs), a member with bad input with status invalid_input and empty arrays.");

    m.def(
        "solve_ensemble",
        [](const std::vector<const BoundModel*>& bound, const py::object& y0s, double t0, double t1, const Options& options,
           int threads, py::object progress, double interval, bool batch) {
            const auto starts = initial_states(y0s);
            std::vector<const AnyModel*> models;
            models.reserve(bound.size());
            for (const BoundModel* b : bound) models.push_back(&b->model), reset_python_torques(b->model);
            PythonControl control(std::move(progress), interval);
            CallbackErrors errors;
            const Options watched = errors.watch(options);
            std::vector<Result> results;
            {
                py::gil_scoped_release release;
                results = solve_ensemble(models, starts, t0, t1, watched, threads, control.get(), batch);
            }
            control.rethrow();
            errors.rethrow();
            for (const BoundModel* b : bound) rethrow_python_torques(b->model);
            return results;
        },
        py::arg("models"), py::arg("y0s"), py::arg("t0"), py::arg("t1"), py::arg("options"), py::arg("threads") = 0,
        py::arg("progress") = py::none(), py::arg("interval") = 0.1, py::arg("batch") = true);

    m.def(
        "summaries",
        [](const py::list& runs, const std::vector<std::string>& state_names, const std::vector<std::string>& output_names,
           bool extrema) {
            // Many results as columns (a sweep's summaries): one pass in C++ instead of a dozen
            // attribute look-ups per result in Python. A result's row of `final` (and of `min`,
            // `max`) is its last state and outputs, NaN when it has no output time or other names.
            const py::ssize_t n = static_cast<py::ssize_t>(runs.size());
            const std::size_t width = state_names.size() + output_names.size();
            py::list status, message, warning;
            py::array_t<long> steps(n), rhs_evals(n), rejected(n), jacobians(n), failures(n), rows(n), terminal(n);
            py::array_t<double> last_step(n), t_final(n);
            py::array_t<bool> named(n);
            const std::vector<py::ssize_t> shape{n, static_cast<py::ssize_t>(width)};
            py::array_t<double> final_row(shape), low(extrema ? shape : std::vector<py::ssize_t>{0, 0}),
                high(extrema ? shape : std::vector<py::ssize_t>{0, 0});
            constexpr double nan = std::numeric_limits<double>::quiet_NaN();
            for (py::ssize_t i = 0; i < n; ++i) {
                const Result& r = runs[i].cast<const Result&>();
                status.append(integrate::status_name(r.status));
                message.append(r.message);
                warning.append(r.warnings.empty() ? std::string() : r.warnings.front());
                steps.mutable_at(i) = r.stats.steps, rhs_evals.mutable_at(i) = r.stats.rhs_evals;
                rejected.mutable_at(i) = r.stats.rejected_steps, jacobians.mutable_at(i) = r.stats.jacobian_evals;
                failures.mutable_at(i) = r.stats.nonlinear_conv_failures, last_step.mutable_at(i) = r.stats.last_step;
                const std::size_t count = r.t.size();
                rows.mutable_at(i) = static_cast<long>(count), terminal.mutable_at(i) = r.terminal_event;
                t_final.mutable_at(i) = count ? r.t.back() : nan;
                const bool same = r.state_names() == state_names && r.output_names() == output_names;
                named.mutable_at(i) = same;
                double* out = final_row.mutable_data(i, 0);
                double* lo = extrema ? low.mutable_data(i, 0) : nullptr;
                double* hi = extrema ? high.mutable_data(i, 0) : nullptr;
                const std::size_t dim = state_names.size();
                for (std::size_t c = 0; c < width; ++c) {
                    if (!same || count == 0) {
                        out[c] = nan;
                        if (extrema) lo[c] = hi[c] = nan;
                        continue;
                    }
                    const auto at = [&](std::size_t k) {
                        return c < dim ? r.y[k * dim + c] : r.outputs[k * (width - dim) + (c - dim)];
                    };
                    out[c] = at(count - 1);
                    if (!extrema) continue;
                    double a = at(0), b = a;  // NaN-propagating, as NumPy's min and max
                    for (std::size_t k = 1; k < count; ++k) {
                        const double v = at(k);
                        if (std::isnan(v) || std::isnan(a)) a = b = nan;
                        else a = std::min(a, v), b = std::max(b, v);
                    }
                    lo[c] = a, hi[c] = b;
                }
            }
            py::dict d;
            d["status"] = status, d["message"] = message, d["warning"] = warning;
            d["steps"] = steps, d["rhs_evals"] = rhs_evals, d["rejected_steps"] = rejected;
            d["jacobian_evals"] = jacobians, d["nonlinear_conv_failures"] = failures, d["last_step"] = last_step;
            d["rows"] = rows, d["terminal_event"] = terminal, d["t_final"] = t_final, d["named"] = named;
            d["final"] = final_row, d["min"] = low, d["max"] = high;
            return d;
        },
        py::arg("results"), py::arg("state_names"), py::arg("output_names"), py::arg("extrema") = false,
        "Many Results as columns: status, message, first warning (lists), the statistics, rows, "
        "terminal_event, t_final, named (the names are these), final (the last state and outputs; "
        "NaN without rows or under other names) and, with extrema, their min and max over the rows.");

    m.def("methods", &integrate::method_names);
    m.def("method_descriptions", &integrate::method_descriptions,
          "One line per integrator, in the order of methods(): what it is and what it is for.");
    m.attr("simd_lanes") = lanes::width;
    m.attr("max_output_bytes") = integrate::kMaxOutputBytes;
    m.attr("simd_instruction_set") = lanes::instruction_set;
    m.def(
        "load_batches",
        [m](const std::string& directory, const std::string& asked) mutable {
            if (!asked.empty() && asked != "sse2" && asked != "avx2" && asked != "avx512")
                throw py::value_error("GYROSTAT_SIMD = '" + asked + "': choose sse2, avx2 or avx512 (or leave it unset)");
            const auto& form = ensemble_batch::load(directory, asked);
            m.attr("simd_lanes") = form.width;
            m.attr("simd_instruction_set") = form.instruction_set;
            return py::make_tuple(form.instruction_set, form.width);
        },
        py::arg("directory"), py::arg("asked") = "",
        "Installs the widest SIMD form of the ensemble batches the CPU runs, from the plugins in "
        "``directory`` (or the one ``asked`` names: sse2, avx2, avx512); returns (instruction set, lanes).");
    m.attr("taylor_kernel") = model::affine_euler_avx2_available() ? "avx2+fma" : "portable";
}

}  // namespace gyrostat::bindings
