// The definition of solve_system (engine.hpp), and the one place each alternative of AnyModel has
// its integration compiled: integrate::solve<Model> and solve_system<Model> are instantiated
// explicitly, for model i in the translation unit src/solve_part<K>.cpp that GYROSTAT_SOLVED_MODELS
// names, and declared `extern template` for every other translation unit that includes
// integrate/solve.hpp (the engine, the C++ tests, the benchmark): they link to that one copy
// instead of compiling the integrators again.
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
#define GYROSTAT_COUNT_ALTERNATIVE(K, M) +(is_alternative<M, AnyModel>::value ? 1 : 0)
static_assert((0 GYROSTAT_SOLVED_MODELS(GYROSTAT_COUNT_ALTERNATIVE)) == std::variant_size_v<AnyModel>,
              "GYROSTAT_SOLVED_MODELS (solve_system.hpp) must list every alternative of AnyModel once");
#undef GYROSTAT_COUNT_ALTERNATIVE

// In the part that compiles them (GYROSTAT_SOLVE_PART defined), nothing is declared extern.
#ifndef GYROSTAT_SOLVE_PART
#define GYROSTAT_EXTERN_SOLVE(K, M) extern template GYROSTAT_SOLVE_SIGNATURE(M); \
                                    extern template GYROSTAT_SOLVE_SYSTEM_SIGNATURE(M);
GYROSTAT_SOLVED_MODELS(GYROSTAT_EXTERN_SOLVE)
#undef GYROSTAT_EXTERN_SOLVE
#endif

}  // namespace gyrostat

#ifdef GYROSTAT_SOLVE_PART
/// In src/solve_part<K>.cpp (GYROSTAT_SOLVE_PART = K): the explicit instantiations of part K.
#define GYROSTAT_INSTANTIATE_SOLVE(M) template GYROSTAT_SOLVE_SIGNATURE(M); template GYROSTAT_SOLVE_SYSTEM_SIGNATURE(M);
#define GYROSTAT_SOLVE_IN_PART(K, M) GYROSTAT_SOLVE_IN_PART_##K(M)
#define GYROSTAT_SOLVE_IN_PART_0(M)
#define GYROSTAT_SOLVE_IN_PART_1(M)
#define GYROSTAT_SOLVE_IN_PART_2(M)
#define GYROSTAT_SOLVE_IN_PART_3(M)
#if GYROSTAT_SOLVE_PART == 0
#undef GYROSTAT_SOLVE_IN_PART_0
#define GYROSTAT_SOLVE_IN_PART_0(M) GYROSTAT_INSTANTIATE_SOLVE(M)
#elif GYROSTAT_SOLVE_PART == 1
#undef GYROSTAT_SOLVE_IN_PART_1
#define GYROSTAT_SOLVE_IN_PART_1(M) GYROSTAT_INSTANTIATE_SOLVE(M)
#elif GYROSTAT_SOLVE_PART == 2
#undef GYROSTAT_SOLVE_IN_PART_2
#define GYROSTAT_SOLVE_IN_PART_2(M) GYROSTAT_INSTANTIATE_SOLVE(M)
#elif GYROSTAT_SOLVE_PART == 3
#undef GYROSTAT_SOLVE_IN_PART_3
#define GYROSTAT_SOLVE_IN_PART_3(M) GYROSTAT_INSTANTIATE_SOLVE(M)
#else
#error "GYROSTAT_SOLVE_PART is 0, 1, 2 or 3"
#endif
#endif
