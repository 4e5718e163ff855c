// Instantiates the engine's solve for the lagrange models (one translation unit per family: parallel builds).
#include "gyrostat/solve_system.hpp"

namespace gyrostat {

GYROSTAT_DEFINE_SOLVE(model::LagrangeTop)
GYROSTAT_DEFINE_SOLVE(model::LagrangeAveraged)

}  // namespace gyrostat
