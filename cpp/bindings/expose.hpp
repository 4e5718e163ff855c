// The binding module is split into expose_*.cpp files, one per core header group.
#pragma once

#include <pybind11/pybind11.h>

namespace gyrostat::bindings {
void expose_body(pybind11::module_& m);
void expose_integrate(pybind11::module_& m);
void expose_torque_free(pybind11::module_& m);
void expose_lagrange(pybind11::module_& m);     // paper 003: heavy symmetric top, averaged over nutation
void expose_orthogonal(pybind11::module_& m);   // paper 004: gyrostat under a torque orthogonal to G and ω
}  // namespace gyrostat::bindings
