// Part 2 of the engine's integration: the models GYROSTAT_SOLVED_MODELS (engine.hpp)
// assigns to part 2, one of four translation units for parallel builds.
#define GYROSTAT_SOLVE_PART 2
#include "gyrostat/solve_system.hpp"

namespace gyrostat {

GYROSTAT_SOLVED_MODELS(GYROSTAT_SOLVE_IN_PART)

}  // namespace gyrostat
