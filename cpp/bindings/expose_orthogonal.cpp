// Bindings of paper 004's models (placeholder: filled by the model's implementation).
#include "expose.hpp"

namespace gyrostat::bindings {

void expose_orthogonal(pybind11::module_& /*m*/) {}

}  // namespace gyrostat::bindings
