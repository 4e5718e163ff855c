// The ensemble's SIMD batches: planning (which members, in which groups) and one batch's run.
#include "ensemble_batch.hpp"

#include <array>
#include <utility>
#if defined(__linux__)
#include <dlfcn.h>
#endif
#include <atomic>
#include <type_traits>
#include <variant>

#include "gyrostat/integrate/batch.hpp"

namespace gyrostat::ensemble_batch {

namespace {

const AnyModel& model_of(const std::vector<const AnyModel*>& models, std::size_t i) {
    return *(models.size() == 1 ? models[0] : models[i]);
}

/// The member's model as System when a batch integrates it with these options and its initial
/// state is valid; nullptr otherwise.
template <class System>
const System* batched(const AnyModel& m, const Eigen::VectorXd& y0, const integrate::Options& options) {
    const System* system = std::get_if<System>(&m);
    if (!system || !integrate::batch::applies(*system, options)) return nullptr;
    try {
        const typename System::State start = model::system::initial_state(*system, y0);
        require_finite(start, "initial state y0");
        model::system::check_state(*system, start);
    } catch (const std::exception&) {
        return nullptr;  // the scalar path reports it, naming the value
    }
    return system;
}

template <class System>
void run(const std::vector<std::size_t>& batch, const std::vector<const AnyModel*>& models,
         const std::vector<Eigen::VectorXd>& y0s, double t0, double t1, const integrate::Options& options,
         const integrate::Control* control, std::vector<integrate::Result>& results) {
    constexpr int W = lanes::width;
    const int count = static_cast<int>(batch.size());
    std::array<const System*, W> members{};
    std::array<typename System::State, W> starts;
    std::array<integrate::Result, W> out;
    for (int l = 0; l < count; ++l) {
        members[l] = std::get_if<System>(&model_of(models, batch[l]));
        starts[l] = model::system::initial_state(*members[l], y0s[batch[l]]);
    }
    integrate::batch::solve_lanes(members.data(), count, starts.data(), t0, t1, options, control, out.data());
    for (int l = 0; l < count; ++l) results[batch[l]] = std::move(out[l]);
}

}  // namespace

Plan plan(const std::vector<const AnyModel*>& models, const std::vector<Eigen::VectorXd>& y0s,
          const integrate::Options& options) {
    constexpr std::size_t W = lanes::width;
    Plan p;
    std::vector<std::size_t> open[std::variant_size_v<AnyModel>];  // per model type: members waiting for a full batch
    for (std::size_t i = 0; i < y0s.size(); ++i) {
        const AnyModel& m = model_of(models, i);
        const bool batches = std::visit(
            [&](const auto& system) {
                using System = std::decay_t<decltype(system)>;
                if constexpr (model::system::has_lanes<System>::value)
                    return batched<System>(m, y0s[i], options) != nullptr;
                else
                    return false;
            },
            m);
        if (!batches) {
            p.single.push_back(i);
            continue;
        }
        auto& waiting = open[m.index()];
        waiting.push_back(i);
        if (waiting.size() == W) p.batches.push_back(std::move(waiting)), waiting.clear();
    }
    for (auto& rest : open)  // a last, partial batch (a member alone is a batch of one: the same numbers)
        if (!rest.empty()) p.batches.push_back(std::move(rest));
    return p;
}

void solve(const std::vector<std::size_t>& batch, const std::vector<const AnyModel*>& models,
           const std::vector<Eigen::VectorXd>& y0s, double t0, double t1, const integrate::Options& options,
           const integrate::Control* control, std::vector<integrate::Result>& results) {
    std::visit(
        [&](const auto& first) {
            using System = std::decay_t<decltype(first)>;
            if constexpr (model::system::has_lanes<System>::value)
                run<System>(batch, models, y0s, t0, t1, options, control, results);
        },
        model_of(models, batch.front()));
}

const Implementation& compiled() {
    static const Implementation own{lanes::instruction_set, lanes::width, &plan, &solve};
    return own;
}

namespace {
std::atomic<const Implementation*> installed{nullptr};
}  // namespace

const Implementation& current() {
    const Implementation* chosen = installed.load(std::memory_order_acquire);
    return chosen ? *chosen : compiled();
}

void use(const Implementation* implementation) { installed.store(implementation, std::memory_order_release); }

const Implementation& load(const std::string& directory, const std::string& asked) {
#if defined(__x86_64__) && defined(__GNUC__) && defined(__linux__)
    __builtin_cpu_init();
    const bool avx512 = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
                        __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512bw");
    const bool avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    const std::pair<const char*, bool> plugins[] = {{"avx512", avx512}, {"avx2", avx2}};
    for (const auto& [name, runs] : plugins) {
        if (!runs || (!asked.empty() && asked != name)) continue;
        void* handle = dlopen((directory + "/_batch_" + name + ".so").c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) continue;
        using Entry = const Implementation* (*)();
        const auto entry = reinterpret_cast<Entry>(dlsym(handle, "gyrostat_batch_implementation"));
        if (!entry) continue;
        use(entry());
        return current();
    }
#else
    (void)directory, (void)asked;
#endif
    use(nullptr);
    return current();
}

}  // namespace gyrostat::ensemble_batch
