// The binding module is split into expose_*.cpp files, one per core header group.
#pragma once

#include <pybind11/pybind11.h>

#include <functional>

namespace gyrostat::bindings {
void expose_body(pybind11::module_& m);         // body.hpp, torque/*.hpp
void expose_custom_torque(pybind11::module_& m);  // torque/custom.hpp: the user's torque (called by expose_body)
void expose_attitude(pybind11::module_& m);     // attitude.hpp
void expose_integrate(pybind11::module_& m);    // integrate/options.hpp, engine.hpp: Options, Result, solve
void expose_models(pybind11::module_& m);       // engine.hpp: the model of every family
void expose_torque_free(pybind11::module_& m);  // model/torque_free.hpp: the closed form
void expose_lagrange(pybind11::module_& m);     // model/lagrange_top.hpp: elliptic functions, nutation
void expose_orthogonal(pybind11::module_& m);   // model/orthogonal.hpp: the magnitude law
}  // namespace gyrostat::bindings
