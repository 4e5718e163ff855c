#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "expose.hpp"
#include "gyrostat/model/torque_free.hpp"

namespace py = pybind11;

namespace gyrostat::bindings {

void expose_torque_free(py::module_& m) {
    py::class_<model::TorqueFreeSolution>(m, "TorqueFreeSolution", R"doc(The closed-form angular velocity of a torque-free rigid body (Jacobi elliptic functions).

Parameters
----------
body : gyrostat.Body
    The body (without rotor).
omega0 : array_like, shape (3,)
    Angular velocity at t0 in body axes, in rad/s.
t0 : float, optional
    Time of omega0, in s (default 0).

Examples
--------
>>> import gyrostat
>>> free = gyrostat.TorqueFreeSolution(gyrostat.Body([3.0, 2.0, 1.0]), [0.1, 0.2, 1.0])
>>> free.period
10.858161104747332
)doc")
        .def(py::init([](const Body& body, const Vec3& omega0, double t0) {
                 if (!body.principal())
                     throw py::value_error(
                         "TorqueFreeSolution: the closed form is written in principal axes; this body was given by an "
                         "inertia tensor: use Body(body.moments) and omega0 = body.principal_axes.T @ omega, or solve the "
                         "torque-free model (it converts)");
                 return model::TorqueFreeSolution(body, omega0, t0);
             }),
             py::arg("body"), py::arg("omega0"), py::arg("t0") = 0.0)
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
             py::arg("t"), "The angular velocity at each time.\n\nParameters\n----------\nt : sequence of float\n"
             "    Times, in s.\n\nReturns\n-------\nnumpy.ndarray, shape (n, 3)\n    omega in body axes, in rad/s."
             "\n\nExamples\n--------\n>>> import gyrostat\n>>> free = gyrostat.TorqueFreeSolution(gyrostat.Body([3.0, 2.0, 1.0]), [0.1, 0.2, 1.0])\n>>> free.omega([0.0])\narray([[0.1, 0.2, 1. ]])\n")
        .def_property_readonly("modulus_squared", &model::TorqueFreeSolution::modulus_squared, "The elliptic modulus squared m = k^2 (0 for a permanent rotation; 1: dimensionless).\n\nExamples\n--------\n>>> import gyrostat\n>>> free = gyrostat.TorqueFreeSolution(gyrostat.Body([3.0, 2.0, 1.0]), [0.1, 0.2, 1.0])\n>>> free.modulus_squared\n0.06730769230769232\n")
        .def_property_readonly("frequency", &model::TorqueFreeSolution::frequency, "The frequency of the elliptic functions' argument, in rad/s (signed).\n\nExamples\n--------\n>>> import gyrostat\n>>> free = gyrostat.TorqueFreeSolution(gyrostat.Body([3.0, 2.0, 1.0]), [0.1, 0.2, 1.0])\n>>> free.frequency\n-0.5887840577551898\n")
        .def_property_readonly("period", &model::TorqueFreeSolution::period, "The period of omega(t), in s.\n\nExamples\n--------\n>>> import gyrostat\n>>> free = gyrostat.TorqueFreeSolution(gyrostat.Body([3.0, 2.0, 1.0]), [0.1, 0.2, 1.0])\n>>> free.period\n10.858161104747332\n")
        .def_property_readonly("is_constant", &model::TorqueFreeSolution::is_constant, "Whether omega is constant (a permanent rotation about a principal axis).\n\nExamples\n--------\n>>> import gyrostat\n>>> free = gyrostat.TorqueFreeSolution(gyrostat.Body([3.0, 2.0, 1.0]), [0.1, 0.2, 1.0])\n>>> free.is_constant\nFalse\n");
}

}  // namespace gyrostat::bindings
