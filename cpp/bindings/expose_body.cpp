#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "convert.hpp"
#include "expose.hpp"
#include "gyrostat/body.hpp"
#include "gyrostat/torque/set.hpp"

namespace py = pybind11;

namespace gyrostat::bindings {

namespace {
std::string vector_text(const Eigen::Ref<const Eigen::VectorXd>& v) {
    std::string s = "[";
    for (Eigen::Index i = 0; i < v.size(); ++i) s += (i ? ", " : "") + format_value(v[i]);
    return s + "]";
}
std::string matrix_text(const Mat3& m) {
    return "[" + vector_text(m.row(0).transpose()) + ", " + vector_text(m.row(1).transpose()) + ", " +
           vector_text(m.row(2).transpose()) + "]";
}

/// What every torque shares in Python: evaluation, its averaged contribution, its name. Every
/// argument is converted here, so that a wrong one is a ValueError naming it (convert.hpp).
template <class Torque>
py::class_<Torque> expose_torque(py::module_& m, const char* python_name) {
    const std::string name = python_name;
    return py::class_<Torque>(m, python_name)
        .def("__call__",
             [name](const Torque& x, const py::object& t, const py::object& omega, const py::object& moments) {
                 return x(scalar(t, name + ": t"), vec3(omega, name + ": omega"), vec3(moments, name + ": moments"));
             },
             py::arg("t"), py::arg("omega"), py::arg("moments"), "The torque in body axes at (t, omega) on a body with these moments.")
        .def("averaged",
             [name](const Torque& x, const py::object& t, const py::object& a, const py::object& r, const py::object& A,
                    const py::object& C) {
                 return x.averaged(scalar(t, name + ": t"), scalar(a, name + ": a"), scalar(r, name + ": r"),
                                   scalar(A, name + ": A"), scalar(C, name + ": C"));
             },
             py::arg("t"), py::arg("a"), py::arg("r"), py::arg("A"), py::arg("C"),
             "Its contribution (da/dt, dr/dt) to the system averaged over the symmetric Euler-Poinsot motion.")
        .def_property_readonly_static("kind", [](py::object) { return std::string(Torque::name); });
}
}  // namespace

void expose_body(py::module_& m) {
    py::class_<Body>(m, "Body")
        .def(py::init([](const py::object& moments, const py::object& rotor) {
                 return Body(vec3(moments, "Body: moments"), rotor.is_none() ? Vec3::Zero() : vec3(rotor, "Body: rotor"));
             }),
             py::arg("moments"), py::arg("rotor") = py::none())
        .def_property_readonly("moments", &Body::moments)
        .def_property_readonly("rotor", &Body::rotor)
        .def("__repr__", &Body::describe);

    expose_torque<torque::Constant>(m, "ConstantTorque")
        .def(py::init([](const py::object& moment) { return torque::Constant(vec3(moment, "ConstantTorque: moment")); }),
             py::arg("moment"))
        .def_readonly("moment", &torque::Constant::moment)
        .def("__repr__", [](const torque::Constant& x) { return "ConstantTorque(moment=" + vector_text(x.moment) + ")"; });

    expose_torque<torque::LinearDamping>(m, "LinearDamping")
        .def(py::init([](const py::object& matrix) { return torque::LinearDamping(mat3(matrix, "LinearDamping: matrix")); }),
             py::arg("matrix"))
        .def_readonly("matrix", &torque::LinearDamping::matrix)
        .def("__repr__", [](const torque::LinearDamping& x) { return "LinearDamping(matrix=" + matrix_text(x.matrix) + ")"; });

    expose_torque<torque::ResistiveMedium>(m, "ResistiveMedium")
        .def(py::init([](const py::iterable& coefficients) {
                 std::vector<Mat3> matrices;
                 for (const py::handle& c : coefficients)
                     matrices.push_back(mat3(c, "ResistiveMedium: coefficient " + std::to_string(matrices.size())));
                 return torque::ResistiveMedium(std::move(matrices));
             }),
             py::arg("coefficients"))
        .def_readonly("coefficients", &torque::ResistiveMedium::coefficients)
        .def(
            "at", [](const torque::ResistiveMedium& x, const py::object& t) { return x.at(scalar(t, "ResistiveMedium.at: t")); },
            py::arg("t"))
        .def("__repr__", [](const torque::ResistiveMedium& x) {
            std::string s = "ResistiveMedium(coefficients=[";
            for (std::size_t k = 0; k < x.coefficients.size(); ++k) s += (k ? ", " : "") + matrix_text(x.coefficients[k]);
            return s + "])";
        });

    expose_torque<torque::ViscousCavity>(m, "ViscousCavity")
        .def(py::init([](const py::object& density, const py::object& viscosity, const py::object& p0) {
                 return torque::ViscousCavity(scalar(density, "ViscousCavity: density"),
                                              scalar(viscosity, "ViscousCavity: viscosity"), scalar(p0, "ViscousCavity: p0"));
             }),
             py::arg("density"), py::arg("viscosity"), py::arg("p0"))
        .def_static(
            "sphere",
            [](const py::object& density, const py::object& viscosity, const py::object& radius) {
                return torque::ViscousCavity::sphere(scalar(density, "ViscousCavity.sphere: density"),
                                                     scalar(viscosity, "ViscousCavity.sphere: viscosity"),
                                                     scalar(radius, "ViscousCavity.sphere: radius"));
            },
            py::arg("density"), py::arg("viscosity"), py::arg("radius"))
        .def_readonly("density", &torque::ViscousCavity::density)
        .def_readonly("viscosity", &torque::ViscousCavity::viscosity)
        .def_readonly("p0", &torque::ViscousCavity::p0)
        .def_property_readonly("kappa", &torque::ViscousCavity::kappa)
        .def_property_readonly("equivalent_radius", &torque::ViscousCavity::equivalent_radius)
        .def("__repr__", [](const torque::ViscousCavity& x) {
            return "ViscousCavity(density=" + format_value(x.density) + ", viscosity=" + format_value(x.viscosity) +
                   ", p0=" + format_value(x.p0) + ")";
        });

    expose_torque<torque::MovingMassDamper>(m, "MovingMassDamper")
        .def(py::init([](const py::object& mass, const py::object& arm, const py::object& frequency,
                         const py::object& damping) {
                 return torque::MovingMassDamper(scalar(mass, "MovingMassDamper: mass"), scalar(arm, "MovingMassDamper: arm"),
                                                 scalar(frequency, "MovingMassDamper: frequency"),
                                                 scalar(damping, "MovingMassDamper: damping"));
             }),
             py::arg("mass"), py::arg("arm"), py::arg("frequency"), py::arg("damping"))
        .def_readonly("mass", &torque::MovingMassDamper::mass)
        .def_readonly("arm", &torque::MovingMassDamper::arm)
        .def_readonly("frequency", &torque::MovingMassDamper::frequency)
        .def_readonly("damping", &torque::MovingMassDamper::damping)
        .def(
            "S",
            [](const torque::MovingMassDamper& x, const py::object& A, const py::object& C) {
                return x.S(scalar(A, "MovingMassDamper.S: A"), scalar(C, "MovingMassDamper.S: C"));
            },
            py::arg("A"), py::arg("C"))
        .def("__repr__", [](const torque::MovingMassDamper& x) {
            return "MovingMassDamper(mass=" + format_value(x.mass) + ", arm=" + format_value(x.arm) +
                   ", frequency=" + format_value(x.frequency) + ", damping=" + format_value(x.damping) + ")";
        });
}

}  // namespace gyrostat::bindings
