// Many trajectories in one call, on a pool of threads.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <new>
#include <system_error>
#include <thread>
#include <vector>

#include "gyrostat/integrate/control.hpp"
#include "gyrostat/integrate/options.hpp"
#include "gyrostat/solve_system.hpp"  // the models' integration, compiled once in the core (extern here)

namespace gyrostat {

/// Runs `solve_member(i, control)` for i = 0..n−1 on `threads` threads (≤ 0: one per hardware
/// thread) and returns the results in index order. Each member runs the same code on its own
/// data, so results equal single runs bit for bit. A member that throws gets status
/// InvalidInput and the message (SolverFailure, "out of memory", for std::bad_alloc); the others
/// are unaffected. With a `control`, the calling
/// thread reports the fraction of members finished through control->poll; when poll returns
/// false, running members stop (status Interrupted, partial trajectory kept) and members not
/// started yet are returned empty with status Interrupted. When a thread cannot be created the
/// ensemble runs on the threads it has (at least the calling one).
template <class SolveMember>
std::vector<integrate::Result> run_ensemble(std::size_t n, SolveMember&& solve_member, int threads,
                                            const integrate::Control* control = nullptr) {
    using integrate::Result;
    std::vector<Result> results(n);
    std::atomic<std::size_t> next{0}, done{0};
    std::atomic<bool> stop{false};
    std::mutex mutex;
    std::condition_variable finished;
    // The caller's wish to stop, through its poll or its own stop flag, at a fraction done.
    auto caller_continues = [&](double fraction) {
        if (control->stop && control->stop->load()) return false;
        return !control->poll || control->poll(fraction);
    };
    integrate::Control member_control;
    member_control.stop = &stop;
    if (control && control->stop && control->stop->load()) stop = true;  // stopped before it started
    const bool inline_only = threads == 1 || n <= 1;
    // Run inline, the calling thread polls within its members' runs (their tickers) and between
    // them: a run shorter than the interval never polls, and an ensemble of short members would
    // otherwise see Ctrl-C only at its end.
    using Clock = std::chrono::steady_clock;
    Clock::time_point last_poll = Clock::now();
    const bool polls_inline = inline_only && control && control->poll;
    if (polls_inline) {
        member_control.interval = control->interval;
        member_control.poll = [&](double fraction) {
            last_poll = Clock::now();
            return caller_continues((static_cast<double>(done.load()) + fraction) / static_cast<double>(n));
        };
    }
    auto worker = [&]() {
        for (std::size_t i = next++; i < n; i = next++) {
            if (stop.load()) {
                results[i].status = integrate::Status::Interrupted;
                results[i].message = "member " + std::to_string(i) + ": not started, the ensemble was interrupted";
            } else {
                try {
                    results[i] = solve_member(i, &member_control);
                } catch (const std::bad_alloc&) {  // this member's outputs did not fit: the others go on
                    results[i] = Result{};
                    results[i].status = integrate::Status::SolverFailure;
                    results[i].message = "member " + std::to_string(i) +
                                         ": out of memory (its outputs could not be allocated): ask for fewer output "
                                         "times or fewer members at once";
                } catch (const integrate::Interruption&) {  // Ctrl-C seen by a user's function outside a step loop
                    results[i] = Result{};
                    results[i].status = integrate::Status::Interrupted;
                    results[i].message = "member " + std::to_string(i) + ": " + integrate::Interruption().what();
                } catch (const std::exception& e) {
                    results[i] = Result{};
                    results[i].status = integrate::Status::InvalidInput;
                    results[i].message = "member " + std::to_string(i) + ": " + e.what();
                } catch (...) {  // anything else thrown must not escape the thread (std::terminate)
                    results[i] = Result{};
                    results[i].status = integrate::Status::SolverFailure;
                    results[i].message = "member " + std::to_string(i) + ": an unknown exception";
                }
                if (results[i].status == integrate::Status::Interrupted) stop = true;  // the caller asked
            }
            ++done;
            if (polls_inline && !stop.load() &&
                std::chrono::duration<double>(Clock::now() - last_poll).count() >= control->interval) {
                last_poll = Clock::now();
                if (!caller_continues(static_cast<double>(done.load()) / static_cast<double>(n))) stop = true;
            }
            std::lock_guard<std::mutex> lock(mutex);
            finished.notify_all();
        }
    };
    unsigned count = threads > 0 ? static_cast<unsigned>(threads) : std::max(1u, std::thread::hardware_concurrency());
    count = static_cast<unsigned>(std::min<std::size_t>(count, std::max<std::size_t>(n, 1)));
    if (inline_only || count <= 1) {
        worker();
        return results;
    }
    std::vector<std::thread> pool;
    pool.reserve(count);
    for (unsigned k = 0; k < count; ++k) {
        try {
            pool.emplace_back(worker);
        } catch (const std::system_error&) {
            break;  // no more threads to be had: the ones started (or this one) do the work
        }
    }
    if (pool.empty()) {
        worker();
        return results;
    }
    if (control) {
        std::unique_lock<std::mutex> lock(mutex);
        const auto interval = std::chrono::duration<double>(control->interval);
        while (done.load() < n) {
            finished.wait_for(lock, interval);
            lock.unlock();
            if (!stop.load() && !caller_continues(static_cast<double>(done.load()) / static_cast<double>(n))) stop = true;
            lock.lock();
        }
    }
    for (auto& thread : pool) thread.join();
    return results;
}

/// The ensemble of one model type: member i solves systems[i] (or systems[0] for every member
/// when one system is given) from (t0, initial_states[i]) to t1.
template <class System>
std::vector<integrate::Result> solve_ensemble(const std::vector<System>& systems,
                                              const std::vector<typename System::State>& initial_states, double t0,
                                              double t1, const integrate::Options& options, int threads = 0,
                                              const integrate::Control* control = nullptr) {
    const std::size_t n = initial_states.size();
    if (systems.size() != 1 && systems.size() != n)
        throw std::invalid_argument("solve_ensemble: " + std::to_string(systems.size()) + " systems for " +
                                    std::to_string(n) + " initial states (give 1 or " + std::to_string(n) + ")");
    integrate::validate(options, t0, t1);
    auto results = run_ensemble(
        n,
        [&](std::size_t i, const integrate::Control* member) {
            return integrate::solve(systems.size() == 1 ? systems[0] : systems[i], t0, initial_states[i], t1, options,
                                    member);
        },
        threads, control);
    for (auto& r : results) {
        if (!r.declared) integrate::describe<System>(r), r.method = integrate::method_name(options.method);
        r.options = integrate::recorded(options);
    }
    return results;
}

}  // namespace gyrostat
