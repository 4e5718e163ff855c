// Instantiates the engine for the models at indices 2, 6, 10, 14 of AnyModel (solve_system.hpp):
// one of four translation units, for parallel builds.
#include "gyrostat/solve_system.hpp"

namespace gyrostat {

GYROSTAT_INSTANTIATE_SOLVE_PART(2)

}  // namespace gyrostat
