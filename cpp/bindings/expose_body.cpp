#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "convert.hpp"
#include "expose.hpp"
#include "gyrostat/body.hpp"
#include "gyrostat/torque/set.hpp"

#include <algorithm>
#include <cctype>
#include <map>
#include <utility>
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

/// A value of the parameter's shape for the generated examples: the smallest list that satisfies
/// its constraint (0.5 on the diagonal or in every scalar).
py::object example_value(const torque::Parameter& p) {
    const py::list vector = py::cast(std::vector<double>{0.0, 0.0, 0.5});
    py::list matrix;
    for (int i = 0; i < 3; ++i) {
        std::vector<double> row(3, 0.0);
        row[static_cast<std::size_t>(i)] = 0.5;
        matrix.append(py::cast(row));
    }
    switch (p.shape) {
        case torque::Shape::Scalar: return py::float_(0.5);
        case torque::Shape::Vector3:
            return p.constraint == torque::Constraint::Finite ? py::object(vector) : py::object(py::cast(std::vector<double>(3, 0.5)));
        case torque::Shape::Matrix3: return matrix;
        case torque::Shape::Matrices: {
            py::list list;
            list.append(matrix);
            return list;
        }
    }
    return py::none();
}

/// A declaration's one-line text as a sentence of a docstring: capital first letter.
std::string sentence(const char* text) {
    std::string s = text;
    if (!s.empty()) s[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(s[0])));
    return s;
}

/// Python source of a value (a float, or nested lists of floats).
std::string source(const py::handle& value) { return py::str(py::repr(value)); }

/// The numpydoc type of a parameter: "float", "array_like, shape (3,)", ….
const char* numpydoc_type(torque::Shape shape) {
    switch (shape) {
        case torque::Shape::Vector3: return "array_like, shape (3,)";
        case torque::Shape::Matrix3: return "array_like, shape (3, 3)";
        case torque::Shape::Matrices: return "sequence of array_like, shape (3, 3)";
        case torque::Shape::Scalar: break;
    }
    return "float";
}

/// The generated example of torque T: its construction from one value per required parameter
/// (the first of each choice) with the repr it gives, as doctest lines, and the torque itself.
template <class Torque>
std::pair<std::string, Torque> torque_example() {
    const std::string name = Torque::python_name;
    std::string call;
    torque::Values values;
    std::vector<int> chosen;
    for (const auto& p : Torque::parameters) {
        if (p.choice && std::find(chosen.begin(), chosen.end(), p.choice) != chosen.end()) continue;
        if (p.choice) chosen.push_back(p.choice);
        const py::object value = example_value(p);
        call += (call.empty() ? "" : ", ") + std::string(p.name) + "=" + source(value);
        values.set(p.name, value_from(value, p, name));
    }
    Torque torque = Torque::from(values);
    return {">>> import gyrostat\n>>> torque = gyrostat." + name + "(" + call + ")\n", torque};
}

/// The repr of T's instance x (the stored parameters by name).
template <class Torque>
std::string torque_repr(const Torque& x) {
    const torque::Values kept = x.values();
    std::string s = std::string(Torque::python_name) + "(";
    bool first = true;
    for (const auto& p : Torque::parameters) {
        if (!p.stored || !kept.has(p.name)) continue;  // an optional parameter left out (an orbit torque on the model's orbit)
        s += (first ? "" : ", ") + std::string(p.name) + "=" + value_text(kept.all().at(p.name));
        first = false;
    }
    return s + ")";
}

/// One declared parameter as the dict Python reads (name, label, shape, unit, description,
/// constraint, choice, stored, default).
py::dict parameter_entry(const torque::Parameter& p) {
    py::dict entry;
    entry["name"] = p.name, entry["label"] = p.label, entry["shape"] = shape_name(p.shape), entry["unit"] = p.unit;
    entry["description"] = p.description, entry["constraint"] = constraint_name(p.constraint);
    entry["choice"] = p.choice, entry["stored"] = p.stored;
    entry["default"] = p.default_value ? py::object(py::str(p.default_value)) : py::object(py::none());
    return entry;
}

/// The Python class of one torque, generated from its declaration (torque/parameter.hpp): the
/// constructor T(*args, **kwargs) over its parameters, a read-only property per kept parameter,
/// evaluation, its averaged contribution, its validity numbers, its repr, and the declaration
/// itself (kind, description, parameters) for the scene schema and the docs. Every docstring is
/// numpydoc, written here once from the declaration (parameters with their units, an example
/// whose printed values are computed by the same code as the call they show).
template <class Torque>
void expose_torque(py::module_& m) {
    const std::string name = Torque::python_name;
    const auto [example, instance] = torque_example<Torque>();
    std::string doc = sentence(Torque::description) + " (scene type ``\"" + Torque::name +
                      "\"``): a torque in body axes acting on the body it is given to.\n\nParameters\n----------\n";
    py::list parameters;
    for (const auto& p : Torque::parameters) {
        doc += std::string(p.name) + " : " + numpydoc_type(p.shape) + "\n    " + sentence(p.description) + ", in " + p.unit +
               " (" + torque::constraint_text(p.constraint) + (p.choice ? "; give exactly one of its choice" : "") +
               (p.default_value ? std::string("; optional, default ") + p.default_value : std::string()) + ").\n";
        parameters.append(parameter_entry(p));
    }
    doc += "\nAttributes\n----------\nkind : str\n    Its type in a scene's ``[[torques]]`` table (``\"" + std::string(Torque::name) +
           "\"``).\ndescription : str\n    What it is, in one line.\nparameters : tuple of dict\n    Its declaration: one dict "
           "per parameter (name, label, shape, unit, description, constraint, choice, stored, default), for the "
           "scene schema and the docs.\naffine_in : tuple of str\n    The stored parameters the torque is affine in "
           "(sensitivities take their derivative by a one-sided difference, exact to rounding).\ninverse_in : tuple of str\n    The stored parameters the torque is inversely proportional to (the same difference, scaled).\nneeds_attitude : bool\n    Whether it depends on the attitude (then only "
           "models with the quaternion take it).\nhas_averaged : bool\n    Whether it has a contribution to the "
           "averaged (a, r) system.\n";
    doc += "\nExamples\n--------\n" + example + ">>> torque\n" + torque_repr(instance) + "\n>>> torque.kind, [p[\"unit\"] for p in torque.parameters]\n" +
           source(py::make_tuple(Torque::name, [] {
               py::list units;
               for (const auto& p : Torque::parameters) units.append(p.unit);
               return units;
           }())) + "\n";

    // the example's evaluation, its averaged contribution and its validity numbers, as printed
    const Vec3 omega(0.1, 0.0, 1.0), moments(2.0, 2.0, 1.0);
    std::string call, averaged;
    if constexpr (needs_attitude<Torque>::value)
        call = source(py::cast(instance(0.0, omega, moments, Eigen::Vector4d(1.0, 0.0, 0.0, 0.0))));
    else
        call = source(py::cast(instance(0.0, omega, moments)));
    if constexpr (has_averaged<Torque>::value) averaged = source(py::cast(instance.averaged(0.0, 0.1, 1.0, 2.0, 1.0)));
    Eigen::MatrixX3d rows(1, 3);
    rows.row(0) = omega.transpose();
    const std::size_t checks = assumptions_of(instance, torque::Motion::of(moments, rows)).size();

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
             ("The torque in body axes at (t, omega) on a body with these moments" +
              std::string(needs_attitude<Torque>::value ? " and this attitude" : "") +
              ".\n\nParameters\n----------\n"
              "t : float\n    Time, in s.\nomega : array_like, shape (3,)\n    Angular velocity in body axes, in rad/s.\n"
              "moments : array_like, shape (3,)\n    Principal moments of inertia (A1, A2, A3), in kg m^2.\n"
              "quaternion : array_like, shape (4,), optional\n    The attitude (w, x, y, z), body to inertial: " +
              std::string(needs_attitude<Torque>::value ? "required (this torque depends on it)" : "not used by this torque") +
              ".\n\nReturns\n-------\nnumpy.ndarray, shape (3,)\n    The torque, in N m.\n\nExamples\n--------\n" +
              example + ">>> torque(0.0, [0.1, 0.0, 1.0], [2.0, 2.0, 1.0]" +
              (needs_attitude<Torque>::value ? ", quaternion=[1.0, 0.0, 0.0, 0.0]" : "") + ")\n" + call + "\n")
                 .c_str());
    if constexpr (has_averaged<Torque>::value)
        cls.def("averaged",
                [name](const Torque& x, const py::object& t, const py::object& a, const py::object& r, const py::object& A,
                       const py::object& C) {
                    return x.averaged(scalar(t, name + ": t"), scalar(a, name + ": a"), scalar(r, name + ": r"),
                                      scalar(A, name + ": A"), scalar(C, name + ": C"));
                },
                py::arg("t"), py::arg("a"), py::arg("r"), py::arg("A"), py::arg("C"),
                ("Its contribution (da/dt, dr/dt) to the system averaged over the symmetric Euler-Poinsot motion.\n\n"
                 "Parameters\n----------\nt : float\n    Time, in s.\na : float\n    Equatorial angular speed "
                 "a = sqrt(p^2 + q^2), in rad/s.\nr : float\n    Axial angular velocity, in rad/s.\nA : float\n"
                 "    Equatorial moment of inertia, in kg m^2.\nC : float\n    Axial moment of inertia, in kg m^2.\n\n"
                 "Returns\n-------\nnumpy.ndarray, shape (2,)\n    (da/dt, dr/dt), in rad/s^2.\n\nExamples\n--------\n" +
                 example + ">>> torque.averaged(0.0, 0.1, 1.0, 2.0, 1.0)\n" + averaged + "\n")
                    .c_str());
    cls.def("assumptions", [](const Torque& x, const torque::Motion& motion) { return assumptions_of(x, motion); },
             py::arg("motion"),
             ("Its validity numbers over a motion (empty when it assumes nothing).\n\nParameters\n----------\n"
              "motion : gyrostat._core.Motion\n    The largest |omega|, |J omega| and axial frequency over the states "
              "checked.\n\nReturns\n-------\nlist of gyrostat._core.TorqueAssumption\n    Each assumption measured: "
              "statement, value, limit, holds.\n\nExamples\n--------\n" +
              example + ">>> motion = gyrostat._core.Motion([2.0, 2.0, 1.0], [[0.1, 0.0, 1.0]])\n"
              ">>> len(torque.assumptions(motion))\n" + std::to_string(checks) + "\n")
                 .c_str())
        .def("__repr__", [](const Torque& x) { return torque_repr(x); });
    // what the torque declares about itself, as class attributes (named in the docstring's Attributes)
    cls.attr("kind") = std::string(Torque::name);
    cls.attr("description") = std::string(Torque::description);
    cls.attr("parameters") = py::tuple(parameters);
    cls.attr("affine_in") = py::tuple(py::cast(affine_in<Torque>()));
    cls.attr("inverse_in") = py::tuple(py::cast(inverse_in<Torque>()));
    cls.attr("needs_attitude") = needs_attitude<Torque>::value;
    cls.attr("has_averaged") = has_averaged<Torque>::value;
    for (const auto& p : Torque::parameters) {
        if (!p.stored) continue;
        const std::string key = p.name;
        const auto kept = instance.values().all();
        const std::string shown = kept.count(key) ? source(python_value(kept.at(key))) : "";
        cls.def_property_readonly(p.name, [key](const Torque& x) {
                                      const torque::Values kept = x.values();
                                      return kept.has(key) ? python_value(kept.all().at(key)) : py::object(py::none());
                                  },
                                  (sentence(p.description) + ", in " + p.unit + ".\n\nExamples\n--------\n" + example +
                                   ">>> torque." + key + "\n" + shown + "\n")
                                      .c_str());
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

/// torque/orbit.hpp: the circular orbit a model is given (its parameters declared there).
static void expose_orbit(py::module_& m) {
    using torque::CircularOrbit;
    py::list parameters;
    for (const auto& p : CircularOrbit::parameters) parameters.append(parameter_entry(p));
    py::class_<CircularOrbit> cls(m, "Orbit", R"doc(A circular orbit, given once to a model (``gyrostat.Model(..., orbit=...)``, a scene's ``[orbit]`` table):
every orbit torque of the model (GravityGradient, DipoleFieldTorque) reads it, and the model reports the
attitude relative to its orbit frame (docs/orbit_frame.md).

The body is at c(t) = cos u e1 + sin u e2, u = n t + phase, from the planet, with e1 = z x N / |z x N|
(x when N is along z) and e2 = N x e1: it moves about N. The orbit frame (LVLH) has x along track
(N x c), y = -N, z nadir (-c).

Parameters
----------
rate : float
    The orbit's mean motion n = sqrt(mu / r^3), in rad/s (finite and positive).
normal : array_like, shape (3,), optional
    The orbit plane's normal N in inertial axes, any length (default [0, 0, 1]).
phase : float, optional
    The body's angle u(0) on the orbit from e1 at t = 0, in rad (default 0).

Attributes
----------
description : str
    What it is, in one line.
parameters : tuple of dict
    Its declaration: one dict per parameter (name, label, shape, unit, description, constraint,
    choice, stored, default), for the scene schema and the docs.

Examples
--------
>>> import gyrostat
>>> orbit = gyrostat.Orbit(rate=0.001)
>>> orbit
Orbit(rate=0.001, normal=[0, 0, 1], phase=0)
>>> orbit.position(0.0), orbit.frame(0.0)[:, 0]
(array([1., 0., 0.]), array([0., 1., 0.]))
)doc");
    cls.def(py::init([](const py::args& args, const py::kwargs& kwargs) {
           return CircularOrbit::from(values_from<CircularOrbit>(args, kwargs));
       }))
        .def_property_readonly("rate", [](const CircularOrbit& o) { return o.rate; }, R"doc(The orbit rate n, in rad/s.

Examples
--------
>>> import gyrostat
>>> gyrostat.Orbit(0.001).rate
0.001
)doc")
        .def_property_readonly("normal", [](const CircularOrbit& o) { return o.normal; }, R"doc(The unit normal N of the orbit plane, in inertial axes.

Examples
--------
>>> import gyrostat
>>> gyrostat.Orbit(0.001, normal=[0.0, 0.0, 2.0]).normal
array([0., 0., 1.])
)doc")
        .def_property_readonly("phase", [](const CircularOrbit& o) { return o.phase; }, R"doc(The body's angle on the orbit at t = 0 from e1, in rad.

Examples
--------
>>> import gyrostat
>>> gyrostat.Orbit(0.001, phase=0.5).phase
0.5
)doc")
        .def("position", [](const CircularOrbit& o, const py::object& t) { return o.position(scalar(t, "Orbit.position: t")); },
             py::arg("t"), R"doc(The unit vector c(t) from the planet to the body, in inertial axes.

Parameters
----------
t : float
    Time, in s.

Examples
--------
>>> import gyrostat
>>> gyrostat.Orbit(1.0).position(0.5 * 3.141592653589793).round(12)
array([0., 1., 0.])
)doc")
        .def("frame", [](const CircularOrbit& o, const py::object& t) { return o.frame(scalar(t, "Orbit.frame: t")); },
             py::arg("t"), R"doc(The orbit frame's axes (x along track, y = -N, z nadir) as the columns of a matrix, in inertial axes.

Parameters
----------
t : float
    Time, in s.

Returns
-------
numpy.ndarray, shape (3, 3)
    The rotation orbit frame to inertial axes.

Examples
--------
>>> import gyrostat
>>> gyrostat.Orbit(1.0).frame(0.0)
array([[ 0.,  0., -1.],
       [ 1.,  0.,  0.],
       [ 0., -1.,  0.]])
)doc")
        .def("__eq__", [](const CircularOrbit& a, const CircularOrbit& b) { return a.same_as(b); })
        .def("__repr__", &CircularOrbit::text);
    cls.attr("__hash__") = py::none();
    cls.attr("description") = std::string(CircularOrbit::description);
    cls.attr("parameters") = py::tuple(parameters);
}

void expose_body(py::module_& m) {
    py::class_<Body>(m, "Body", R"doc(A rigid body or gyrostat: its moments of inertia and the constant angular momentum of its rotors.

Give either its principal moments (the body axes are then its principal axes) or its inertia
tensor in any body frame. With a tensor, the models run in the principal axes (the rotation is
``principal_axes``) and every state, torque parameter given in body axes, rotor and event is
given and returned in your frame; the named outputs (Euler angles, nutation angle) are those of
the principal axes, body z being the third principal axis.

Parameters
----------
moments : array_like, shape (3,), optional
    Principal moments of inertia (A1, A2, A3), in kg m^2: finite, positive, and each at most
    the sum of the other two (the triangle inequality of a real body).
rotor : array_like, shape (3,), optional
    Constant gyrostatic momentum k of rotors spinning at a constant rate relative to the
    carrier, in body axes, in kg m^2/s (N m s). Default: none (a rigid body).
inertia : array_like, shape (3, 3), optional
    Instead of ``moments``: the inertia tensor in your body frame, in kg m^2 (products of
    inertia off the diagonal, I_xy = -sum m x y). Finite and symmetric; its eigenvalues, the
    principal moments, must satisfy the checks of ``moments``. Its principal axes are ordered
    and signed to be the rotation closest to the identity: a diagonal tensor keeps its axes.

Examples
--------
>>> import gyrostat
>>> gyrostat.Body([2.0, 2.0, 1.0])
Body(A1=2, A2=2, A3=1, k=[0, 0, 0])
>>> gyrostat.Body([3.0, 2.0, 1.0], rotor=[0.0, 0.0, 0.1])
Body(A1=3, A2=2, A3=1, k=[0, 0, 0.1])
>>> body = gyrostat.Body(inertia=[[2.5, 0.3, 0.0], [0.3, 2.0, 0.0], [0.0, 0.0, 1.0]])
>>> body.moments.round(6)
array([2.640512, 1.859488, 1.      ])
>>> body.principal_axes.round(6)
array([[ 0.905589, -0.424155,  0.      ],
       [ 0.424155,  0.905589,  0.      ],
       [ 0.      ,  0.      ,  1.      ]])
)doc")
        .def(py::init([](const py::object& moments, const py::object& rotor, const py::object& inertia) {
                 const Vec3 k = rotor.is_none() ? Vec3::Zero() : vec3(rotor, "Body: rotor");
                 if (moments.is_none() == inertia.is_none())
                     throw py::type_error("Body: give either moments=[A1, A2, A3] or inertia=[[...], [...], [...]], not " +
                                          std::string(moments.is_none() ? "neither" : "both"));
                 if (!inertia.is_none()) return Body::from_inertia(mat3(inertia, "Body: inertia"), k);
                 return Body(vec3(moments, "Body: moments"), k);
             }),
             py::arg("moments") = py::none(), py::arg("rotor") = py::none(), py::arg("inertia") = py::none())
        .def_property_readonly("moments", &Body::moments, R"doc(The principal moments of inertia (A1, A2, A3), in kg m^2.

Examples
--------
>>> import gyrostat
>>> gyrostat.Body([2.0, 2.0, 1.0]).moments
array([2., 2., 1.])
)doc")
        .def_property_readonly("rotor", [](const Body& b) -> Vec3 { return b.principal_axes() * b.rotor(); },
                               R"doc(The rotors' constant momentum k in your body axes, in kg m^2/s (zero for a rigid body).

Examples
--------
>>> import gyrostat
>>> gyrostat.Body([3.0, 2.0, 1.0], rotor=[0.0, 0.0, 0.1]).rotor
array([0. , 0. , 0.1])
)doc")
        .def_property_readonly("principal_rotor", &Body::rotor, R"doc(The rotors' momentum k in principal axes, in kg m^2/s (``principal_axes.T @ rotor``).

Examples
--------
>>> import gyrostat
>>> gyrostat.Body(inertia=[[1.0, 0.0, 0.0], [0.0, 2.0, 0.3], [0.0, 0.3, 1.5]], rotor=[0.0, 0.0, 0.1]).principal_rotor.round(6)
array([0.      , 0.042416, 0.090559])
)doc")
        .def_property_readonly("inertia", &Body::inertia, R"doc(The inertia tensor in your body frame, in kg m^2.

Examples
--------
>>> import gyrostat
>>> gyrostat.Body([3.0, 2.0, 1.0]).inertia
array([[3., 0., 0.],
       [0., 2., 0.],
       [0., 0., 1.]])
)doc")
        .def_property_readonly("principal_axes", &Body::principal_axes, R"doc(R: the principal axes as columns, in your body frame (v = R v_principal, det R = +1).

The identity for a body given by its moments.

Examples
--------
>>> import gyrostat
>>> gyrostat.Body([3.0, 2.0, 1.0]).principal_axes
array([[1., 0., 0.],
       [0., 1., 0.],
       [0., 0., 1.]])
)doc")
        .def_property_readonly("principal", &Body::principal, R"doc(Whether the body was given in its principal axes (``principal_axes`` is the identity).

Examples
--------
>>> import gyrostat
>>> gyrostat.Body(inertia=[[2.0, 0.1, 0.0], [0.1, 2.0, 0.0], [0.0, 0.0, 1.0]]).principal
False
)doc")
        .def("with_rotor", &Body::with_rotor, py::arg("rotor"), R"doc(The same body with the rotors' momentum k (kg m^2/s, your body frame).

Its moments and principal axes are this body's, bit for bit (a tensor given again would be
decomposed again, and its axes could differ in their last bits).

Parameters
----------
rotor : array_like
    k, three numbers in your body frame.

Examples
--------
>>> import gyrostat
>>> gyrostat.Body([3.0, 2.0, 1.0]).with_rotor([0.0, 0.0, 0.5]).rotor
array([0. , 0. , 0.5])
)doc")
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

    expose_orbit(m);

    // Every alternative of AnyTorque, from its declaration: a new torque needs nothing here.
    m.attr("torque_types") = expose_torques(m, static_cast<AnyTorque*>(nullptr));

    // What only some torques have: derived quantities users and the papers' analyses ask for.
    bound<torque::ResistiveMedium>(m).def(
        "at", [](const torque::ResistiveMedium& x, const py::object& t) { return x.at(scalar(t, "ResistiveMedium.at: t")); },
        py::arg("t"), R"doc(The resistance matrix D(t) = D0 + D1 t + D2 t^2 + ... at time t.

Parameters
----------
t : float
    Time, in s.

Returns
-------
numpy.ndarray, shape (3, 3)
    D(t), in N m s (the torque is M = -D(t) omega).

Examples
--------
>>> import gyrostat
>>> medium = gyrostat.ResistiveMedium(coefficients=[[[0.5, 0, 0], [0, 0.5, 0], [0, 0, 0.5]],
...                                                 [[0.1, 0, 0], [0, 0.1, 0], [0, 0, 0.1]]])
>>> medium.at(2.0)
array([[0.7, 0. , 0. ],
       [0. , 0.7, 0. ],
       [0. , 0. , 0.7]])
)doc");
    bound<torque::ViscousCavity>(m)
        .def_static(
            "sphere",
            [](const py::object& density, const py::object& viscosity, const py::object& radius) {
                return torque::ViscousCavity::sphere(scalar(density, "ViscousCavity.sphere: density"),
                                                     scalar(viscosity, "ViscousCavity.sphere: viscosity"),
                                                     scalar(radius, "ViscousCavity.sphere: radius"));
            },
            py::arg("density"), py::arg("viscosity"), py::arg("radius"), R"doc(A spherical cavity of this radius (P0 from the sphere's formula).

Parameters
----------
density : float
    Fluid density rho, in kg/m^3.
viscosity : float
    Kinematic viscosity nu, in m^2/s.
radius : float
    Cavity radius b, in m.

Examples
--------
>>> import gyrostat
>>> gyrostat.ViscousCavity.sphere(density=1000.0, viscosity=1e-3, radius=0.1)
ViscousCavity(density=1000, viscosity=0.001, p0=4.787188805470163e-09)
)doc")
        .def_property_readonly("kappa", &torque::ViscousCavity::kappa, R"doc(kappa = rho P0 / nu, in kg s: the strength of the cavity torque.

Examples
--------
>>> import gyrostat
>>> gyrostat.ViscousCavity.sphere(density=1000.0, viscosity=1e-3, radius=0.1).kappa
0.004787188805470163
)doc")
        .def_property_readonly("equivalent_radius", &torque::ViscousCavity::equivalent_radius,
                               R"doc(The radius of the sphere with this P0, in m.

Examples
--------
>>> import gyrostat
>>> gyrostat.ViscousCavity.sphere(density=1000.0, viscosity=1e-3, radius=0.1).equivalent_radius
0.10000000000000002
)doc");
    bound<torque::GravityGradient>(m).def(
        "precession_rate",
        [](const torque::GravityGradient& x, const py::object& moments, const py::object& omega, const py::object& quaternion,
           const py::object& orbit) {
            const Vec3 J = vec3(moments, "GravityGradient.precession_rate: moments");
            const Vec3 w = vec3(omega, "GravityGradient.precession_rate: omega");
            const Eigen::Vector4d q = unit_quaternion(vec4(quaternion, "GravityGradient.precession_rate: quaternion"));
            if (orbit.is_none()) return x.precession_rate(J, w, q);
            return torque::GravityGradient::precession_rate(J, w, q, orbit.cast<const torque::CircularOrbit&>());
        },
        py::arg("moments"), py::arg("omega"), py::arg("quaternion"), py::arg("orbit") = py::none(),
        R"doc(The rate at which G precesses about the orbit normal, averaged over the orbit and the free motion.

For a symmetric body (A, A, C): -3 n^2 (C - A)(3 cos^2 nutation - 1) cos i / (4 |G|), with the
nutation angle between body z and G and i the angle between G and the orbit normal.

Parameters
----------
moments : array_like, shape (3,)
    Principal moments (A, A, C), in kg m^2.
omega : array_like, shape (3,)
    Angular velocity in body axes, in rad/s.
quaternion : array_like, shape (4,)
    The attitude (w, x, y, z), body to inertial.
orbit : gyrostat.Orbit, optional
    The orbit (the model's); default: the torque's own (orbit_rate, orbit_normal, phase).

Returns
-------
float
    The precession rate, in rad/s (about the orbit normal).

Examples
--------
>>> import gyrostat as g
>>> g.GravityGradient(0.01).precession_rate([1.0, 1.0, 2.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0, 0.0])
-7.5e-05
>>> g.GravityGradient().precession_rate([1.0, 1.0, 2.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0, 0.0], orbit=g.Orbit(0.01))
-7.5e-05
)doc");
    bound<torque::DipoleFieldTorque>(m).def(
        "field", [](const torque::DipoleFieldTorque& x, const py::object& t) { return x.field(scalar(t, "DipoleFieldTorque.field: t")); },
        py::arg("t"), R"doc(The planet's field at the body, in inertial axes.

Parameters
----------
t : float
    Time, in s.

Returns
-------
numpy.ndarray, shape (3,)
    B(t) = B0 [3 (d . c) c - d], in T.

Examples
--------
>>> import gyrostat as g
>>> g.DipoleFieldTorque(dipole=[0.0, 0.0, 1.0], field_strength=2e-5, orbit_rate=0.001).field(0.0)
array([0.e+00, 0.e+00, 2.e-05])
)doc");
    bound<torque::MovingMassDamper>(m).def(
        "S",
        [](const torque::MovingMassDamper& x, const py::object& A, const py::object& C) {
            return x.S(scalar(A, "MovingMassDamper.S: A"), scalar(C, "MovingMassDamper.S: C"));
        },
        py::arg("A"), py::arg("C"), R"doc(S of paper 001 eq. (3) for a symmetric body (A, A, C).

Parameters
----------
A : float
    Equatorial moment of inertia, in kg m^2.
C : float
    Axial moment of inertia, in kg m^2.

Examples
--------
>>> import gyrostat
>>> gyrostat.MovingMassDamper(mass=0.5, arm=0.5, frequency=0.5, damping=0.5).S(2.0, 1.0)
0.0625
)doc");
}

}  // namespace gyrostat::bindings
