// The binding module is split into expose_*.cpp files, one per core header group.
#pragma once

#include <pybind11/pybind11.h>

namespace gyrostat::bindings {
void expose_body(pybind11::module_& m);
void expose_integrate(pybind11::module_& m);
void expose_torque_free(pybind11::module_& m);
}  // namespace gyrostat::bindings
