// Bindings of paper 004's model: the magnitude law, the gyrostat under the orthogonal servo
// torque, its solve and ensemble (GIL released). Translation of types only.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <limits>
#include <variant>

#include "convert.hpp"
#include "expose.hpp"
#include "gyrostat/ensemble.hpp"
#include "gyrostat/model/orthogonal.hpp"

namespace gyrostat::bindings {

namespace {

using Law = model::MagnitudeLaw;

struct OrthogonalCore {
    std::variant<model::OrthogonalTorque<false>, model::OrthogonalTorque<true>> system;
    int dim() const {
        return std::visit([](const auto& s) { return std::decay_t<decltype(s)>::dim; }, system);
    }
};

}  // namespace

void expose_orthogonal(py::module_& m) {
    py::class_<Law>(m, "MagnitudeLaw", "The magnitude L(t) of paper 004's servo torque, evaluated in C++.")
        .def_static("constant", &Law::constant, py::arg("value"))
        .def_static("polynomial", &Law::polynomial, py::arg("coefficients"))
        .def_static("harmonic", &Law::harmonic, py::arg("mean"), py::arg("amplitudes"), py::arg("frequencies"),
                    py::arg("phases"))
        .def_static("tabulated", &Law::tabulated, py::arg("times"), py::arg("values"), py::arg("cubic") = false)
        .def_property_readonly("kind",
                               [](const Law& l) {
                                   switch (l.kind()) {
                                       case Law::Kind::Constant: return "constant";
                                       case Law::Kind::Polynomial: return "polynomial";
                                       case Law::Kind::Harmonic: return "harmonic";
                                       default: return "tabulated";
                                   }
                               })
        .def("__call__", [](const Law& l, double t) { return l(t); }, py::arg("t"))
        .def("values",
             [](const Law& l, const Eigen::VectorXd& t) {
                 Eigen::VectorXd v(t.size());
                 for (Eigen::Index i = 0; i < t.size(); ++i) v[i] = l(t[i]);
                 return v;
             },
             py::arg("t"));

    py::class_<OrthogonalCore>(m, "OrthogonalCore")
        .def_property_readonly("dim", &OrthogonalCore::dim)
        .def("rhs", [](const OrthogonalCore& c, double t, const Eigen::VectorXd& y) { return variant_rhs(c.system, t, y); },
             py::arg("t"), py::arg("y"))
        .def("tau_rate",
             [](const OrthogonalCore& c, const Eigen::VectorXd& t, const Eigen::MatrixXd& omega) {
                 if (omega.cols() != 3 || omega.rows() != t.size())
                     throw std::invalid_argument("tau_rate: omega must be (n, 3) with n = len(t)");
                 return std::visit(
                     [&](const auto& s) -> Eigen::VectorXd {
                         Eigen::VectorXd g(t.size());
                         for (Eigen::Index i = 0; i < t.size(); ++i) g[i] = s.tau_rate(t[i], omega.row(i).transpose());
                         return g;
                     },
                     c.system);
             },
             py::arg("t"), py::arg("omega"));

    m.def(
        "orthogonal_model",
        [](const Body& body, const Law& law, const py::sequence& torques, bool attitude, double eta, bool smooth) {
            TorqueSet set(torques_from(torques));
            if (attitude) return OrthogonalCore{model::OrthogonalTorque<true>(body, law, set, eta, smooth)};
            return OrthogonalCore{model::OrthogonalTorque<false>(body, law, set, eta, smooth)};
        },
        py::arg("body"), py::arg("law"), py::arg("torques"), py::arg("attitude"), py::arg("eta"),
        py::arg("smooth") = false);

    m.def(
        "solve_orthogonal",
        [](const OrthogonalCore& core, const Eigen::VectorXd& y0, double t0, double t1, const std::string& method,
           double rtol, double atol, std::vector<double> t_eval, bool every_step, long max_steps, double first_step,
           double max_step) {
            const auto o = make_options(method, rtol, atol, std::move(t_eval), every_step, max_steps, first_step, max_step);
            py::gil_scoped_release release;
            return std::visit(
                [&](const auto& s) {
                    using S = std::decay_t<decltype(s)>;
                    return integrate::solve(s, t0, to_state<S>(y0), t1, o);
                },
                core.system);
        },
        py::arg("model"), py::arg("y0"), py::arg("t0"), py::arg("t1"), py::arg("method"), py::arg("rtol"),
        py::arg("atol"), py::arg("t_eval"), py::arg("every_step"), py::arg("max_steps"), py::arg("first_step"),
        py::arg("max_step"));

    m.def(
        "solve_orthogonal_ensemble",
        [](const OrthogonalCore& core, const Eigen::MatrixXd& y0s, double t0, double t1, const std::string& method,
           double rtol, double atol, std::vector<double> t_eval, long max_steps, int threads) {
            const auto o = make_options(method, rtol, atol, std::move(t_eval), false, max_steps, 0.0,
                                   std::numeric_limits<double>::infinity());
            py::gil_scoped_release release;
            return std::visit(
                [&](const auto& s) {
                    using S = std::decay_t<decltype(s)>;
                    std::vector<typename S::State> starts;
                    for (Eigen::Index i = 0; i < y0s.rows(); ++i) starts.push_back(to_state<S>(y0s.row(i).transpose()));
                    return solve_ensemble(std::vector<S>{s}, starts, t0, t1, o, threads);
                },
                core.system);
        },
        py::arg("model"), py::arg("y0s"), py::arg("t0"), py::arg("t1"), py::arg("method"), py::arg("rtol"),
        py::arg("atol"), py::arg("t_eval"), py::arg("max_steps"), py::arg("threads"));
}

}  // namespace gyrostat::bindings
