// What one run records, shared by the integrators that carry it: one for a plain run, several
// in turn for method 'auto' (auto_switch.hpp), so that the segments chain into one Result.
#pragma once

#include "gyrostat/integrate/events.hpp"
#include "gyrostat/integrate/recorder.hpp"

namespace gyrostat::integrate {

/// The Result of a run from t0 to t1 with its output grid (each time recorded once, in order),
/// its events (crossing counts of terminal events carried from segment to segment), its dense
/// output and its statistics. A segment of the run starts where the previous one stopped and
/// continues all of these: nothing is copied or merged afterwards. Not copyable (the recorder
/// and the cursor refer to each other and to the Result).
template <class System>
struct Recording {
    Recording(const System& system, const Options& options, double t0_, double t1_, Result& result_)
        : Recording(system, options, t0_, t1_, result_, output_times(options, t0_, t1_)) {}
    Recording(const Recording&) = delete;
    Recording& operator=(const Recording&) = delete;

    /// The start of the run: the outputs at t0, the events' values there, and (t0, y0) as
    /// where the run stopped until its first step is accepted.
    void start(const typename System::State& y0) {
        cursor.start(t0, y0);
        events.start(t0, y0);
        keep_last(result, t0, y0, 0.0);
    }

    Result& result;
    const double t0, t1, direction;
    Recorder<System> record;
    OutputCursor<System> cursor;
    EventLocator<System> events;

private:
    Recording(const System& system, const Options& options, double t0_, double t1_, Result& result_,
              std::vector<double> outputs)
        : result(result_),
          t0(t0_),
          t1(t1_),
          direction(t1_ >= t0_ ? 1.0 : -1.0),
          record(system, result_, outputs.size(), options.only_measured_outputs),
          cursor(record, std::move(outputs), direction),
          events(system, options.events, result_) {
        result.dense = make_dense<System>(options);
    }
};

}  // namespace gyrostat::integrate
