// Instantiates the engine for the models at indices 0, 4, 8, 12 of AnyModel (solve_system.hpp):
// one of four translation units, for parallel builds.
#include "gyrostat/solve_system.hpp"

namespace gyrostat {

GYROSTAT_INSTANTIATE_SOLVE_PART(0)

}  // namespace gyrostat
