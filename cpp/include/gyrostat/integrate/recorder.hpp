// Collects outputs (time, state, invariants) into a Result; shared by every integrator.
#pragma once

#include <cmath>
#include <sstream>
#include <string>

#include <Eigen/Core>

#include "gyrostat/body.hpp"
#include "gyrostat/integrate/options.hpp"

namespace gyrostat::integrate {

template <class System>
class Recorder {
public:
    using State = typename System::State;

    Recorder(const System& system, Result& result, std::size_t expected) : system_(system), result_(result) {
        result_.dim = System::dim;
        result_.invariant_names.assign(System::invariant_names.begin(), System::invariant_names.end());
        result_.t.reserve(expected);
        result_.y.reserve(expected * System::dim);
        result_.invariants.reserve(expected * System::n_invariants);
    }

    /// Records y(t); constrained parts (a quaternion) are projected back onto their manifold first.
    void push(double t, State y) {
        system_.project(y);
        result_.t.push_back(t);
        result_.y.insert(result_.y.end(), y.data(), y.data() + System::dim);
        double inv[System::n_invariants > 0 ? System::n_invariants : 1];
        system_.invariants(t, y, inv);
        result_.invariants.insert(result_.invariants.end(), inv, inv + System::n_invariants);
    }

private:
    const System& system_;
    Result& result_;
};

inline std::string format_number(double x, int precision = 6) {
    std::ostringstream s;
    s.precision(precision);
    s << x;
    return s.str();
}

template <class State>
bool all_finite(const State& y) {
    for (Eigen::Index i = 0; i < y.size(); ++i)
        if (!std::isfinite(y[i])) return false;
    return true;
}

}  // namespace gyrostat::integrate
