// Bindings of paper 003's models (placeholder: filled by the model's implementation).
#include "expose.hpp"

namespace gyrostat::bindings {

void expose_lagrange(pybind11::module_& /*m*/) {}

}  // namespace gyrostat::bindings
