// Bindings of the model of every family as one class `Model` (the engine's AnyModel), with one
// constructor function per family and the few family-specific queries. Translation only.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "convert.hpp"
#include "expose.hpp"
#include "gyrostat/engine.hpp"

namespace gyrostat::bindings {

namespace {

using Rows = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// The model held, when it is of type T; otherwise a ValueError naming both families.
template <class T>
const T& as(const AnyModel& model, const char* needed) {
    if (const auto* m = std::get_if<T>(&model)) return *m;
    throw py::value_error(std::string("this is a '") + family(model) + "' model; " + needed);
}

template <class T>
const T* either(const AnyModel& model) {
    return std::get_if<T>(&model);
}

}  // namespace

void expose_models(py::module_& m) {
    py::class_<BoundModel>(m, "Model", "A model of any family, as the engine integrates it.")
        .def_property_readonly("family", [](const BoundModel& b) { return std::string(family(b.model)); })
        .def_property_readonly("dim", [](const BoundModel& b) { return dim(b.model); })
        .def_property_readonly("state_names", [](const BoundModel& b) { return state_names(b.model); })
        .def_property_readonly(
            "affine_in",
            [](const BoundModel& b) {
                return std::visit([](const auto& x) { return affine_in<std::decay_t<decltype(x)>>(); }, b.model);
            },
            "The model's own numbers its right-hand side is affine in (sensitivities take their derivative by a "
            "one-sided difference, exact to rounding).")
        .def_property_readonly(
            "analytic_in",
            [](const BoundModel& b) {
                return std::visit([](const auto& x) { return model::system::analytic_in<std::decay_t<decltype(x)>>(); },
                                  b.model);
            },
            "The model's own numbers whose derivative of the right-hand side it gives in closed form (sensitivities "
            "take it instead of a difference quotient).")
        .def_property_readonly("output_names", [](const BoundModel& b) { return output_names(b.model); })
        .def_property_readonly(
            "quantities",
            [](const BoundModel& b) {
                const integrate::Result r = described(b.model);
                py::list all;
                auto add = [&](const std::string& name, const std::string& unit, const std::string& description,
                               const char* role, bool conserved) {
                    py::dict q;
                    q["name"] = name, q["unit"] = unit, q["description"] = description, q["role"] = role;
                    q["conserved"] = conserved;
                    all.append(q);
                };
                for (std::size_t i = 0; i < r.state_names().size(); ++i)
                    add(r.state_names()[i], r.state_units()[i], r.state_descriptions()[i], "state", false);
                for (std::size_t i = 0; i < r.output_names().size(); ++i)
                    add(r.output_names()[i], r.output_units()[i], r.output_descriptions()[i], "output", r.output_conserved()[i]);
                return all;
            },
            "What the model declares about its state and outputs: name, unit, description, role ('state' or "
            "'output') and whether it is conserved without perturbation.")
        .def_property_readonly(
            "measured_quantities",
            [](const BoundModel& b) {
                py::list all;
                for (const MeasuredQuantity& q : measured_quantities(b.model))
                    all.append(py::make_tuple(q.name, q.output ? "output" : "state", q.columns));
                return all;
            },
            "What a run's error is measured on (the accuracy contract): (name, role ('state' or 'output'), "
            "columns) per quantity; a vector's components (omega, quaternion, ...) as one quantity, labels left out.")
        .def("rhs", [](const BoundModel& b, double t, const Eigen::VectorXd& y) { return rhs(b.model, t, y); }, py::arg("t"),
             py::arg("y"))
        .def("initial_state", [](const BoundModel& b, const Eigen::VectorXd& y) { return initial_state(b.model, y); },
             py::arg("given"))
        .def("measured_differences",
             [](const BoundModel& b, const integrate::Result& reference, const integrate::Result& other,
                const py::object& reference_rows, const py::object& other_rows) {
                 return measured_differences(b.model, reference, other, row_numbers(reference_rows, "reference_rows"),
                                             row_numbers(other_rows, "other_rows"));
             },
             py::arg("reference"), py::arg("other"), py::arg("reference_rows") = py::none(),
             py::arg("other_rows") = py::none(),
             "How far two runs are apart on each measured quantity (rows: measured_quantities) at each pair of rows "
             "(empty: every row), relative to the quantity's largest size in the reference.")
        .def("first_crossing",
             [](const BoundModel& b, const integrate::Result& run, double after) { return first_crossing(b.model, run, after); },
             py::arg("run"), py::arg("after"),
             "The first output time of the run past `after` (in its direction) at which its state has crossed a separatrix "
             "(separatrix's sign changed since the output before); NaN when none, or when the model declares none.")
        .def("separatrix", [](const BoundModel& b, const Eigen::MatrixXd& states) { return separatrix(b.model, states); },
             py::arg("states"),
             "The signed distance to a separatrix of the unperturbed motion at each state (rows): a change of sign "
             "along a run is a crossing; NaN where the model declares none.")
        .def("principal_states",
             [](const BoundModel& b, const Eigen::MatrixXd& states) { return principal_states(b.model, states); },
             py::arg("states"), "States (rows) in the user's body frame, written in the model's principal axes.")
        .def("full_state",
             [](const BoundModel& b, const Eigen::VectorXd& y, double phase) { return full_state(b.model, y, phase); },
             py::arg("slow"), py::arg("phase") = 0.0)
        .def("outputs_at",
             [](const BoundModel& b, double t, const Eigen::VectorXd& y) { return outputs_at(b.model, t, y); },
             py::arg("t"), py::arg("y"))
        // the two above over many rows at once (the model ladder maps a run of the top rung down)
        .def("initial_states",
             [](const BoundModel& b, const Eigen::Ref<const Rows>& given) {
                 Rows out(given.rows(), dim(b.model));
                 for (Eigen::Index i = 0; i < given.rows(); ++i)
                     out.row(i) = initial_state(b.model, given.row(i).transpose()).transpose();
                 return out;
             },
             py::arg("given"), "initial_state of every row of ``given`` (n, k): (n, dim).")
        .def("outputs_along",
             [](const BoundModel& b, const Eigen::Ref<const Eigen::VectorXd>& t, const Eigen::Ref<const Rows>& y) {
                 if (t.size() != y.rows())
                     throw py::value_error("outputs_along: " + std::to_string(t.size()) + " times for " +
                                           std::to_string(y.rows()) + " states");
                 Rows out(y.rows(), static_cast<Eigen::Index>(output_names(b.model).size()));
                 for (Eigen::Index i = 0; i < y.rows(); ++i) out.row(i) = outputs_at(b.model, t[i], y.row(i).transpose()).transpose();
                 return out;
             },
             py::arg("t"), py::arg("y"), "outputs_at at every time t[i] (n,) and state y[i] (n, dim): (n, outputs).")
        // the model ladder: on the top rung, whether this (lower) model's watched assumptions hold again
        .def("watch_event",
             [](const BoundModel& b, const std::vector<int>& outputs, const std::vector<double>& back,
                const std::vector<double>& limit, std::string name, int direction, int terminal, double sample_interval) {
                 const auto n = static_cast<int>(output_names(b.model).size());
                 if (outputs.empty() || back.size() != outputs.size() || limit.size() != outputs.size())
                     throw py::value_error("watch_event: give one back and one limit per watched output (at least one)");
                 for (std::size_t i = 0; i < outputs.size(); ++i) {
                     if (outputs[i] < 0 || outputs[i] >= n)
                         throw py::value_error("watch_event: output " + std::to_string(outputs[i]) +
                                               " does not exist (the model records " + std::to_string(n) + ")");
                     if (!(limit[i] != back[i]) || !std::isfinite(limit[i]) || !std::isfinite(back[i]))
                         throw py::value_error("watch_event: output " + std::to_string(outputs[i]) +
                                               ": back and limit must be finite and differ");
                 }
                 if (!(sample_interval >= 0.0) || !std::isfinite(sample_interval))
                     throw py::value_error("watch_event: sample_interval must be finite and >= 0, got " +
                                           format_value(sample_interval));
                 integrate::Event e;
                 e.quantity = integrate::Event::Quantity::Function;
                 e.direction = direction, e.terminal = terminal, e.name = std::move(name);
                 e.sample_interval = sample_interval;
                 // g(t, y) = max_i (o_i - back_i) / (limit_i - back_i), o the outputs of this model at the
                 // top's state y mapped down (outputs_at projects it, as initial_state does): 0 where every watched output is back below its
                 // `back`, 1 at a limit; 1 where an output is not finite (no margin to come back down on)
                 e.function = [model = b.model, outputs, back, limit](double t, const double* y, int dim) {
                     const Eigen::VectorXd values = outputs_at(model, t, Eigen::Map<const Eigen::VectorXd>(y, dim));
                     double worst = -std::numeric_limits<double>::infinity();
                     for (std::size_t i = 0; i < outputs.size(); ++i) {
                         const double ratio = (values[outputs[i]] - back[i]) / (limit[i] - back[i]);
                         if (!std::isfinite(ratio)) return 1.0;
                         worst = std::max(worst, ratio);
                     }
                     return worst;
                 };
                 return e;
             },
             py::arg("outputs"), py::arg("back"), py::arg("limit"), py::arg("name"), py::arg("direction") = -1,
             py::arg("terminal") = 1, py::arg("sample_interval") = 0.0,
             "An engine event for a run of a model above this one on the ladder, evaluated in C++ at every step "
             "(or, with ``sample_interval`` > 0, at step ends that far apart in t, the crossing placed at the step end "
             "where it is seen): "
             "g(t, y) = the largest (o_i - back_i) / (limit_i - back_i) of this model's outputs o = outputs_at(t, y) "
             "(y mapped down as initial_state maps it) at the indices ``outputs`` (1 where one is not finite). It falls through 0 where every "
             "watched output is back below its ``back``.")
        // the gyrostat on an orbit
        .def_property_readonly("orbit",
                               [](const BoundModel& b) -> py::object {
                                   if (const auto* s = either<model::OrbitingGyrostat>(b.model)) return py::cast(s->orbit());
                                   return py::none();
                               },
                               "The model's orbit (gyrostat.Orbit), or None.")
        .def("from_orbit_frame",
             [](const BoundModel& b, double t, const Eigen::Vector4d& q_ob, const Vec3& omega_rel) -> Eigen::VectorXd {
                 return as<model::OrbitingGyrostat>(b.model, "from_orbit_frame is for a model with an orbit (orbit=...)")
                     .from_orbit_frame(t, q_ob, omega_rel);
             },
             py::arg("t"), py::arg("attitude"), py::arg("omega"),
             "The state (omega, q) at t of a body with this attitude (body to orbit frame) and this angular velocity "
             "relative to the orbit frame (body axes).")
        // averaged symmetric system
        .def("fast_frequency",
             [](const BoundModel& b, double r) {
                 return as<model::AveragedSymmetric>(b.model, "fast_frequency is for the averaged model").fast_frequency(r);
             },
             py::arg("r"))
        .def("exact_reduction",
             [](const BoundModel& b) {
                 return as<model::AveragedSymmetric>(b.model, "exact_reduction is for the averaged model").exact_reduction();
             },
             "Whether the (a, r) system is exact (a symmetric body without rotor under axisymmetric torques).")
        .def("slow_rate",
             [](const BoundModel& b, double t, const Eigen::Vector2d& y) {
                 return as<model::AveragedSymmetric>(b.model, "slow_rate is for the averaged model").slow_rate(t, y);
             },
             py::arg("t"), py::arg("y"))
        // explicit moving mass
        .def("quasi_static_state",
             [](const BoundModel& b, const Vec3& omega) -> Eigen::VectorXd {
                 return as<model::MovingMass>(b.model, "quasi_static_state is for the moving-mass model").quasi_static_state(omega);
             },
             py::arg("omega"))
        // averaged top
        .def("rate",
             [](const BoundModel& b, double t) {
                 return as<model::LagrangeAveraged>(b.model, "rate is for the averaged Lagrange top").rate(t);
             },
             py::arg("t"))
        // orthogonal servo torque
        .def("tau_rate",
             [](const BoundModel& b, const Eigen::VectorXd& t, const Eigen::MatrixXd& omega) {
                 if (omega.cols() != 3 || omega.rows() != t.size())
                     throw py::value_error("tau_rate: omega must be (n, 3) with n = len(t)");
                 Eigen::VectorXd g(t.size());
                 auto fill = [&](const auto& s) {
                     for (Eigen::Index i = 0; i < t.size(); ++i) g[i] = s.tau_rate(t[i], omega.row(i).transpose());
                 };
                 if (const auto* s = either<model::OrthogonalTorque<false>>(b.model)) fill(*s);
                 else fill(as<model::OrthogonalTorque<true>>(b.model, "tau_rate is for the orthogonal-torque model"));
                 return g;
             },
             py::arg("t"), py::arg("omega"));

    m.def(
        "gyrostat_model",
        [](const Body& body, const py::iterable& torques, bool attitude, const py::object& orbit) -> BoundModel {
            TorqueSet set(torques_from(torques));
            std::optional<torque::CircularOrbit> given;
            if (!orbit.is_none()) given = orbit.cast<const torque::CircularOrbit&>();
            const std::optional<torque::CircularOrbit> shared = set.common_orbit(given);
            if (given && !attitude)
                throw py::value_error("Model(orbit=...) needs the attitude (attitude=True): the orbit frame's outputs "
                                      "and the orbit torques read it");
            if (attitude && shared) return {model::OrbitingGyrostat(body, set, *shared)};
            if (attitude) return {model::Gyrostat<true>(body, set)};
            return {model::Gyrostat<false>(body, set)};
        },
        py::arg("body"), py::arg("torques"), py::arg("attitude"), py::arg("orbit") = py::none());
    m.def(
        "averaged_model",
        [](const Body& body, const py::iterable& torques) -> BoundModel {
            return {model::AveragedSymmetric(body, TorqueSet(torques_from(torques)))};
        },
        py::arg("body"), py::arg("torques"));
    m.def(
        "averaged_triaxial_model",
        [](const Body& body, const py::iterable& torques) -> BoundModel {
            return {model::AveragedTriaxial(body, TorqueSet(torques_from(torques)))};
        },
        py::arg("body"), py::arg("torques"));
    m.def(
        "moving_mass_model",
        [](const Body& body, const py::object& mass, const py::object& arm, const py::object& frequency,
           const py::object& damping, const py::iterable& torques) -> BoundModel {
            return {model::MovingMass(body, scalar(mass, "MovingMassModel: mass"), scalar(arm, "MovingMassModel: arm"),
                                      scalar(frequency, "MovingMassModel: frequency"),
                                      scalar(damping, "MovingMassModel: damping"), TorqueSet(torques_from(torques)))};
        },
        py::arg("body"), py::arg("mass"), py::arg("arm"), py::arg("frequency"), py::arg("damping"), py::arg("torques"));
    m.def(
        "lagrange_top_model",
        [](const Body& body, double mu, const py::iterable& torques) -> BoundModel {
            return {model::LagrangeTop(body, mu, TorqueSet(torques_from(torques)))};
        },
        py::arg("body"), py::arg("mu"), py::arg("torques"));
    m.def(
        "lagrange_averaged_model",
        [](const Body& body, double mu, const py::iterable& torques) -> BoundModel {
            return {model::LagrangeAveraged(body, mu, TorqueSet(torques_from(torques)))};
        },
        py::arg("body"), py::arg("mu"), py::arg("torques"));
    m.def(
        "orthogonal_model",
        [](const Body& body, const model::MagnitudeLaw& law, const py::iterable& torques, bool attitude, double eta,
           bool smooth) -> BoundModel {
            TorqueSet set(torques_from(torques));
            if (attitude) return {model::OrthogonalTorque<true>(body, law, set, eta, smooth)};
            return {model::OrthogonalTorque<false>(body, law, set, eta, smooth)};
        },
        py::arg("body"), py::arg("law"), py::arg("torques"), py::arg("attitude"), py::arg("eta"), py::arg("smooth"));
    m.def(
        "torque_free_model",
        [](const Body& body, bool attitude) -> BoundModel {
            if (attitude) return {model::TorqueFreeAttitude(body)};
            return {model::TorqueFree(body)};
        },
        py::arg("body"), py::arg("attitude") = false);
}

}  // namespace gyrostat::bindings
