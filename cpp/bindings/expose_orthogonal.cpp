// Bindings of paper 004's magnitude law L(t) (the model itself is bound in expose_models.cpp).
// Translation of types only.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "convert.hpp"
#include "expose.hpp"
#include "gyrostat/model/orthogonal.hpp"

namespace gyrostat::bindings {

namespace {

using Law = model::MagnitudeLaw;

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
        .def("__repr__",
             [](const Law& l) {
                 auto list = [](const std::vector<double>& v, std::size_t from = 0) {
                     std::string s = "[";
                     for (std::size_t i = from; i < v.size(); ++i) s += (i > from ? ", " : "") + format_value(v[i]);
                     return s + "]";
                 };
                 switch (l.kind()) {
                     case Law::Kind::Constant: return "MagnitudeLaw.constant(" + format_value(l.a()[0]) + ")";
                     case Law::Kind::Polynomial: return "MagnitudeLaw.polynomial(" + list(l.a()) + ")";
                     case Law::Kind::Harmonic:
                         return "MagnitudeLaw.harmonic(mean=" + format_value(l.a()[0]) + ", amplitudes=" + list(l.a(), 1) +
                                ", frequencies=" + list(l.b()) + ", phases=" + list(l.c()) + ")";
                     default:
                         return "MagnitudeLaw.tabulated(<" + std::to_string(l.a().size()) + " points from t = " +
                                format_value(l.a().front()) + " to " + format_value(l.a().back()) + ">, cubic=" +
                                (l.cubic() ? "True" : "False") + ")";
                 }
             })
        .def("values",
             [](const Law& l, const Eigen::VectorXd& t) {
                 Eigen::VectorXd v(t.size());
                 for (Eigen::Index i = 0; i < t.size(); ++i) v[i] = l(t[i]);
                 return v;
             },
             py::arg("t"));

}

}  // namespace gyrostat::bindings
