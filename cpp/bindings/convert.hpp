// Conversions shared by the binding files: Python arguments → core options, states, torques;
// core results → NumPy arrays. Translation only.
#pragma once

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>
#include <variant>
#include <vector>

#include "gyrostat/integrate/options.hpp"
#include "gyrostat/torque/set.hpp"

namespace gyrostat::bindings {

namespace py = pybind11;

/// Python torque objects → the core's torque values.
inline std::vector<AnyTorque> torques_from(const py::sequence& objects) {
    std::vector<AnyTorque> torques;
    for (const py::handle& obj : objects) {
        if (py::isinstance<torque::Constant>(obj)) {
            torques.emplace_back(obj.cast<torque::Constant>());
        } else if (py::isinstance<torque::LinearDamping>(obj)) {
            torques.emplace_back(obj.cast<torque::LinearDamping>());
        } else if (py::isinstance<torque::ResistiveMedium>(obj)) {
            torques.emplace_back(obj.cast<torque::ResistiveMedium>());
        } else if (py::isinstance<torque::ViscousCavity>(obj)) {
            torques.emplace_back(obj.cast<torque::ViscousCavity>());
        } else if (py::isinstance<torque::MovingMassDamper>(obj)) {
            torques.emplace_back(obj.cast<torque::MovingMassDamper>());
        } else {
            throw py::type_error("unknown torque: " + std::string(py::repr(obj)));
        }
    }
    return torques;
}

inline py::array_t<double> as_array(const std::vector<double>& flat, std::size_t rows, std::size_t cols) {
    py::array_t<double> out({static_cast<py::ssize_t>(rows), static_cast<py::ssize_t>(cols)});
    std::copy(flat.begin(), flat.end(), out.mutable_data());
    return out;
}

inline integrate::Options make_options(const std::string& method, double rtol, double atol, std::vector<double> t_eval,
                                bool every_step, long max_steps, double first_step, double max_step) {
    integrate::Options o;
    o.method = integrate::method_from_name(method);
    o.rtol = rtol;
    o.atol = atol;
    o.t_eval = std::move(t_eval);
    o.every_step = every_step;
    o.max_steps = max_steps;
    o.first_step = first_step;
    o.max_step = max_step;
    return o;
}

template <class System>
typename System::State to_state(const Eigen::VectorXd& y0) {
    if (y0.size() != System::dim)
        throw std::invalid_argument("initial state has " + std::to_string(y0.size()) + " components; this model needs " +
                                    std::to_string(System::dim));
    return y0;
}

/// f(t, y) of whichever system a variant of systems holds (for checks from Python, not speed).
template <class Variant>
Eigen::VectorXd variant_rhs(const Variant& systems, double t, const Eigen::VectorXd& y) {
    return std::visit(
        [&](const auto& s) -> Eigen::VectorXd {
            using S = std::decay_t<decltype(s)>;
            typename S::State dy;
            s.rhs(t, to_state<S>(y), dy);
            return dy;
        },
        systems);
}

}  // namespace gyrostat::bindings
