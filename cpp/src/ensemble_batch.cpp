// The ensemble's SIMD batches: planning (which members, in which groups) and one batch's run.
#include "ensemble_batch.hpp"

#include <array>
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
    std::vector<std::size_t> open[3];  // per batched model type: members waiting for a full batch
    for (std::size_t i = 0; i < y0s.size(); ++i) {
        const AnyModel& m = model_of(models, i);
        int kind = -1;
        if (batched<model::Gyrostat<false>>(m, y0s[i], options)) kind = 0;
        else if (batched<model::Gyrostat<true>>(m, y0s[i], options)) kind = 1;
        else if (batched<model::AveragedSymmetric>(m, y0s[i], options)) kind = 2;
        if (kind < 0) {
            p.single.push_back(i);
            continue;
        }
        open[kind].push_back(i);
        if (open[kind].size() == W) p.batches.push_back(std::move(open[kind])), open[kind].clear();
    }
    for (auto& rest : open)  // a last, partial batch (a member alone is a batch of one: the same numbers)
        if (!rest.empty()) p.batches.push_back(std::move(rest));
    return p;
}

void solve(const std::vector<std::size_t>& batch, const std::vector<const AnyModel*>& models,
           const std::vector<Eigen::VectorXd>& y0s, double t0, double t1, const integrate::Options& options,
           const integrate::Control* control, std::vector<integrate::Result>& results) {
    const AnyModel& first = model_of(models, batch.front());
    if (std::holds_alternative<model::Gyrostat<false>>(first))
        run<model::Gyrostat<false>>(batch, models, y0s, t0, t1, options, control, results);
    else if (std::holds_alternative<model::Gyrostat<true>>(first))
        run<model::Gyrostat<true>>(batch, models, y0s, t0, t1, options, control, results);
    else
        run<model::AveragedSymmetric>(batch, models, y0s, t0, t1, options, control, results);
}

}  // namespace gyrostat::ensemble_batch
