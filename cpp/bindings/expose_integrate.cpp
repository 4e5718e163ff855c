#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <variant>

#include "convert.hpp"
#include "expose.hpp"
#include "gyrostat/ensemble.hpp"
#include "gyrostat/model/averaged.hpp"
#include "gyrostat/model/gyrostat.hpp"
#include "gyrostat/model/moving_mass.hpp"

namespace py = pybind11;

namespace gyrostat::bindings {

namespace {

/// A model as Python holds it: the full gyrostat (without or with the attitude quaternion), the
/// averaged symmetric system, or the explicit moving-mass model.
struct CoreModel {
    std::variant<model::Gyrostat<false>, model::Gyrostat<true>, model::AveragedSymmetric, model::MovingMass> system;
    int dim() const {
        return std::visit([](const auto& s) { return std::decay_t<decltype(s)>::dim; }, system);
    }
};

CoreModel make_full(const Body& body, const py::sequence& torque_objects, bool attitude) {
    TorqueSet set(torques_from(torque_objects));
    if (attitude) return {model::Gyrostat<true>(body, set)};
    return {model::Gyrostat<false>(body, set)};
}

CoreModel make_averaged(const Body& body, const py::sequence& torque_objects) {
    return {model::AveragedSymmetric(body, TorqueSet(torques_from(torque_objects)))};
}

CoreModel make_moving_mass(const Body& body, double mass, double arm, double frequency, double damping,
                           const py::sequence& torque_objects) {
    return {model::MovingMass(body, mass, arm, frequency, damping, TorqueSet(torques_from(torque_objects)))};
}

const model::AveragedSymmetric& as_averaged(const CoreModel& m) {
    if (const auto* a = std::get_if<model::AveragedSymmetric>(&m.system)) return *a;
    throw std::invalid_argument("this is not an averaged model");
}

integrate::Result solve_model(const CoreModel& model, const Eigen::VectorXd& y0, double t0, double t1,
                              const integrate::Options& o) {
    return std::visit(
        [&](const auto& system) {
            using System = std::decay_t<decltype(system)>;
            return integrate::solve(system, t0, to_state<System>(y0), t1, o);
        },
        model.system);
}

template <class System>
std::vector<integrate::Result> ensemble_of(const std::vector<const CoreModel*>& models, const Eigen::MatrixXd& y0s,
                                           double t0, double t1, const integrate::Options& o, int threads) {
    std::vector<System> systems;
    for (const CoreModel* m : models) systems.push_back(std::get<System>(m->system));
    std::vector<typename System::State> starts;
    for (Eigen::Index i = 0; i < y0s.rows(); ++i) starts.push_back(to_state<System>(y0s.row(i).transpose()));
    return solve_ensemble(systems, starts, t0, t1, o, threads);
}

}  // namespace

void expose_integrate(py::module_& m) {
    py::class_<CoreModel>(m, "CoreModel")
        .def_property_readonly("dim", &CoreModel::dim)
        .def_property_readonly("attitude", [](const CoreModel& fm) { return fm.system.index() == 1; })
        .def("fast_frequency", [](const CoreModel& fm, double r) { return as_averaged(fm).fast_frequency(r); },
             py::arg("r"))
        .def("slow_rate",
             [](const CoreModel& fm, double t, const Eigen::Vector2d& y) { return as_averaged(fm).slow_rate(t, y); },
             py::arg("t"), py::arg("y"))
        .def("quasi_static_state",
             [](const CoreModel& fm, const Vec3& omega) -> Eigen::VectorXd {
                 if (const auto* mm = std::get_if<model::MovingMass>(&fm.system)) return mm->quasi_static_state(omega);
                 throw std::invalid_argument("this is not a moving-mass model");
             },
             py::arg("omega"))
        .def("rhs", [](const CoreModel& fm, double t, const Eigen::VectorXd& y) { return variant_rhs(fm.system, t, y); },
             py::arg("t"), py::arg("y"));

    py::class_<integrate::Stats>(m, "Stats")
        .def_readonly("steps", &integrate::Stats::steps)
        .def_readonly("rhs_evals", &integrate::Stats::rhs_evals)
        .def_readonly("rejected_steps", &integrate::Stats::rejected_steps)
        .def_readonly("jacobian_evals", &integrate::Stats::jacobian_evals)
        .def_readonly("nonlinear_conv_failures", &integrate::Stats::nonlinear_conv_failures)
        .def_readonly("last_step", &integrate::Stats::last_step);

    py::class_<integrate::Result>(m, "Result")
        .def_readonly("method", &integrate::Result::method)
        .def_property_readonly("t", [](const integrate::Result& r) { return as_array(r.t, r.t.size(), 1).attr("ravel")(); })
        .def_property_readonly("y", [](const integrate::Result& r) { return as_array(r.y, r.t.size(), r.dim); })
        .def_readonly("invariant_names", &integrate::Result::invariant_names)
        .def_property_readonly("invariants", [](const integrate::Result& r) {
            return as_array(r.invariants, r.t.size(), r.invariant_names.size());
        })
        .def_readonly("stats", &integrate::Result::stats)
        .def_property_readonly("status", [](const integrate::Result& r) { return integrate::status_name(r.status); })
        .def_readonly("message", &integrate::Result::message)
        .def_property_readonly("success", &integrate::Result::success);

    m.def("full_model", &make_full, py::arg("body"), py::arg("torques"), py::arg("attitude") = false);
    m.def("averaged_model", &make_averaged, py::arg("body"), py::arg("torques"));
    m.def("moving_mass_model", &make_moving_mass, py::arg("body"), py::arg("mass"), py::arg("arm"),
          py::arg("frequency"), py::arg("damping"), py::arg("torques"));

    m.def(
        "solve",
        [](const CoreModel& model, const Eigen::VectorXd& y0, double t0, double t1, const std::string& method, double rtol,
           double atol, std::vector<double> t_eval, bool every_step, long max_steps, double first_step, double max_step) {
            const auto o = make_options(method, rtol, atol, std::move(t_eval), every_step, max_steps, first_step, max_step);
            py::gil_scoped_release release;
            return solve_model(model, y0, t0, t1, o);
        },
        py::arg("model"), py::arg("y0"), py::arg("t0"), py::arg("t1"), py::arg("method"), py::arg("rtol"),
        py::arg("atol"), py::arg("t_eval"), py::arg("every_step"), py::arg("max_steps"), py::arg("first_step"),
        py::arg("max_step"));

    m.def(
        "solve_ensemble",
        [](const std::vector<const CoreModel*>& models, const Eigen::MatrixXd& y0s, double t0, double t1,
           const std::string& method, double rtol, double atol, std::vector<double> t_eval, bool every_step,
           long max_steps, double first_step, double max_step, int threads) {
            if (models.empty()) throw std::invalid_argument("solve_ensemble: no model given");
            const std::size_t kind = models.front()->system.index();
            for (const CoreModel* fm : models)
                if (fm->system.index() != kind)
                    throw std::invalid_argument("solve_ensemble: all models must be of one kind (and attitude on or off for all)");
            const auto o = make_options(method, rtol, atol, std::move(t_eval), every_step, max_steps, first_step, max_step);
            py::gil_scoped_release release;
            switch (kind) {
                case 0: return ensemble_of<model::Gyrostat<false>>(models, y0s, t0, t1, o, threads);
                case 1: return ensemble_of<model::Gyrostat<true>>(models, y0s, t0, t1, o, threads);
                case 2: return ensemble_of<model::AveragedSymmetric>(models, y0s, t0, t1, o, threads);
                default: return ensemble_of<model::MovingMass>(models, y0s, t0, t1, o, threads);
            }
        },
        py::arg("models"), py::arg("y0s"), py::arg("t0"), py::arg("t1"), py::arg("method"), py::arg("rtol"),
        py::arg("atol"), py::arg("t_eval"), py::arg("every_step"), py::arg("max_steps"), py::arg("first_step"),
        py::arg("max_step"), py::arg("threads"));

    m.def("methods", &integrate::method_names);
}

}  // namespace gyrostat::bindings
