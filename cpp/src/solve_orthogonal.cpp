// Instantiates the engine's solve for the orthogonal models (one translation unit per family: parallel builds).
#include "gyrostat/solve_system.hpp"

namespace gyrostat {

GYROSTAT_DEFINE_SOLVE(model::OrthogonalTorque<false>)
GYROSTAT_DEFINE_SOLVE(model::OrthogonalTorque<true>)

}  // namespace gyrostat
