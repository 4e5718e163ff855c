// Compiled parts of paper 004's model: none. The model (gyrostat/model/orthogonal.hpp) is a
// header-only System so that every integrator inlines its right-hand side.
namespace gyrostat {}
