// Instantiates the engine's solve for the averaged models (one translation unit per family: parallel builds).
#include "gyrostat/solve_system.hpp"

namespace gyrostat {

GYROSTAT_DEFINE_SOLVE(model::AveragedSymmetric)
GYROSTAT_DEFINE_SOLVE(model::MovingMass)

}  // namespace gyrostat
