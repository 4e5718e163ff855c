// Bindings of attitude.hpp: quaternions, rotation matrices, Euler angles (translation only).
// Every function maps the core's per-rotation function over the rows of an array: one item of
// shape (4,), (3,) or (3, 3), or a stack (n, ...) of them; the GIL is released around the loop.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "expose.hpp"
#include "gyrostat/attitude.hpp"
#include "gyrostat/numeric/unit_vector.hpp"

namespace py = pybind11;

namespace gyrostat::bindings {

namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;
using RowMajor3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;

std::string shape_text(const py::array& a) {
    std::string s = "(";
    for (py::ssize_t i = 0; i < a.ndim(); ++i) s += (i ? ", " : "") + std::to_string(a.shape(i));
    return s + (a.ndim() == 1 ? ",)" : ")");
}

std::string shape_text(const std::vector<py::ssize_t>& item, bool stacked) {
    std::string s = stacked ? "(n" : "(";
    for (std::size_t i = 0; i < item.size(); ++i) s += (i || stacked ? ", " : "") + std::to_string(item[i]);
    return s + (!stacked && item.size() == 1 ? ",)" : ")");
}

/// f(const double* in, double* out) applied to every item of `input`, whose shape is `item`
/// (returns shape `out_item`) or (n, *item) (returns (n, *out_item)). Errors of the core for an
/// item of a stack name its row.
template <class F>
py::array_t<double> map_items(const Array& input, const std::vector<py::ssize_t>& item,
                              const std::vector<py::ssize_t>& out_item, const char* what, F f) {
    const auto dims = static_cast<py::ssize_t>(item.size());
    const bool single = input.ndim() == dims;
    bool ok = single || input.ndim() == dims + 1;
    for (py::ssize_t i = 0; ok && i < dims; ++i) ok = input.shape(input.ndim() - dims + i) == item[static_cast<std::size_t>(i)];
    if (!ok)
        throw py::value_error(std::string(what) + " must have shape " + shape_text(item, false) + " or " +
                              shape_text(item, true) + ", got shape " + shape_text(input));
    const py::ssize_t n = single ? 1 : input.shape(0);
    std::vector<py::ssize_t> shape;
    if (!single) shape.push_back(n);
    shape.insert(shape.end(), out_item.begin(), out_item.end());
    py::array_t<double> output(shape);
    py::ssize_t in_size = 1, out_size = 1;
    for (auto d : item) in_size *= d;
    for (auto d : out_item) out_size *= d;
    const double* in = input.data();
    double* out = output.mutable_data();
    {
        py::gil_scoped_release release;
        for (py::ssize_t i = 0; i < n; ++i) {
            try {
                f(in + i * in_size, out + i * out_size);
            } catch (const std::invalid_argument& e) {
                if (single) throw;
                throw std::invalid_argument(std::string(what) + "[" + std::to_string(i) + "]: " + e.what());
            }
        }
    }
    return output;
}

}  // namespace

void expose_attitude(py::module_& m) {
    m.def(
        "euler_angles",
        [](const Array& q, const std::string& convention) {
            const EulerConvention c = euler_convention_from_name(convention);
            return map_items(q, {4}, {3}, "q", [c](const double* in, double* out) {
                Eigen::Map<Vec3>{out} = euler_angles(Eigen::Map<const Eigen::Vector4d>(in), c);
            });
        },
        py::arg("q"), py::arg("convention") = "zxz",
        "Euler angles (psi, theta, phi) of quaternions (w, x, y, z), shape (4,) or (n, 4), body -> inertial;\n"
        "convention 'zxz' (R = Rz(psi) Rx(theta) Rz(phi)) or 'zyx' (R = Rz(psi) Ry(theta) Rx(phi)).\n"
        "At a singular theta the free rotation is in psi and phi = 0. Returns shape (3,) or (n, 3).");
    m.def(
        "quaternion_from_euler",
        [](const Array& angles, const std::string& convention) {
            const EulerConvention c = euler_convention_from_name(convention);
            return map_items(angles, {3}, {4}, "angles", [c](const double* in, double* out) {
                Eigen::Map<Eigen::Vector4d>{out} = quaternion_from_euler(Eigen::Map<const Vec3>(in), c);
            });
        },
        py::arg("angles"), py::arg("convention") = "zxz",
        "Unit quaternions (w, x, y, z), w >= 0, of Euler angles (psi, theta, phi), shape (3,) or (n, 3),\n"
        "convention 'zxz' or 'zyx'. Returns shape (4,) or (n, 4).");
    m.def(
        "rotation_matrix",
        [](const Array& q) {
            return map_items(q, {4}, {3, 3}, "q", [](const double* in, double* out) {
                Eigen::Map<RowMajor3>{out} = rotation_matrix(Eigen::Map<const Eigen::Vector4d>(in));
            });
        },
        py::arg("q"),
        "Body -> inertial rotation matrices R(q) of quaternions (w, x, y, z) (normalised first), shape (4,)\n"
        "or (n, 4). Returns shape (3, 3) or (n, 3, 3).");
    m.def(
        "quaternion_from_matrix",
        [](const Array& R) {
            return map_items(R, {3, 3}, {4}, "R", [](const double* in, double* out) {
                Eigen::Map<Eigen::Vector4d>{out} = quaternion_from_matrix(Eigen::Map<const RowMajor3>(in));
            });
        },
        py::arg("R"),
        "Unit quaternions (w, x, y, z), w >= 0, of rotation matrices, shape (3, 3) or (n, 3, 3) (Shepperd's\n"
        "method). Returns shape (4,) or (n, 4).");
    m.def(
        "unit_vector",
        [](const Array& v, const std::string& name) {
            if (v.ndim() != 1) throw py::value_error(name + " must have shape (n,), got shape " + shape_text(v));
            const Eigen::VectorXd u = unit_direction(Eigen::Map<const Eigen::VectorXd>(v.data(), v.shape(0)), name, "");
            return py::array_t<double>(u.size(), u.data());
        },
        py::arg("v"), py::arg("name") = "v",
        "The unit vector along v, shape (n,), whatever its length: v / max|v_i| normalised (no overflow or\n"
        "underflow). ValueError naming `name` and v when v is zero or not finite.");
}

}  // namespace gyrostat::bindings
