// The definition behind each solve_system overload of engine.hpp (included by src/solve_*.cpp only).
#pragma once

#include "gyrostat/engine.hpp"
#include "gyrostat/integrate/solve.hpp"

#define GYROSTAT_DEFINE_SOLVE(Model)                                                                       \
    integrate::Result solve_system(const Model& model, double t0, const Eigen::VectorXd& y0, double t1,   \
                                   const integrate::Options& options, const integrate::Control* control) { \
        const auto start = model::system::initial_state(model, y0);                                        \
        return integrate::solve(model, t0, start, t1, options, control);                                   \
    }
