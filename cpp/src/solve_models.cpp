// The engine's integration of every model: the explicit instantiations of integrate::solve and
// solve_system for each model GYROSTAT_SOLVED_MODELS (engine.hpp) lists, in this one translation
// unit (every other one declares them extern: solve_system.hpp).
#define GYROSTAT_SOLVING_MODELS
#include "gyrostat/solve_system.hpp"

namespace gyrostat {

GYROSTAT_SOLVED_MODELS(GYROSTAT_INSTANTIATE_SOLVE)

}  // namespace gyrostat
