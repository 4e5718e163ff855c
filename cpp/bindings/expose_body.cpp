#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "convert.hpp"
#include "expose.hpp"
#include "gyrostat/body.hpp"
#include "gyrostat/torque/set.hpp"

#include <map>
#include <string>
#include <variant>
#include <vector>

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

const char* shape_name(torque::Shape shape) {
    switch (shape) {
        case torque::Shape::Vector3: return "vector3";
        case torque::Shape::Matrix3: return "matrix3";
        case torque::Shape::Matrices: return "matrices";
        case torque::Shape::Scalar: break;
    }
    return "scalar";
}
const char* constraint_name(torque::Constraint c) {
    switch (c) {
        case torque::Constraint::Positive: return "positive";
        case torque::Constraint::NonNegative: return "non_negative";
        case torque::Constraint::Finite: break;
    }
    return "finite";
}

/// A Python value → the parameter's shape, or a ValueError naming "<Torque>: <name>".
torque::Value value_from(const py::handle& obj, const torque::Parameter& p, const std::string& torque) {
    const std::string what = torque + ": " + p.name;
    switch (p.shape) {
        case torque::Shape::Scalar: return scalar(obj, what);
        case torque::Shape::Vector3: return vec3(obj, what);
        case torque::Shape::Matrix3: return mat3(obj, what);
        case torque::Shape::Matrices: {
            if (!py::isinstance<py::iterable>(obj) || py::isinstance<py::str>(obj))
                throw py::value_error(what + " must be a list of 3x3 matrices, got " + shown(obj));
            std::vector<Mat3> matrices;
            for (const py::handle& c : py::iter(obj))
                matrices.push_back(mat3(c, torque + ": " + p.label + " " + std::to_string(matrices.size())));
            return matrices;
        }
    }
    return 0.0;
}

py::object python_value(const torque::Value& value) {
    return std::visit([](const auto& x) -> py::object { return py::cast(x); }, value);
}

std::string value_text(const torque::Value& value) {
    struct Text {
        std::string operator()(double x) const { return format_value(x); }
        std::string operator()(const Vec3& v) const { return vector_text(v); }
        std::string operator()(const Mat3& d) const { return matrix_text(d); }
        std::string operator()(const std::vector<Mat3>& list) const {
            std::string s = "[";
            for (std::size_t k = 0; k < list.size(); ++k) s += (k ? ", " : "") + matrix_text(list[k]);
            return s + "]";
        }
    };
    return std::visit(Text{}, value);
}

/// The named values of a call T(*args, **kwargs): positional arguments in the declared order,
/// keywords by name; every parameter converted and a wrong one named (TypeError for a missing,
/// unknown or doubled one; ValueError for a bad value or not exactly one of a choice).
template <class Torque>
torque::Values values_from(const py::args& args, const py::kwargs& kwargs) {
    const std::string torque = Torque::python_name;
    const auto& parameters = Torque::parameters;
    std::string names;
    for (const auto& p : parameters) names += (names.empty() ? "" : ", ") + std::string(p.name);
    if (args.size() > parameters.size())
        throw py::type_error(torque + " takes at most " + std::to_string(parameters.size()) + " arguments (" + names +
                             "), got " + std::to_string(args.size()));
    std::map<std::string, py::object> given;
    for (std::size_t i = 0; i < args.size(); ++i) given[parameters[i].name] = py::reinterpret_borrow<py::object>(args[i]);
    for (const auto& item : kwargs) {
        const std::string key = py::str(item.first);
        bool known = false;
        for (const auto& p : parameters) known = known || key == p.name;
        if (!known) throw py::type_error(torque + ": unknown parameter '" + key + "' (parameters: " + names + ")");
        if (given.count(key)) throw py::type_error(torque + ": " + key + " is given twice");
        given[key] = py::reinterpret_borrow<py::object>(item.second);
    }
    torque::Values values;
    for (const auto& p : parameters) {
        const auto it = given.find(p.name);
        if (it != given.end()) values.set(p.name, value_from(it->second, p, torque));
    }
    for (const auto& p : parameters) {
        if (p.choice == 0) {
            if (!values.has(p.name) && !p.default_value)
                throw py::type_error(torque + ": missing parameter '" + p.name + "'");
            continue;
        }
        std::string choice;
        int count = 0;
        for (const auto& q : parameters)
            if (q.choice == p.choice) choice += (choice.empty() ? "" : " or ") + std::string(q.name), count += values.has(q.name);
        if (count != 1) throw py::value_error(torque + ": give exactly one of " + choice + " (got " + std::to_string(count) + ")");
    }
    return values;
}

/// The Python class of one torque, generated from its declaration (torque/parameter.hpp): the
/// constructor T(*args, **kwargs) over its parameters, a read-only property per kept parameter,
/// evaluation, its averaged contribution, its validity numbers, its repr, and the declaration
/// itself (kind, description, parameters) for the scene schema and the docs.
template <class Torque>
void expose_torque(py::module_& m) {
    const std::string name = Torque::python_name;
    std::string doc = std::string(Torque::description) + " (scene type \"" + Torque::name + "\").\n\nParameters:\n";
    py::list parameters;
    for (const auto& p : Torque::parameters) {
        doc += std::string("    ") + p.name + " [" + p.unit + "]: " + p.description + " (" +
               torque::constraint_text(p.constraint) + (p.choice ? "; one of a choice" : "") +
               (p.default_value ? std::string("; default ") + p.default_value : std::string()) + ")\n";
        py::dict entry;
        entry["name"] = p.name, entry["label"] = p.label, entry["shape"] = shape_name(p.shape), entry["unit"] = p.unit;
        entry["description"] = p.description, entry["constraint"] = constraint_name(p.constraint);
        entry["choice"] = p.choice, entry["stored"] = p.stored;
        entry["default"] = p.default_value ? py::object(py::str(p.default_value)) : py::object(py::none());
        parameters.append(entry);
    }
    py::class_<Torque> cls(m, Torque::python_name, doc.c_str());
    cls.def(py::init([](const py::args& args, const py::kwargs& kwargs) { return Torque::from(values_from<Torque>(args, kwargs)); }))
        .def("__call__",
             [name](const Torque& x, const py::object& t, const py::object& omega, const py::object& moments,
                    const py::object& quaternion) -> Vec3 {
                 const double time = scalar(t, name + ": t");
                 const Vec3 w = vec3(omega, name + ": omega"), J = vec3(moments, name + ": moments");
                 if constexpr (needs_attitude<Torque>::value) {
                     if (quaternion.is_none())
                         throw py::value_error(name + " depends on the attitude: give quaternion=(w, x, y, z)");
                     return x(time, w, J, unit_quaternion(vec4(quaternion, name + ": quaternion")));
                 } else {
                     return x(time, w, J);
                 }
             },
             py::arg("t"), py::arg("omega"), py::arg("moments"), py::arg("quaternion") = py::none(),
             "The torque in body axes at (t, omega) on a body with these moments (and this attitude, body to "
             "inertial, for a torque that needs it).");
    if constexpr (has_averaged<Torque>::value)
        cls.def("averaged",
                [name](const Torque& x, const py::object& t, const py::object& a, const py::object& r, const py::object& A,
                       const py::object& C) {
                    return x.averaged(scalar(t, name + ": t"), scalar(a, name + ": a"), scalar(r, name + ": r"),
                                      scalar(A, name + ": A"), scalar(C, name + ": C"));
                },
                py::arg("t"), py::arg("a"), py::arg("r"), py::arg("A"), py::arg("C"),
                "Its contribution (da/dt, dr/dt) to the system averaged over the symmetric Euler-Poinsot motion.");
    cls.def("assumptions", [](const Torque& x, const torque::Motion& motion) { return assumptions_of(x, motion); },
             py::arg("motion"), "Its validity numbers over a motion: a list of Assumption (empty when it assumes nothing).")
        .def("__repr__",
             [name](const Torque& x) {
                 const torque::Values kept = x.values();
                 std::string s = name + "(";
                 bool first = true;
                 for (const auto& p : Torque::parameters) {
                     if (!p.stored) continue;
                     s += (first ? "" : ", ") + std::string(p.name) + "=" + value_text(kept.all().at(p.name));
                     first = false;
                 }
                 return s + ")";
             })
        .def_property_readonly_static("kind", [](py::object) { return std::string(Torque::name); })
        .def_property_readonly_static("needs_attitude", [](py::object) { return needs_attitude<Torque>::value; })
        .def_property_readonly_static("has_averaged", [](py::object) { return has_averaged<Torque>::value; })
        .def_property_readonly_static("description", [](py::object) { return std::string(Torque::description); })
        .def_property_readonly_static("parameters", [parameters](py::object) { return parameters; });
    for (const auto& p : Torque::parameters) {
        if (!p.stored) continue;
        const std::string key = p.name;
        cls.def_property_readonly(p.name, [key](const Torque& x) { return python_value(x.values().all().at(key)); },
                                  (std::string(p.description) + " [" + p.unit + "]").c_str());
    }
}

/// A torque declared by its parameters (generated here) or the user's own (expose_custom.cpp).
template <class Torque>
void expose_one(py::module_& m) {
    if constexpr (std::is_same_v<Torque, torque::Custom>)
        expose_custom_torque(m);
    else
        expose_torque<Torque>(m);
}

template <class... Torques>
py::list expose_torques(py::module_& m, std::variant<Torques...>*) {
    (expose_one<Torques>(m), ...);
    py::list classes;
    (classes.append(m.attr(Torques::python_name)), ...);
    return classes;
}

/// The class bound for T, to add what only that torque has.
template <class T>
py::class_<T> bound(py::module_& m) {
    return py::reinterpret_borrow<py::class_<T>>(m.attr(T::python_name));
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

    py::class_<torque::Motion>(m, "Motion",
                               "The motion a validity check looks at: the largest |omega|, |J omega| and |(C - A) r / A| "
                               "over the angular velocities given (rows).")
        .def(py::init([](const py::object& moments, const Eigen::MatrixX3d& omegas) {
                 return torque::Motion::of(vec3(moments, "Motion: moments"), omegas);
             }),
             py::arg("moments"), py::arg("omegas"))
        .def_readonly("moments", &torque::Motion::moments)
        .def_readonly("speed", &torque::Motion::speed)
        .def_readonly("momentum", &torque::Motion::momentum)
        .def_readonly("axial_frequency", &torque::Motion::axial_frequency);
    py::class_<torque::Assumption>(m, "TorqueAssumption", "One assumption of a torque, measured (torque/parameter.hpp).")
        .def_readonly("part", &torque::Assumption::part)
        .def_readonly("statement", &torque::Assumption::statement)
        .def_readonly("value", &torque::Assumption::value)
        .def_readonly("limit", &torque::Assumption::limit)
        .def_readonly("holds", &torque::Assumption::holds)
        .def_readonly("note", &torque::Assumption::note);
    m.attr("small") = torque::kSmall;
    m.attr("large") = torque::kLarge;

    // Every alternative of AnyTorque, from its declaration: a new torque needs nothing here.
    m.attr("torque_types") = expose_torques(m, static_cast<AnyTorque*>(nullptr));

    // What only some torques have: derived quantities users and the papers' analyses ask for.
    bound<torque::ResistiveMedium>(m).def(
        "at", [](const torque::ResistiveMedium& x, const py::object& t) { return x.at(scalar(t, "ResistiveMedium.at: t")); },
        py::arg("t"), "D(t).");
    bound<torque::ViscousCavity>(m)
        .def_static(
            "sphere",
            [](const py::object& density, const py::object& viscosity, const py::object& radius) {
                return torque::ViscousCavity::sphere(scalar(density, "ViscousCavity.sphere: density"),
                                                     scalar(viscosity, "ViscousCavity.sphere: viscosity"),
                                                     scalar(radius, "ViscousCavity.sphere: radius"));
            },
            py::arg("density"), py::arg("viscosity"), py::arg("radius"), "A spherical cavity of this radius.")
        .def_property_readonly("kappa", &torque::ViscousCavity::kappa, "kappa = rho P0 / nu")
        .def_property_readonly("equivalent_radius", &torque::ViscousCavity::equivalent_radius,
                               "the radius of the sphere with this P0");
    bound<torque::GravityGradient>(m).def(
        "precession_rate",
        [](const torque::GravityGradient& x, const py::object& moments, const py::object& omega, const py::object& quaternion) {
            return x.precession_rate(vec3(moments, "GravityGradient.precession_rate: moments"),
                                     vec3(omega, "GravityGradient.precession_rate: omega"),
                                     unit_quaternion(vec4(quaternion, "GravityGradient.precession_rate: quaternion")));
        },
        py::arg("moments"), py::arg("omega"), py::arg("quaternion"),
        "The rate (rad/s) at which G precesses about the orbit normal, averaged over the orbit and the free motion "
        "of a symmetric body (A, A, C): -3 n^2 (C - A)(3 cos^2 nutation - 1) cos i / (4 |G|).");
    bound<torque::DipoleFieldTorque>(m).def(
        "field", [](const torque::DipoleFieldTorque& x, const py::object& t) { return x.field(scalar(t, "DipoleFieldTorque.field: t")); },
        py::arg("t"), "The planet's field B(t) at the body, in inertial axes [T].");
    bound<torque::MovingMassDamper>(m).def(
        "S",
        [](const torque::MovingMassDamper& x, const py::object& A, const py::object& C) {
            return x.S(scalar(A, "MovingMassDamper.S: A"), scalar(C, "MovingMassDamper.S: C"));
        },
        py::arg("A"), py::arg("C"), "S of paper 001 eq. (3) for a symmetric body (A, A, C).");
}

}  // namespace gyrostat::bindings
