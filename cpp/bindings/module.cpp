// gyrostat._core: translation of types between Python and the C++ core; no physics here.
#include "expose.hpp"

PYBIND11_MODULE(_core, m) {
    m.doc() = "gyrostat C++ core: bodies, torques, models, integrators, ensembles";
    gyrostat::bindings::expose_body(m);
    gyrostat::bindings::expose_attitude(m);
    gyrostat::bindings::expose_orthogonal(m);
    gyrostat::bindings::expose_models(m);
    gyrostat::bindings::expose_integrate(m);
    gyrostat::bindings::expose_torque_free(m);
    gyrostat::bindings::expose_lagrange(m);
#ifdef GYROSTAT_VERSION
    m.attr("__version__") = GYROSTAT_VERSION;
#endif
}
