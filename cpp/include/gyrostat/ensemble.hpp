// Many trajectories in one call, on a pool of threads.
#pragma once

#include <algorithm>
#include <atomic>
#include <exception>
#include <thread>
#include <vector>

#include "gyrostat/integrate/solve.hpp"

namespace gyrostat {

/// Solves member i from (t0, initial_states[i]) to t1 with systems[i] (or systems[0] for every
/// member when one system is given), on `threads` threads (≤ 0: one per hardware thread).
/// Results come in index order and are identical to single runs: each member runs the same code
/// on its own data. A member that throws (bad input) gets status InvalidInput and the message;
/// the others are unaffected.
template <class System>
std::vector<integrate::Result> solve_ensemble(const std::vector<System>& systems,
                                              const std::vector<typename System::State>& initial_states, double t0,
                                              double t1, const integrate::Options& options, int threads = 0) {
    const std::size_t n = initial_states.size();
    if (systems.size() != 1 && systems.size() != n)
        throw std::invalid_argument("solve_ensemble: " + std::to_string(systems.size()) + " systems for " +
                                    std::to_string(n) + " initial states (give 1 or " + std::to_string(n) + ")");
    integrate::validate(options, t0, t1);
    std::vector<integrate::Result> results(n);
    std::atomic<std::size_t> next{0};
    auto worker = [&]() {
        for (std::size_t i = next++; i < n; i = next++) {
            const System& system = systems.size() == 1 ? systems[0] : systems[i];
            try {
                results[i] = integrate::solve(system, t0, initial_states[i], t1, options);
            } catch (const std::exception& e) {
                results[i] = integrate::Result{};
                results[i].method = integrate::method_name(options.method);
                results[i].dim = System::dim;
                results[i].status = integrate::Status::InvalidInput;
                results[i].message = "member " + std::to_string(i) + ": " + e.what();
            }
        }
    };
    unsigned count = threads > 0 ? static_cast<unsigned>(threads) : std::max(1u, std::thread::hardware_concurrency());
    count = static_cast<unsigned>(std::min<std::size_t>(count, std::max<std::size_t>(n, 1)));
    if (count <= 1) {
        worker();
        return results;
    }
    std::vector<std::thread> pool;
    pool.reserve(count);
    for (unsigned k = 0; k < count; ++k) pool.emplace_back(worker);
    for (auto& thread : pool) thread.join();
    return results;
}

}  // namespace gyrostat
