// Progress reports and interruption of a running integration, without restarting it.
#pragma once

#include <atomic>
#include <chrono>
#include <exception>
#include <functional>

namespace gyrostat::integrate {

/// What a caller may do to a running solve: be told how far it got, and stop it.
/// Neither changes the trajectory: a run with a Control is bit-identical to one without,
/// up to where it was stopped.
struct Control {
    /// Called from the solving thread at most once every `interval` seconds with the fraction
    /// done (of the time span for one run, of the members for an ensemble). Returning false
    /// stops the run: it ends with status Interrupted and keeps what it computed.
    std::function<bool(double fraction)> poll;
    double interval = 0.1;
    /// Set by another thread to stop the run (an ensemble stops its members this way).
    const std::atomic<bool>* stop = nullptr;
};

/// Thrown from inside a right-hand side to stop the run there: a user's Python torque that saw
/// Ctrl-C (KeyboardInterrupt raised in it, bindings/expose_custom.cpp) throws it. Each step loop
/// (DOP853, CVODE/ARKODE, splitting) catches it and ends the run as when its Ticker stops it:
/// status Interrupted, the outputs up to the last accepted step kept, t_last and y_last there.
struct Interruption : std::exception {
    const char* what() const noexcept override { return "interrupted (Ctrl-C in a user's function)"; }
};

/// Whether `error` (an exception a callback kept, integrate/sundials.hpp) is an Interruption.
inline bool is_interruption(const std::exception_ptr& error) {
    try {
        std::rethrow_exception(error);
    } catch (const Interruption&) {
        return true;
    } catch (...) {
        return false;
    }
}

/// The integrators' side of a Control: ask `keep_going(t)` once per step. It reads the stop flag
/// every 16 steps and the clock every 64 (a few ns per step), and calls poll at the set rate.
class Ticker {
public:
    Ticker(const Control* control, double t0, double t1) : control_(control), t0_(t0), span_(t1 - t0) {
        if (control_) last_ = std::chrono::steady_clock::now();
    }

    bool keep_going(double t) {
        if (control_ == nullptr) return true;
        if ((++count_ & 15) != 0) return true;
        if (control_->stop && control_->stop->load(std::memory_order_relaxed)) return stop_here();
        if (!control_->poll || (count_ & 63) != 0) return true;
        const auto now = std::chrono::steady_clock::now();
        if (std::chrono::duration<double>(now - last_).count() < control_->interval) return true;
        last_ = now;
        if (!control_->poll(span_ != 0.0 ? (t - t0_) / span_ : 1.0)) return stop_here();
        return true;
    }
    bool interrupted() const { return interrupted_; }

private:
    bool stop_here() {
        interrupted_ = true;
        return false;
    }

    const Control* control_;
    double t0_, span_;
    unsigned long count_ = 0;
    bool interrupted_ = false;
    std::chrono::steady_clock::time_point last_;
};

}  // namespace gyrostat::integrate
