// The definition of solve_system (engine.hpp) and its explicit instantiation for the alternatives
// of AnyModel, spread over the translation units src/solve_part<K>.cpp by index (alternative i in
// part i mod kSolveParts): parallel builds, and no list of models to keep here.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <type_traits>
#include <variant>

#include "gyrostat/engine.hpp"
#include "gyrostat/integrate/solve.hpp"

namespace gyrostat {

/// The number of translation units that instantiate the engine (src/solve_part0.cpp …).
inline constexpr std::size_t kSolveParts = 4;
/// Room for this many models: a static_assert below says when AnyModel outgrows it.
inline constexpr std::size_t kMaxModels = 16;
static_assert(std::variant_size_v<AnyModel> <= kMaxModels, "AnyModel has more models than kMaxModels: raise it");

/// The model at index I of AnyModel, or a placeholder past its end (instantiated to nothing).
template <std::size_t I>
struct NoModel {};
template <std::size_t I, class = void>
struct model_at {
    using type = NoModel<I>;
};
template <std::size_t I>
struct model_at<I, std::enable_if_t<(I < std::variant_size_v<AnyModel>)>> {
    using type = std::variant_alternative_t<I, AnyModel>;
};

template <class T>
struct is_placeholder : std::false_type {};
template <std::size_t I>
struct is_placeholder<NoModel<I>> : std::true_type {};

template <class Model>
integrate::Result solve_system(const Model& model, double t0, const Eigen::VectorXd& y0, double t1,
                               const integrate::Options& options, const integrate::Control* control) {
    if constexpr (is_placeholder<Model>::value) {
        (void)model, (void)t0, (void)y0, (void)t1, (void)options, (void)control;
        throw std::logic_error("no model at this index of AnyModel");
    } else {
        const auto start = model::system::initial_state(model, y0);
        return integrate::solve(model, t0, start, t1, options, control);
    }
}

}  // namespace gyrostat

/// Instantiates solve_system for the alternative of AnyModel at index I, if there is one.
#define GYROSTAT_INSTANTIATE_SOLVE_AT(I)                                                                          \
    template integrate::Result solve_system<model_at<I>::type>(const model_at<I>::type&, double,                  \
                                                              const Eigen::VectorXd&, double,                      \
                                                              const integrate::Options&, const integrate::Control*);
/// Part K of the engine: the alternatives K, K + 4, K + 8, K + 12 of AnyModel.
#define GYROSTAT_INSTANTIATE_SOLVE_PART(K)                                                            \
    static_assert(K < kSolveParts && kSolveParts * 4 == kMaxModels, "four parts of four models each"); \
    GYROSTAT_INSTANTIATE_SOLVE_AT(K)                                                                  \
    GYROSTAT_INSTANTIATE_SOLVE_AT(K + 4)                                                              \
    GYROSTAT_INSTANTIATE_SOLVE_AT(K + 8)                                                              \
    GYROSTAT_INSTANTIATE_SOLVE_AT(K + 12)
