// What the step loops (dop853.hpp, taylor.hpp) integrate: one trajectory, or W members of an
// ensemble side by side in SIMD lanes (numeric/lanes.hpp). The loop is written once over a
// "run" that gives its values (double for one trajectory, lanes::Lanes for W), its state
// (std::array of `parts`: one State, or dim lanes of every component), its right-hand side, and
// the bookkeeping of each trajectory it carries (outputs, statistics, failures, the end of the
// span). A lane's arithmetic never depends on the other lanes, so a member's result is the same,
// bit for bit, whichever members share its batch.
//
// A run gives
//   using System, State, Value, Part;  static constexpr int dim, parts, width;
//   using Vector = std::array<Part, parts>;
//   int count() const; bool active(int l) const; bool any_active() const;
//   void rhs(const Value& t, const Vector& y, Vector& dy) const;   void project(Vector& y) const;
//   decltype(auto) state(const Vector& y, int l) const;           trajectory l's State
//   Stats& stats(int l); const System& system(int l) const;
//   void fail(int l, Status, std::string message, double t, const State& y, double h_next);
//   bool keep_going(Ticker&, const Value& t, const Vector& y, const Value& h_next);
#pragma once

#include <algorithm>
#include <array>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "gyrostat/integrate/control.hpp"
#include "gyrostat/integrate/options.hpp"
#include "gyrostat/integrate/recorder.hpp"
#include "gyrostat/model/system.hpp"
#include "gyrostat/numeric/lanes.hpp"

namespace gyrostat::integrate {

/// The bookkeeping every run shares: one trajectory (W = 1) or the lanes of a batch.
template <class System_, class Value_, class Part_, int Parts, int Width>
struct RunTraits {
    using System = System_;
    using State = typename System::State;
    using Value = Value_;
    using Part = Part_;
    static constexpr int dim = System::dim;
    static constexpr int parts = Parts;
    static constexpr int width = Width;
    using Vector = std::array<Part, parts>;
};

/// One trajectory (W = 1): its Result, and whether it is still running. The methods' own runs
/// (dop853.hpp: OneRun, taylor.hpp: OneTaylorRun) add their recording of outputs and events.
template <class System_>
class OneTrajectory : public RunTraits<System_, double, typename System_::State, 1, 1> {
public:
    using Base = RunTraits<System_, double, typename System_::State, 1, 1>;
    using typename Base::State;
    using typename Base::System;
    using typename Base::Vector;

    OneTrajectory(const System& system, Result& result) : system_(system), result_(result) {}

    void project(Vector& y) const { model::system::project(system_, y[0]); }
    int count() const { return 1; }
    bool active(int) const { return active_; }
    bool any_active() const { return active_; }
    const System& system(int) const { return system_; }
    Stats& stats(int) { return result_.stats; }
    static const State& state(const Vector& y, int) { return y[0]; }
    static void copy_lane(Vector& to, const Vector& from, int) { to[0] = from[0]; }
    template <class... Vectors>
    void fill_done_lanes(double&, Vectors&...) const {}
    bool keep_going(Ticker& ticker, double t, const Vector& y, double h_next) {
        if (ticker.keep_going(t)) return true;
        mark_interrupted(result_, t);
        finish(0, t, y[0], h_next);
        return false;
    }
    /// Ends the run where it is (its status and message already set, or success).
    void finish(int, double t, const State& y, double h_next) {
        keep_last(result_, t, y, h_next);
        active_ = false;
    }
    void fail(int l, Status status, std::string message, double t, const State& y, double h_next) {
        result_.status = status;
        result_.message = std::move(message);
        finish(l, t, y, h_next);
    }

protected:
    const System& system_;
    Result& result_;
    bool active_ = true;
};

/// W members of an ensemble in the SIMD lanes of one batch: the lane model `LaneModel` (declared
/// by the scalar model as `LaneModel`, model/system.hpp) evaluates the W right-hand sides at once;
/// each lane has its own Result, outputs and status.
template <class LaneModel>
class LaneRuns : public RunTraits<typename LaneModel::System, lanes::Lanes, lanes::Lanes, LaneModel::dim, lanes::width> {
public:
    using Base = RunTraits<typename LaneModel::System, lanes::Lanes, lanes::Lanes, LaneModel::dim, lanes::width>;
    using typename Base::State;
    using typename Base::System;
    using typename Base::Vector;
    using Lanes = lanes::Lanes;
    static constexpr int dim = Base::dim, W = lanes::width;

    /// systems[0..W) (padded by repetition past `count`), results[0..count).
    LaneRuns(const LaneModel& model, const System* const* systems, int count, Result* results, const Options& options,
             double t0, double t1)
        : model_(model), systems_(systems), count_(count), results_(results), outputs_(output_times(options, t0, t1)),
          direction_(t1 >= t0 ? 1.0 : -1.0), t1_(t1) {
        for (int l = 0; l < count; ++l) {
            results[l] = Result{};
            results[l].method = method_name(options.method);
            results[l].methods_used = {results[l].method};
            records_[l] = std::make_unique<Recorder<System>>(*systems[l], results[l], outputs_.size(),
                                                             options.only_measured_outputs);
            active_[l] = true;
        }
    }

    void rhs(const Lanes& t, const Vector& y, Vector& dy) const { model_.rhs(t, y.data(), dy.data()); }
    void project(Vector& y) const { model_.project(y.data()); }
    const LaneModel& model() const { return model_; }

    int count() const { return count_; }
    bool active(int l) const { return l < count_ && active_[l]; }
    bool any_active() const {
        for (int l = 0; l < count_; ++l)
            if (active_[l]) return true;
        return false;
    }
    const System& system(int l) const { return *systems_[l]; }
    Stats& stats(int l) { return results_[l].stats; }

    static State state(const Vector& y, int l) {
        State s;
        for (int i = 0; i < dim; ++i) s[i] = y[i][l];
        return s;
    }
    /// Lane l of `to` ← lane l of `from`.
    static void copy_lane(Vector& to, const Vector& from, int l) {
        for (int i = 0; i < dim; ++i) to[i][l] = from[i][l];
    }
    /// The lanes' initial states (lanes past `count` repeat the last member).
    Vector load(const State* y0) const {
        Vector y;
        for (int l = 0; l < W; ++l)
            for (int i = 0; i < dim; ++i) y[i][l] = y0[std::min(l, count_ - 1)][i];
        return y;
    }
    /// Asks the ticker whether to go on (at the earliest running lane's time); when not, every
    /// running lane ends Interrupted where it is.
    bool keep_going(Ticker& ticker, const Lanes& t, const Vector& y, const Lanes& h_next) {
        double earliest = std::numeric_limits<double>::infinity();
        for (int l = 0; l < count_; ++l)
            if (active_[l]) earliest = std::min(earliest, direction_ * t[l]);
        if (ticker.keep_going(direction_ * earliest)) return true;
        for (int l = 0; l < count_; ++l)
            if (active_[l]) {
                mark_interrupted(results_[l], t[l]);
                finish(l, t[l], state(y, l), h_next[l]);
            }
        return false;
    }
    /// Lanes that are done take a running lane's values (t and the states given), so that no NaN
    /// or overflow lingers in their arithmetic.
    template <class... Vectors>
    void fill_done_lanes(Lanes& t, Vectors&... vectors) const {
        int running = -1;
        for (int l = 0; l < count_ && running < 0; ++l)
            if (active_[l]) running = l;
        if (running < 0) return;
        for (int l = 0; l < W; ++l) {
            if (l < count_ && active_[l]) continue;
            t[l] = t[running];
            for (int i = 0; i < dim; ++i) ((vectors[i][l] = vectors[i][running]), ...);
        }
    }
    /// The outputs at t0.
    void start(double t0, const Vector& y) {
        for (int l = 0; l < count_; ++l)
            while (next_[l] < outputs_.size() && outputs_[next_[l]] == t0) records_[l]->push(t0, state(y, l)), ++next_[l];
    }
    /// A span of length zero: lane l ends where it starts.
    void empty_span(int l, double t0, const Vector& y) { finish(l, t0, state(y, l), 0.0); }
    /// Whether lane l has an output time strictly inside its step to t_new.
    bool output_inside(int l, double t_new) const {
        return next_[l] < outputs_.size() && direction_ * (outputs_[next_[l]] - t_new) < 0.0;
    }
    /// Records lane l's outputs strictly inside its step to t_new from `value(time)`.
    template <class Fn>
    void inside(int l, double t_new, Fn&& value) {
        while (output_inside(l, t_new)) records_[l]->push(outputs_[next_[l]], value(outputs_[next_[l]])), ++next_[l];
    }
    /// Records lane l's outputs inside its accepted step from t to t_new (DOP853: from the dense
    /// output). A batch has no events: false.
    template <class Dense>
    bool inside(int l, double /*t*/, double t_new, double /*h*/, const Vector&, const Vector&, Dense& dense) {
        inside(l, t_new, [&](double time) { return dense.value(l, time); });
        return false;
    }
    /// Lane l's step ended at t (y there): records its outputs there; ends the lane with success
    /// at t1 (a batch has no every_step).
    void at_end(int l, double t, const Vector& y, double h_next, bool /*every_step*/ = false) {
        if (!(t == t1_ || (next_[l] < outputs_.size() && outputs_[next_[l]] == t))) return;
        const State here = state(y, l);
        while (next_[l] < outputs_.size() && outputs_[next_[l]] == t) records_[l]->push(t, here), ++next_[l];
        if (t == t1_) finish(l, t, here, h_next);
    }
    /// Ends lane l where it is (its status and message already set, or success).
    void finish(int l, double t, const State& y, double h_next) {
        keep_last(results_[l], t, y, h_next);
        active_[l] = false;
    }
    void fail(int l, Status status, std::string message, double t, const State& y, double h_next) {
        results_[l].status = status;
        results_[l].message = std::move(message);
        finish(l, t, y, h_next);
    }
    /// A failure found before the first step (at t0, y there).
    void fail_at_start(int l, Status status, std::string message, double t0, const Vector& y) {
        fail(l, status, std::move(message), t0, state(y, l), 0.0);
    }

private:
    const LaneModel& model_;
    const System* const* systems_;
    int count_;
    Result* results_;
    std::vector<double> outputs_;
    double direction_, t1_;
    std::array<std::unique_ptr<Recorder<System>>, W> records_;
    std::array<std::size_t, W> next_{};
    std::array<bool, W> active_{};
};

/// The smallest step that still changes t (10 ulp).
inline double min_step(double t, double direction) {
    return 10.0 * std::abs(std::nextafter(t, direction * std::numeric_limits<double>::infinity()) - t);
}

}  // namespace gyrostat::integrate
