// Conversions shared by the binding files: Python torque objects → core torque values, core
// vectors → NumPy arrays. Translation only.
#pragma once

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>
#include <variant>
#include <vector>

#include "gyrostat/engine.hpp"
#include "gyrostat/torque/set.hpp"

namespace gyrostat::bindings {

namespace py = pybind11;

/// The engine's AnyModel as Python holds it (pybind11's stl.h would otherwise convert the
/// variant instead of binding it as a class).
struct BoundModel {
    AnyModel model;
};

namespace detail {
template <class... Torques>
bool append_torque(const py::handle& obj, std::vector<AnyTorque>& out, std::variant<Torques...>*) {
    return ((py::isinstance<Torques>(obj) ? (out.emplace_back(obj.cast<Torques>()), true) : false) || ...);
}
}  // namespace detail

/// Python torque objects → the core's torque values (every alternative of AnyTorque is known).
inline std::vector<AnyTorque> torques_from(const py::iterable& objects) {
    std::vector<AnyTorque> torques;
    for (const py::handle& obj : objects) {
        if (!detail::append_torque(obj, torques, static_cast<AnyTorque*>(nullptr)))
            throw py::type_error("not a torque: " + std::string(py::str(py::type::of(obj).attr("__name__"))) +
                                 " (torques are gyrostat.ConstantTorque, LinearDamping, ResistiveMedium, "
                                 "ViscousCavity, MovingMassDamper)");
    }
    return torques;
}

/// A (rows × cols) NumPy view of `data`, kept alive by `owner` (no copy).
inline py::array_t<double> view(const std::vector<double>& data, py::ssize_t rows, py::ssize_t cols, py::handle owner) {
    if (cols == 0) return py::array_t<double>({rows, cols});
    return py::array_t<double>({rows, cols}, {static_cast<py::ssize_t>(cols * sizeof(double)), py::ssize_t(sizeof(double))},
                               data.data(), owner);
}

}  // namespace gyrostat::bindings
