// The user's torque (torque/custom.hpp): a Python callable, or a compiled function given as a
// scipy.LowLevelCallable, behind the core's TorqueFunction. Translation only: the Python call
// takes the GIL, converts ω (and q) to arrays and M back, and keeps the user's exception so that
// it reaches the caller as it was raised.
#include <Python.h>

#include <algorithm>
#include <functional>
#include <tuple>
#include <type_traits>
#include <memory>
#include <string>

#include "convert.hpp"
#include "expose.hpp"
#include "gyrostat/integrate/control.hpp"
#include "gyrostat/torque/custom.hpp"

namespace gyrostat::bindings {

namespace {

/// A Python callable f(t, omega[, quaternion]) -> M and its optional jac(t, omega[, quaternion]) -> dM/domega.
/// Each call holds the GIL (ensembles call it one thread at a time). The first exception it
/// raises is kept for solve_ensemble to re-raise (a single solve propagates it directly); a
/// KeyboardInterrupt becomes integrate::Interruption, which the run turns into its status.
class PythonTorqueFunction final : public torque::TorqueFunction {
public:
    PythonTorqueFunction(py::object function, py::object jacobian, std::string label)
        : function_(std::move(function)), jacobian_(std::move(jacobian)), label_(std::move(label)) {}
    ~PythonTorqueFunction() override {
        if (!Py_IsInitialized()) {  // at exit: leak rather than touch a finalised interpreter
            function_.release(), jacobian_.release();
            return;
        }
        py::gil_scoped_acquire gil;
        function_ = py::object(), jacobian_ = py::object();
    }

    Vec3 torque(double t, const Vec3& omega, const Eigen::Vector4d* quaternion) const override {
        py::gil_scoped_acquire gil;
        const py::object value = call(function_, t, omega, quaternion);
        Vec3 moment;
        if (read_flat(value, 3, moment.data())) return moment;
        return numbers(value, 3, 0, "CustomTorque '" + label_ + "' returned a value that, as M in body axes,");
    }
    bool jacobian(double t, const Vec3& omega, const Eigen::Vector4d* quaternion, Mat3& d) const override {
        if (jacobian_.is_none()) return false;
        py::gil_scoped_acquire gil;
        const py::object value = call(jacobian_, t, omega, quaternion);
        d = numbers(value, 3, 3, "CustomTorque '" + label_ + "' Jacobian returned a value that, as dM/domega,");
        return true;
    }

    /// Forgets an earlier run's exception (GIL held).
    void reset() const { error_.reset(); }
    /// Re-raises the first exception the user's function raised in the last run (GIL held).
    void rethrow() const {
        if (error_) {
            auto error = std::move(error_);
            throw std::move(*error);
        }
    }

private:
    py::object call(const py::object& f, double t, const Vec3& omega, const Eigen::Vector4d* quaternion) const {
        try {
            py::array_t<double> w(3, omega.data());
            if (quaternion) return f(t, w, py::array_t<double>(4, quaternion->data()));
            return f(t, w);
        } catch (py::error_already_set& e) {
            // Ctrl-C while the function ran (or its own KeyboardInterrupt): the run stops there and
            // keeps what it computed (status interrupted), as Ctrl-C between two steps does
            if (e.matches(PyExc_KeyboardInterrupt)) throw integrate::Interruption();
            if (!error_) error_ = std::make_unique<py::error_already_set>(e);
            throw;
        }
    }

    py::object function_;
    py::object jacobian_;
    std::string label_;
    mutable std::unique_ptr<py::error_already_set> error_;  // guarded by the GIL
};

/// The two signatures a compiled torque may have (torque/custom.hpp), as the LowLevelCallable
/// names them with spaces and const removed.
constexpr const char* scalar_signature = "int(double,double*,double*,double*,void*)";
constexpr const char* vector_signature = "int(int,double*,double*,double*,double*,void*)";
constexpr const char* signatures_text =
    "int (double t, const double *omega, const double *quaternion, double *moment, void *user_data), or "
    "vectorised over n members (structure of arrays: omega[i*n + l]) int (int n, const double *t, const double "
    "*omega, const double *quaternion, double *moment, void *user_data)";

/// The signature with spaces and const removed.
std::string normalised(std::string signature) {
    for (auto at = signature.find("const"); at != std::string::npos; at = signature.find("const")) signature.erase(at, 5);
    signature.erase(std::remove_if(signature.begin(), signature.end(), [](char c) { return c == ' '; }), signature.end());
    return signature;
}

bool is_low_level_callable(const py::handle& obj) {
    return PyTuple_Check(obj.ptr()) && std::string(py::str(py::type::of(obj).attr("__name__"))) == "LowLevelCallable";
}

/// A compiled function: its pointer, user_data and whether it has the vectorised signature.
struct Compiled {
    void* pointer;
    void* user_data;
    bool vectorised;
};

/// The function pointer and user_data of a scipy.LowLevelCallable, its signature checked
/// (`vector`: the vectorised one is accepted too; the Jacobian has only the scalar one).
Compiled compiled(const py::handle& callable, const std::string& what, bool vector) {
    PyObject* capsule = PyTuple_GET_ITEM(callable.ptr(), 0);
    const char* signature = PyCapsule_GetName(capsule);
    const std::string given = signature ? normalised(signature) : "";
    const bool vectorised = vector && given == vector_signature;
    if (given != scalar_signature && !vectorised)
        throw py::value_error(what + ": the LowLevelCallable's signature is '" + std::string(signature ? signature : "") +
                              "'; a compiled " + (vector ? std::string("torque is ") + signatures_text
                                                         : std::string("Jacobian is int (double t, const double *omega, "
                                                                       "const double *quaternion, double *jacobian, "
                                                                       "void *user_data)")));
    void* pointer = PyCapsule_GetPointer(capsule, signature);
    if (!pointer) throw py::error_already_set();
    return {pointer, PyCapsule_GetContext(capsule), vectorised};
}

std::string label_of(const py::handle& function, const py::object& name) {
    if (!name.is_none()) return py::str(name);
    if (is_low_level_callable(function)) {
        const py::object inner = function.attr("function");
        if (py::hasattr(inner, "__name__")) return py::str(inner.attr("__name__"));
        return "compiled";
    }
    if (py::hasattr(function, "__qualname__")) return py::str(function.attr("__qualname__"));
    return py::str(py::type::of(function).attr("__name__"));
}

/// What a CustomTorque was made from (torque::Custom::origin): the factory and its keyword
/// arguments when it was given `parameters`, and the function and Jacobian the core calls. The
/// last reference may go on any thread: the GIL is taken to release the objects.
struct Origin {
    py::object factory, jacobian_factory, function, jacobian;
    py::dict arguments;
    ~Origin() {
        if (!Py_IsInitialized()) {  // at exit: leak rather than touch a finalised interpreter
            factory.release(), jacobian_factory.release(), function.release(), jacobian.release(), arguments.release();
            return;
        }
        py::gil_scoped_acquire gil;
        factory = jacobian_factory = function = jacobian = py::object();
        arguments = py::dict();
    }
};

/// The origin's `part` (None, or an empty dict, for a torque made in C++ without one).
template <class Part>
py::object origin_part(const torque::Custom& x, Part Origin::*part) {
    if (!x.origin) return std::is_same_v<Part, py::dict> ? py::object(py::dict()) : py::object(py::none());
    return static_cast<const Origin*>(x.origin.get())->*part;
}

/// `parameters` as a dict of names (str) to the factories' keyword arguments (sensitivities move
/// the numbers among them).
py::dict named_arguments(const py::object& parameters, const std::string& what) {
    if (!py::isinstance<py::dict>(parameters))
        throw py::type_error(what + ": parameters must be a dict of names to values, got " + shown(parameters));
    py::dict arguments;
    for (const auto& [key, value] : py::reinterpret_borrow<py::dict>(parameters)) {
        if (!py::isinstance<py::str>(key))
            throw py::type_error(what + ": a parameter's name must be a str, got " + shown(py::reinterpret_borrow<py::object>(key)));
        arguments[key] = value;
    }
    return arguments;
}

/// factory(**arguments), the factory checked to be a Python callable.
py::object made_by(const py::object& factory, const py::dict& arguments, const std::string& what) {
    if (is_low_level_callable(factory) || !PyCallable_Check(factory.ptr()))
        throw py::type_error(what + ": with parameters, give a factory (a Python callable) that takes them as keyword "
                             "arguments and returns the torque function (or its Jacobian), got " + shown(factory));
    return factory(**arguments);
}

torque::Custom make_custom(const py::object& given_function, const py::object& given_jacobian, bool attitude,
                           const py::object& name, const py::object& parameters) {
    auto origin = std::make_shared<Origin>();
    origin->arguments = parameters.is_none() ? py::dict() : named_arguments(parameters, "CustomTorque '" + label_of(given_function, name) + "'");
    if (!parameters.is_none()) {
        const std::string what = "CustomTorque '" + label_of(given_function, name) + "'";
        origin->factory = given_function, origin->jacobian_factory = given_jacobian;
        origin->function = made_by(given_function, origin->arguments, what);
        origin->jacobian = given_jacobian.is_none() ? py::none() : made_by(given_jacobian, origin->arguments, what + " Jacobian");
    } else {
        origin->factory = origin->jacobian_factory = py::none();
        origin->function = given_function, origin->jacobian = given_jacobian;
    }
    const py::object& function = origin->function;
    const py::object& jacobian = origin->jacobian;
    const std::string label = label_of(name.is_none() && !parameters.is_none() ? given_function : function, name);
    const std::string what = "CustomTorque '" + label + "'";
    const bool low_level = is_low_level_callable(function);
    if (!low_level && !PyCallable_Check(function.ptr()))
        throw py::type_error(what + ": the function must be a Python callable f(t, omega[, quaternion]) or a "
                             "scipy.LowLevelCallable, got " + shown(function));
    if (!jacobian.is_none() && is_low_level_callable(jacobian) != low_level)
        throw py::type_error(what + ": give the function and its Jacobian both as Python callables or both as "
                             "LowLevelCallables");
    if (!jacobian.is_none() && !low_level && !PyCallable_Check(jacobian.ptr()))
        throw py::type_error(what + ": the Jacobian must be callable, got " + shown(jacobian));
    std::shared_ptr<const torque::TorqueFunction> core;
    if (low_level) {
        const Compiled f = compiled(function, what, true);
        torque::JacobianFunctionPointer df = nullptr;
        void* jacobian_data = nullptr;
        if (!jacobian.is_none()) {
            const Compiled d = compiled(jacobian, what + " Jacobian", false);
            df = reinterpret_cast<torque::JacobianFunctionPointer>(d.pointer), jacobian_data = d.user_data;
        }
        if (f.vectorised)
            core = std::make_shared<torque::CompiledTorqueFunction>(
                label, torque::VectorForm{reinterpret_cast<torque::VectorTorqueFunctionPointer>(f.pointer), f.user_data},
                df, jacobian_data);
        else
            core = std::make_shared<torque::CompiledTorqueFunction>(
                label, reinterpret_cast<torque::TorqueFunctionPointer>(f.pointer), f.user_data, df, jacobian_data);
    } else {
        core = std::make_shared<PythonTorqueFunction>(function, jacobian, label);
    }
    torque::Custom custom(core, label, attitude);
    custom.origin = std::move(origin);
    return custom;
}

}  // namespace

static void for_each_python_torque(const AnyModel& model, const std::function<void(const torque::TorqueFunction&)>& f) {
    std::visit(
        [&](const auto& m) {
            if constexpr (has_torques<std::decay_t<decltype(m)>>::value) {
                for (const auto& part : m.torques().parts())
                    if (const torque::TorqueFunction* user = std::visit([](const auto& x) { return user_function_of(x); }, part))
                        f(*user);
            }
        },
        model);
}

void reset_python_torques(const AnyModel& model) {
    for_each_python_torque(model, [](const torque::TorqueFunction& f) {
        if (const auto* p = dynamic_cast<const PythonTorqueFunction*>(&f)) p->reset();
    });
}
void rethrow_python_torques(const AnyModel& model) {
    for_each_python_torque(model, [](const torque::TorqueFunction& f) {
        if (const auto* p = dynamic_cast<const PythonTorqueFunction*>(&f)) p->rethrow();
    });
}

void expose_custom_torque(py::module_& m) {
    using torque::Custom;
    py::class_<Custom> cls(m, Custom::python_name,
                       R"doc(A torque the user writes, in body axes (scene type ``"custom"``).

M = f(t, omega) or, with ``attitude=True``, f(t, omega, quaternion): omega in rad/s (body axes),
the quaternion (w, x, y, z) body to inertial, M in N m (body axes).

Parameters
----------
function : callable or scipy.LowLevelCallable
    A Python callable (each call holds the GIL and costs the library 0.2-0.6 us when it returns a
    float64 NumPy array or a tuple or list of floats, plus the function's own time:
    bench/custom_torque.py; other returns, e.g. ints or a float32 array, take a general
    conversion, about 0.6 us more; an ensemble of such members runs on one thread, since more
    would only pass the GIL back and forth; its exception reaches the caller as raised, but
    Ctrl-C in it ends the run with status "interrupted", keeping what was computed), or a
    ``scipy.LowLevelCallable`` (from ``numba.cfunc``, ctypes or cffi) of one of the C signatures::

        int f(double t, const double *omega, const double *quaternion, double *moment, void *user_data)
        int f(int n, const double *t, const double *omega, const double *quaternion, double *moment,
              void *user_data)

    called from C++ without the GIL on every thread (quaternion is NULL without the attitude;
    it returns 0, and a non-zero code stops the run with an error naming the torque). The
    second, vectorised, takes n members at once as structure of arrays: t[l] the time of member
    l, omega[i*n + l] its omega_i (3n numbers), quaternion[i*n + l] its q_i, i = w, x, y, z (4n
    numbers, or NULL), moment[i*n + l] its M_i (3n numbers to write); member l's M must depend on
    member l's numbers only. The SIMD batches of ``solve_ensemble`` (DOP853) call it once per
    stage for their lanes (n = ``gyrostat.simd_lanes``), every other path with n = 1; a scalar
    function keeps its members out of the batches (one at a time), and so does a body given by
    its inertia tensor (the batches do not rotate the user's frame). In numba::

        @numba.cfunc(numba.types.intc(numba.types.intc, *[numba.types.CPointer(numba.types.double)] * 4,
                                      numba.types.voidptr))
        def drag(n, t, omega, quaternion, moment, user_data):
            w, m = numba.carray(omega, (3, n)), numba.carray(moment, (3, n))
            for i in range(3):
                for l in range(n):
                    m[i, l] = -0.1 * w[i, l]
            return 0

        g.CustomTorque(scipy.LowLevelCallable(drag.ctypes))
jacobian : callable or scipy.LowLevelCallable, optional
    dM/domega, of the same kind and arguments as ``function`` (a 3x3 array; compiled: 9 numbers
    row-major, the scalar signature, also beside a vectorised function). None: central difference
    quotients (6 calls) for the implicit methods.
attitude : bool
    The function takes the quaternion; only models with the attitude take the torque.
name : str, optional
    The name in messages and the repr (default: the function's name).
parameters : dict of str, optional
    The torque's own parameters (numbers, or any value a factory takes). Then ``function`` (and ``jacobian``) are factories: called once
    here as ``function(**parameters)``, they return the torque function (a Python callable or a
    ``scipy.LowLevelCallable``) as above. Sensitivities (``gyrostat.solve(..., sensitivities=
    ["CustomTorque.c"])``) move a number among them by calling the factory again, and take dM/dc
    as a central difference quotient of the two torques made.

Examples
--------
>>> import numpy as np, gyrostat as g
>>> drag = g.CustomTorque(lambda t, omega: -0.1 * omega, name="drag")
>>> drag(0.0, [1.0, 0.0, 0.0], [1.0, 2.0, 3.0])
array([-0.1, -0. , -0. ])
>>> def drag_with(c):
...     return lambda t, omega: -c * omega
>>> g.CustomTorque(drag_with, parameters={"c": 0.2}, name="drag")(0.0, [1.0, 0.0, 0.0], [1.0, 2.0, 3.0])
array([-0.2, -0. , -0. ])
)doc");
    cls.def(py::init(&make_custom), py::arg("function"), py::arg("jacobian") = py::none(), py::kw_only(),
             py::arg("attitude") = false, py::arg("name") = py::none(), py::arg("parameters") = py::none())
        .def("__call__",
             [](const Custom& x, const py::object& t, const py::object& omega, const py::object& moments,
                const py::object& quaternion) {
                 const std::string what = "CustomTorque '" + x.label + "'";
                 if (x.attitude && quaternion.is_none())
                     throw py::value_error(what + " depends on the attitude: give quaternion=(w, x, y, z)");
                 const Eigen::Vector4d q = x.attitude ? unit_quaternion(vec4(quaternion, what + ": quaternion"))
                                                      : Eigen::Vector4d(1, 0, 0, 0);
                 return x(scalar(t, what + ": t"), vec3(omega, what + ": omega"), vec3(moments, what + ": moments"),
                          x.attitude ? &q : nullptr);
             },
             py::arg("t"), py::arg("omega"), py::arg("moments"), py::arg("quaternion") = py::none(),
             R"doc(The user's function at (t, omega[, quaternion]): the torque in body axes.

Parameters
----------
t : float
    Time, in s.
omega : array_like, shape (3,)
    Angular velocity in body axes, in rad/s.
moments : array_like, shape (3,)
    Principal moments of inertia, in kg m^2 (not passed to the function).
quaternion : array_like, shape (4,), optional
    The attitude (w, x, y, z), body to inertial: required when the torque takes it.

Returns
-------
numpy.ndarray, shape (3,)
    The torque, in N m.

Examples
--------
>>> import gyrostat as g
>>> g.CustomTorque(lambda t, omega: -0.5 * omega)(0.0, [0.0, 0.0, 2.0], [1.0, 1.0, 1.0])
array([-0., -0., -1.])
)doc")
        .def_readonly("name", &Custom::label, R"doc(The name used in messages and the repr (str).

Examples
--------
>>> import gyrostat as g
>>> g.CustomTorque(lambda t, omega: -omega, name="drag").name
'drag'
)doc")
        .def_readonly("attitude", &Custom::attitude, R"doc(Whether the function takes the quaternion (bool).

Examples
--------
>>> import gyrostat as g
>>> g.CustomTorque(lambda t, omega, q: -omega, attitude=True).attitude
True
)doc")
        .def_property_readonly("function", [](const Custom& x) { return origin_part(x, &Origin::function); },
                               R"doc(The torque function the core calls (made by the factory when the torque has
parameters).

Examples
--------
>>> import gyrostat as g
>>> g.CustomTorque(lambda t, omega: -0.3 * omega).function(0.0, 1.0)
-0.3
)doc")
        .def_property_readonly("jacobian", [](const Custom& x) { return origin_part(x, &Origin::jacobian); },
                               R"doc(The Jacobian dM/domega the core calls, or None (difference quotients).

Examples
--------
>>> import gyrostat as g
>>> g.CustomTorque(lambda t, omega: -omega).jacobian is None
True
)doc")
        .def_property_readonly("factory", [](const Custom& x) { return origin_part(x, &Origin::factory); },
                               R"doc(The factory that made the function from ``arguments``, or None (a torque
given without parameters).

Examples
--------
>>> import gyrostat as g
>>> def drag_with(c):
...     return lambda t, omega: -c * omega
>>> g.CustomTorque(drag_with, parameters={"c": 0.2}).factory is drag_with
True
)doc")
        .def_property_readonly("jacobian_factory", [](const Custom& x) { return origin_part(x, &Origin::jacobian_factory); },
                               R"doc(The factory that made the Jacobian from ``arguments``, or None.

Examples
--------
>>> import gyrostat as g
>>> g.CustomTorque(lambda c: (lambda t, omega: -c * omega), parameters={"c": 0.2}).jacobian_factory is None
True
)doc")
        .def_property_readonly("arguments", [](const Custom& x) { return py::dict(origin_part(x, &Origin::arguments)); },
                               R"doc(The parameters the factories were called with (a dict; empty without parameters).

Examples
--------
>>> import gyrostat as g
>>> g.CustomTorque(lambda c: (lambda t, omega: -c * omega), parameters={"c": 0.2}).arguments
{'c': 0.2}
)doc")
        .def_property_readonly("vectorised", [](const Custom& x) { return x.function->vector_form().function != nullptr; },
                               R"doc(Whether the function is compiled with the vectorised signature (bool): then the
ensembles' SIMD batches take its members.

Examples
--------
>>> import gyrostat as g
>>> g.CustomTorque(lambda t, omega: -omega).vectorised
False
)doc")
        .def("assumptions", [](const Custom&, const py::object&) { return py::list(); }, py::arg("motion"),
             R"doc(A user's torque states no assumption.

Parameters
----------
motion : gyrostat._core.Motion
    The motion checked (not used).

Returns
-------
list
    Empty.

Examples
--------
>>> import gyrostat as g
>>> g.CustomTorque(lambda t, omega: -omega).assumptions(g._core.Motion([1.0, 2.0, 3.0], [[0.0, 0.0, 1.0]]))
[]
)doc")
        .def("__repr__", [](const Custom& x) {
            const py::dict arguments = origin_part(x, &Origin::arguments);
            return "CustomTorque(" + x.label + (x.attitude ? ", attitude=True" : "") +
                   (arguments.empty() ? std::string() : ", parameters=" + std::string(py::str(arguments))) + ")";
        });
    cls.attr("kind") = std::string(Custom::name);
    cls.attr("description") = std::string(Custom::description);
    cls.attr("parameters") = py::tuple();
    cls.attr("affine_in") = py::tuple();
    cls.attr("inverse_in") = py::tuple();
    cls.attr("needs_attitude") = false;
    cls.attr("has_averaged") = false;
}

}  // namespace gyrostat::bindings
