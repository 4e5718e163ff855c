// Conversions shared by the binding files: Python torque objects → core torque values, core
// vectors → NumPy arrays. Translation only.
#pragma once

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cctype>
#include <cstdint>
#include <cstring>
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
                                 " (torques are gyrostat." + torque_python_names() + ")");
    }
    return torques;
}

/// Whether a model has torques() (the families with perturbation torques).
template <class M, class = void>
struct has_torques : std::false_type {};
template <class M>
struct has_torques<M, std::void_t<decltype(std::declval<const M&>().torques())>> : std::true_type {};

/// The user's Python torques of a model (expose_custom.cpp): forget their last exception before a
/// run; re-raise the first one after it (GIL held), as they raised it.
void reset_python_torques(const AnyModel& model);
void rethrow_python_torques(const AnyModel& model);

/// The value as the user wrote it, on one line (runs of white space folded to one space) and
/// shortened to 60 characters: for error messages.
inline std::string shown(const py::handle& obj) {
    std::string text;
    for (char c : std::string(py::repr(obj))) {
        const bool space = std::isspace(static_cast<unsigned char>(c)) != 0;
        if (!space || (!text.empty() && text.back() != ' ')) text += space ? ' ' : c;
    }
    return text.size() > 60 ? text.substr(0, 57) + "..." : text;
}

/// `obj` as one real number (int, float, a NumPy real scalar), or a ValueError naming `what` and
/// the value: str, None, bool, complex, lists are refused (pybind11 would dump its signatures).
inline double scalar(const py::handle& obj, const std::string& what) {
    PyObject* p = obj.ptr();
    const bool real = !PyBool_Check(p) && (PyFloat_Check(p) || PyLong_Check(p) ||
                                           py::isinstance(obj, py::module_::import("numbers").attr("Real")));
    if (real) {
        const double value = PyFloat_AsDouble(p);
        if (!(value == -1.0 && PyErr_Occurred())) return value;
        PyErr_Clear();  // an int too large for a double
    }
    throw py::value_error(what + " must be a number, got " + shown(obj));
}

/// `count` numbers read in place from what a user's function most often returns: a 1-D float64
/// NumPy array, or a tuple or list of Python floats (NumPy's float64 scalars are floats); true when
/// `obj` is one of them with `count` numbers, else false and `numbers` takes it (its checks and
/// messages). No array is made and no message formatted: a Python torque calls this at every
/// evaluation (bench/custom_torque.py).
inline bool read_flat(const py::handle& obj, long count, double* out) {
    PyObject* p = obj.ptr();
    if (PyTuple_CheckExact(p) || PyList_CheckExact(p)) {
        if (PySequence_Fast_GET_SIZE(p) != count) return false;
        PyObject** items = PySequence_Fast_ITEMS(p);
        for (long i = 0; i < count; ++i) {
            if (!PyFloat_Check(items[i])) return false;
            out[i] = PyFloat_AS_DOUBLE(items[i]);
        }
        return true;
    }
    if (!py::isinstance<py::array>(obj)) return false;
    const auto a = py::reinterpret_borrow<py::array>(obj);
    if (a.ndim() != 1 || a.shape(0) != count || a.itemsize() != sizeof(double) || a.dtype().kind() != 'f') return false;
    const auto* first = static_cast<const char*>(a.data());
    for (long i = 0; i < count; ++i) std::memcpy(out + i, first + i * a.strides(0), sizeof(double));
    return true;
}

/// Row numbers (None or none: every row) from a sequence or a 1-D integer array, read without a Python object
/// per number (an array's buffer is copied); a ValueError names a negative or non-integer one.
inline std::vector<std::size_t> row_numbers(const py::object& obj, const char* what) {
    std::vector<std::size_t> made;
    if (obj.is_none()) return made;
    using Integers = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>;
    const py::array given = py::array::ensure(obj);
    if (given && given.ndim() == 1 && given.shape(0) == 0) return made;  // (none given: every row)
    const char kind = given ? given.dtype().kind() : '?';
    if (!(kind == 'i' || kind == 'u') || given.ndim() != 1)
        throw py::value_error(std::string(what) + " must be row numbers (integers), got " + shown(obj));
    const Integers a = Integers::ensure(given);
    if (!a) throw py::value_error(std::string(what) + " must be row numbers (integers), got " + shown(obj));
    made.resize(static_cast<std::size_t>(a.shape(0)));
    const std::int64_t* first = a.data();
    for (std::size_t k = 0; k < made.size(); ++k) {
        if (first[k] < 0) throw py::value_error(std::string(what) + ": row " + std::to_string(first[k]) + " is negative");
        made[k] = static_cast<std::size_t>(first[k]);
    }
    return made;
}

/// `obj` as numbers of the given shape (cols = 0: a vector of `rows`), or a ValueError that names
/// what was expected and what was given (instead of pybind11's list of signatures). Only real
/// numbers are taken: strings, None and complex numbers are refused, not cast.
inline Eigen::MatrixXd numbers(const py::handle& obj, long rows, long cols, const std::string& what) {
    const py::array given = py::array::ensure(obj);  // the values as written, before any cast
    using Doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;
    const char kind = given ? given.dtype().kind() : '?';
    const bool real = kind == 'i' || kind == 'u' || kind == 'f';
    const Doubles a = real ? Doubles::ensure(given) : Doubles();
    const bool vector = cols == 0;
    if (!real || !a || a.ndim() != (vector ? 1 : 2) || a.shape(0) != rows || (!vector && a.shape(1) != cols))
        throw py::value_error(what + " must be " +
                              (vector ? std::to_string(rows) + " numbers" : std::to_string(rows) + "x" + std::to_string(cols) + " numbers") +
                              ", got " + shown(obj));
    Eigen::MatrixXd m(rows, vector ? 1 : cols);
    for (long i = 0; i < rows; ++i)
        for (long j = 0; j < (vector ? 1 : cols); ++j) m(i, j) = a.data()[vector ? i : i * cols + j];
    return m;
}
inline Vec3 vec3(const py::handle& obj, const std::string& what) { return numbers(obj, 3, 0, what); }
inline Eigen::Vector4d vec4(const py::handle& obj, const std::string& what) { return numbers(obj, 4, 0, what); }
inline Mat3 mat3(const py::handle& obj, const std::string& what) { return numbers(obj, 3, 3, what); }

/// A (rows × cols) NumPy view of `data`, kept alive by `owner` (no copy).
inline py::array_t<double> view(const std::vector<double>& data, py::ssize_t rows, py::ssize_t cols, py::handle owner) {
    if (cols == 0) return py::array_t<double>({rows, cols});
    return py::array_t<double>({rows, cols}, {static_cast<py::ssize_t>(cols * sizeof(double)), py::ssize_t(sizeof(double))},
                               data.data(), owner);
}

}  // namespace gyrostat::bindings
