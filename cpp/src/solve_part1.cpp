// Instantiates the engine for the models at indices 1, 5, 9, 13 of AnyModel (solve_system.hpp):
// one of four translation units, for parallel builds.
#include "gyrostat/solve_system.hpp"

namespace gyrostat {

GYROSTAT_INSTANTIATE_SOLVE_PART(1)

}  // namespace gyrostat
