#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "expose.hpp"
#include "gyrostat/body.hpp"
#include "gyrostat/torque/set.hpp"

namespace py = pybind11;

namespace gyrostat::bindings {

void expose_body(py::module_& m) {
    py::class_<Body>(m, "Body")
        .def(py::init<const Vec3&, const Vec3&>(), py::arg("moments"), py::arg("rotor") = Vec3::Zero())
        .def_property_readonly("moments", &Body::moments)
        .def_property_readonly("rotor", &Body::rotor)
        .def("__repr__", &Body::describe);

    py::class_<torque::Constant>(m, "ConstantTorque")
        .def(py::init<const Vec3&>(), py::arg("moment"))
        .def_readonly("moment", &torque::Constant::moment)
        .def("__call__", [](const torque::Constant& t, double time, const Vec3& w) { return t(time, w); },
             py::arg("t"), py::arg("omega"))
        .def("__repr__", [](const torque::Constant& t) {
            return "ConstantTorque([" + std::to_string(t.moment[0]) + ", " + std::to_string(t.moment[1]) + ", " +
                   std::to_string(t.moment[2]) + "])";
        });

    py::class_<torque::LinearDamping>(m, "LinearDamping")
        .def(py::init<const Mat3&>(), py::arg("matrix"))
        .def_readonly("matrix", &torque::LinearDamping::matrix)
        .def("__call__", [](const torque::LinearDamping& t, double time, const Vec3& w) { return t(time, w); },
             py::arg("t"), py::arg("omega"))
        .def("__repr__", [](const torque::LinearDamping&) { return std::string("LinearDamping(matrix=...)"); });
}

}  // namespace gyrostat::bindings
