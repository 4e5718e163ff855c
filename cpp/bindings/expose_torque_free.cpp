#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "expose.hpp"
#include "gyrostat/model/torque_free.hpp"

namespace py = pybind11;

namespace gyrostat::bindings {

void expose_torque_free(py::module_& m) {
    py::class_<model::TorqueFreeSolution>(m, "TorqueFreeSolution")
        .def(py::init<const Body&, const Vec3&, double>(), py::arg("body"), py::arg("omega0"), py::arg("t0") = 0.0)
        .def("omega",
             [](const model::TorqueFreeSolution& s, const std::vector<double>& t) {
                 std::vector<double> flat;
                 {
                     py::gil_scoped_release release;
                     flat = s.omega(t);
                 }
                 py::array_t<double> out({static_cast<py::ssize_t>(t.size()), py::ssize_t(3)});
                 std::copy(flat.begin(), flat.end(), out.mutable_data());
                 return out;
             },
             py::arg("t"))
        .def_property_readonly("modulus_squared", &model::TorqueFreeSolution::modulus_squared)
        .def_property_readonly("frequency", &model::TorqueFreeSolution::frequency)
        .def_property_readonly("period", &model::TorqueFreeSolution::period)
        .def_property_readonly("is_constant", &model::TorqueFreeSolution::is_constant);
}

}  // namespace gyrostat::bindings
