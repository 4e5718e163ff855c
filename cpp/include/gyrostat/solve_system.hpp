// The definition of solve_system (engine.hpp), and the one place each alternative of AnyModel has
// its integration compiled: integrate::solve<Model> and solve_system<Model> are instantiated
// explicitly for every model GYROSTAT_SOLVED_MODELS lists in one translation unit,
// src/solve_models.cpp, and declared `extern template` for every other translation unit that
// includes this header (the engine and the ensemble, the C++ tests, the benchmark, a program
// built against the installed package): they link to that one copy instead of compiling the
// integrators again. The integrators (integrate/) never include it, nor the engine: they know no
// model (tests/test_layers.py checks the headers' include graph). One unit, not one per model: what the models'
// integrations share (Eigen, the torques, the SUNDIALS drivers, the event locator) is then compiled
// once (-O3, one core: 145 s of CPU for the 11 models against 229 s in four units).
#pragma once

#include <type_traits>
#include <variant>

#include "gyrostat/engine.hpp"
#include "gyrostat/integrate/solve.hpp"

namespace gyrostat {

template <class Model>
integrate::Result solve_system(const Model& model, double t0, const Eigen::VectorXd& y0, double t1,
                               const integrate::Options& options, const integrate::Control* control) {
    const auto start = model::system::initial_state(model, y0);
    return integrate::solve(model, t0, start, t1, options, control);
}

}  // namespace gyrostat


#define GYROSTAT_SOLVE_SIGNATURE(M)                                                                            \
    integrate::Result integrate::solve<M>(const M&, double, const M::State&, double, const integrate::Options&, \
                                          const integrate::Control*)
#define GYROSTAT_SOLVE_SYSTEM_SIGNATURE(M)                                                          \
    integrate::Result solve_system<M>(const M&, double, const Eigen::VectorXd&, double, const integrate::Options&, \
                                      const integrate::Control*)

namespace gyrostat {

/// 1 when M is an alternative of AnyModel.
template <class M, class Variant>
struct is_alternative;
template <class M, class... Ts>
struct is_alternative<M, std::variant<Ts...>> : std::bool_constant<(std::is_same_v<M, Ts> || ...)> {};
#define GYROSTAT_COUNT_ALTERNATIVE(M) +(is_alternative<M, AnyModel>::value ? 1 : 0)
static_assert((0 GYROSTAT_SOLVED_MODELS(GYROSTAT_COUNT_ALTERNATIVE)) == std::variant_size_v<AnyModel>,
              "GYROSTAT_SOLVED_MODELS (solve_system.hpp) must list every alternative of AnyModel once");
#undef GYROSTAT_COUNT_ALTERNATIVE

// In the unit that compiles them (src/solve_models.cpp: GYROSTAT_SOLVING_MODELS), nothing is extern.
#ifndef GYROSTAT_SOLVING_MODELS
#define GYROSTAT_EXTERN_SOLVE(M) extern template GYROSTAT_SOLVE_SIGNATURE(M); \
                                 extern template GYROSTAT_SOLVE_SYSTEM_SIGNATURE(M);
GYROSTAT_SOLVED_MODELS(GYROSTAT_EXTERN_SOLVE)
#undef GYROSTAT_EXTERN_SOLVE
#endif

}  // namespace gyrostat

#ifdef GYROSTAT_SOLVING_MODELS
/// In src/solve_models.cpp: the explicit instantiations of one model.
#define GYROSTAT_INSTANTIATE_SOLVE(M) template GYROSTAT_SOLVE_SIGNATURE(M); template GYROSTAT_SOLVE_SYSTEM_SIGNATURE(M);
#endif
