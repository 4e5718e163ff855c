// Which members of an ensemble the SIMD batches take (integrate/batch.hpp), and running one batch.
// Private to the engine (src/engine.cpp): a front end calls gyrostat::solve_ensemble.
#pragma once

#include <cstddef>
#include <vector>

#include "gyrostat/engine.hpp"

namespace gyrostat::ensemble_batch {

/// The ensemble split into batches of at most lanes::width members of one model type (the last
/// one of a type may be partial, down to one member), and the members that run one by one (their
/// model or options have no batch, or their initial state is invalid: the scalar path then
/// reports it).
struct Plan {
    std::vector<std::vector<std::size_t>> batches;
    std::vector<std::size_t> single;
};

Plan plan(const std::vector<const AnyModel*>& models, const std::vector<Eigen::VectorXd>& y0s,
          const integrate::Options& options);

/// Integrates one batch; writes results[i] for each member i of `batch`.
void solve(const std::vector<std::size_t>& batch, const std::vector<const AnyModel*>& models,
           const std::vector<Eigen::VectorXd>& y0s, double t0, double t1, const integrate::Options& options,
           const integrate::Control* control, std::vector<integrate::Result>& results);

}  // namespace gyrostat::ensemble_batch
