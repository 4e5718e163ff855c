// Instantiates the engine's solve for the gyrostat models (one translation unit per family: parallel builds).
#include "gyrostat/solve_system.hpp"

namespace gyrostat {

GYROSTAT_DEFINE_SOLVE(model::Gyrostat<false>)
GYROSTAT_DEFINE_SOLVE(model::Gyrostat<true>)
GYROSTAT_DEFINE_SOLVE(model::TorqueFree)
GYROSTAT_DEFINE_SOLVE(model::TorqueFreeAttitude)

}  // namespace gyrostat
