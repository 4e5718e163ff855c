// Which members of an ensemble the SIMD batches take (integrate/batch.hpp), and running one batch.
// Private to the engine (src/engine.cpp): a front end calls gyrostat::solve_ensemble.
#pragma once

#include <cstddef>
#include <string>
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

/// plan and solve as compiled for one instruction set, with its lane width. The library carries
/// the form compiled with its own flags (`compiled()`); a front end may install another one,
/// compiled for a wider instruction set the CPU has (the Python module loads it from a plugin
/// built from ensemble_batch_plugin.cpp: runtime dispatch of the SIMD lanes).
struct Implementation {
    const char* instruction_set;
    int width;
    Plan (*plan)(const std::vector<const AnyModel*>&, const std::vector<Eigen::VectorXd>&, const integrate::Options&);
    void (*solve)(const std::vector<std::size_t>&, const std::vector<const AnyModel*>&,
                  const std::vector<Eigen::VectorXd>&, double, double, const integrate::Options&,
                  const integrate::Control*, std::vector<integrate::Result>&);
};

/// The form compiled into this binary (the library's own flags).
const Implementation& compiled();
/// The form solve_ensemble uses: compiled() unless another was installed with use().
const Implementation& current();
/// Installs `implementation` for every later solve_ensemble (nullptr: back to compiled()). Not
/// while an ensemble runs: a front end calls it once, when it loads.
void use(const Implementation* implementation);

/// Installs the widest form the CPU runs from the plugins in `directory` (`_batch_avx512.so`,
/// then `_batch_avx2.so`: AVX-512 F/DQ/VL/BW, AVX2 + FMA), or the one `asked` names ("avx512",
/// "avx2", "sse2": the library's own form; for tests and timing) when the CPU runs it; returns
/// the form in use. A plugin that is missing or does not load leaves the next one to try.
const Implementation& load(const std::string& directory, const std::string& asked);

}  // namespace gyrostat::ensemble_batch
