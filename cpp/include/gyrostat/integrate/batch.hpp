// SIMD batches: W members of an ensemble integrated side by side, one per lane of a fixed-size
// Eigen array (numeric/lanes.hpp), each lane with its own model parameters, time, step size,
// outputs, statistics and status. The step loops are the scalar ones (dop853.hpp: dop853_steps;
// taylor.hpp), run over LaneRuns (trajectories.hpp): every arithmetic operation of a step acts on
// the W lanes at once; the per-lane bookkeeping (outputs, failures, the end of the span) is scalar.
//
// A model batches when it declares a lane model (`LaneModel`, model/system.hpp), which gives the
// right-hand side (and the Taylor recursion) of W members at once; this header names no model.
// Results agree with the scalar path to the tolerance, not bit for bit: a lane model may evaluate
// its right-hand side in another form (the gyrostat's: the affine Euler equations), the batch
// Taylor method keeps the order of rtol in absolute mode too, and vectorised arithmetic may round
// differently (exp, log, fused multiply-adds). A lane's arithmetic never depends on the other
// lanes, so a member's result is the same, bit for bit, whichever members share its batch (and a
// member alone runs as a batch of one): ensembles and sweeps give the same numbers however they
// are chunked.
//
// What a batch covers (solve_ensemble falls back to the scalar path for everything else): no
// events, no dense output, no every_step; the models with a lane model, for the methods it has
// (taylor with `max_taylor_order`, dop853 always) and the members it accepts.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <vector>

#include "gyrostat/integrate/control.hpp"
#include "gyrostat/integrate/dop853.hpp"
#include "gyrostat/integrate/options.hpp"
#include "gyrostat/integrate/taylor.hpp"
#include "gyrostat/integrate/trajectories.hpp"
#include "gyrostat/model/system.hpp"
#include "gyrostat/numeric/lanes.hpp"

namespace gyrostat::integrate::batch {

using lanes::Lanes;
constexpr int W = lanes::width;

/// Whether a batch integrates `system` with `options` (else the scalar path does).
template <class System>
bool applies(const System& system, const Options& options) {
    if (!options.events.empty() || options.dense_output || options.every_step) return false;
    if constexpr (model::system::has_lanes<System>::value) {
        using LaneModel = typename System::LaneModel;
        const bool taylor = options.method == Method::Taylor;
        if (taylor && !model::system::has_taylor<LaneModel>::value) return false;
        return (taylor || options.method == Method::Dop853) && LaneModel::accepts(system, taylor);
    } else {
        (void)system;
        return false;
    }
}

/// max_i |y_i| per lane.
template <int dim>
Lanes max_abs(const Lanes* y) {
    Lanes m = y[0].abs();
    for (int i = 1; i < dim; ++i) m = m.max(y[i].abs());
    return m;
}

/// a·b − fl(a·b) lane by lane, exactly: a fused multiply-add where the batch is compiled for one
/// (the AVX2 and AVX-512 forms), else Dekker's split (model::dekker_product_error's algorithm,
/// exact where no multiply-add can be formed).
inline Lanes product_error(const Lanes& a, const Lanes& b, const Lanes& p) {
#ifdef __FMA__
    Lanes e;
    for (int l = 0; l < W; ++l) e[l] = std::fma(a[l], b[l], -p[l]);
    return e;
#else
    constexpr double split = 134217729.0;  // 2^27 + 1
    const Lanes a_big = split * a, b_big = split * b;
    const Lanes a_high = a_big - (a_big - a), b_high = b_big - (b_big - b);
    const Lanes a_low = a - a_high, b_low = b - b_high;
    return ((a_high * b_high - p) + a_high * b_low + a_low * b_high) + a_low * b_low;
#endif
}

/// taylor_detail::fast_log2 lane by lane, to the same bits, in a form the compiler vectorises: the
/// exponent read as a double from the bits of 2^52 + e (no integer conversion, which AVX2 lacks
/// for 64-bit lanes). The step size needs ρ to a few digits only (taylor.hpp: fast_log2), and
/// Eigen's log and exp were a fifth of the batch's step (perf: bench/README.md).
inline Lanes fast_log2(const Lanes& x) {
    constexpr double two_52 = 4503599627370496.0;
    Lanes out;
    for (int l = 0; l < W; ++l) {
        std::uint64_t bits;
        std::memcpy(&bits, &x[l], sizeof bits);
        const std::uint64_t exponent_bits = (bits >> 52) | 0x4330000000000000ULL;  // the double 2^52 + e
        double exponent;
        std::memcpy(&exponent, &exponent_bits, sizeof exponent);
        out[l] = (exponent - (two_52 + 1023.0)) + taylor_detail::log2_of_mantissa(bits);  // exact difference
    }
    return out;
}

/// taylor_detail::fast_exp2 lane by lane, to the same bits, without a branch or an integer
/// conversion: ⌊y⌋ by adding and subtracting 1.5·2^52 (y rounded to an integer) and stepping down
/// where that rounded up; 2^⌊y⌋ from the bits of the double 2^52 + ⌊y⌋ + 1023 shifted into the
/// exponent; +∞ from y ≥ 1023 (NaN for NaN), 0 below −1022. In GCC's vector types, whose
/// comparisons select lane by lane (a loop of scalar comparisons is not vectorised: they may trap).
inline Lanes fast_exp2(const Lanes& lanes) {
    using Vector = double __attribute__((vector_size(W * sizeof(double))));
    using Bits = std::uint64_t __attribute__((vector_size(W * sizeof(double))));
    constexpr double round = 6755399441055744.0, two_52 = 4503599627370496.0;  // 1.5·2^52, 2^52
    constexpr double lowest = -1022.0, below_highest = 1023.0 - 0x1p-43;       // (the largest double below 1023)
    const Vector zero{};
    Vector y;
    std::memcpy(&y, lanes.data(), sizeof y);
    Vector x = y > zero + lowest ? y : zero + lowest;  // y itself where it is in range; NaN and the rest selected out below
    x = x < zero + below_highest ? x : zero + below_highest;
    Vector n = (x + round) - round;
    n = n > x ? n - 1.0 : n;  // ⌊x⌋
    const Vector biased = (n + 1023.0) + two_52;  // its low bits hold n + 1023
    Bits bits;
    std::memcpy(&bits, &biased, sizeof bits);
    bits <<= 52;
    Vector scale;
    std::memcpy(&scale, &bits, sizeof scale);
    Vector out;
    for (int l = 0; l < W; ++l) out[l] = taylor_detail::exp2_of_fraction(x[l] - n[l]) * scale[l];
    out = y < zero + lowest ? zero : out;
    out = y < zero + 1023.0 ? out : y + std::numeric_limits<double>::infinity();
    Lanes result;
    std::memcpy(result.data(), &out, sizeof out);
    return result;
}

/// The value as stored: the compiler may not fuse the multiplication that made it into the
/// additions that use it (a fused y + c·dt would leave two_sum_error and product_error reading a
/// product the sum never saw: their "exact" errors would not be).
inline void as_stored(Lanes& value) { asm volatile("" : "+m"(value)); }

/// The lanes of a batch for taylor_steps (taylor.hpp): one order for every lane and every step,
/// from rtol (atol when rtol = 0), so that a lane's arithmetic never depends on its neighbours (a
/// member's result is the same in any batch); a lane in absolute mode (rtol·‖y‖ ≤ atol) sizes its
/// steps for atol at that order. Step size from the lanes' fast_log2 and fast_exp2 (as the scalar
/// path's: Eigen's log and exp took a third of the step's time outside the recursion); the new
/// state by Horner's scheme at each lane's own step, the components' chains side by side
/// (Estrin's, as the scalar path's, was 7–10 % slower here) or, where that order's ε is below
/// taylor_detail::compensate_below (rtol < 1e-12), as the scalar path makes it there (taylor.hpp:
/// advance_compensated): y + (c_1 dt added exactly) + the rest, with the state's rounding error
/// carried from step to step (with Horner's scheme alone the batch's state rounding walked as the
/// scalar's once did: error 2.85e-12 at rtol 1e-13 over the benchmark's t = 200, against 5.96e-13
/// for the scalar path).
template <class LaneModel>
class LaneTaylorRuns : public LaneRuns<LaneModel> {
public:
    using Base = LaneRuns<LaneModel>;
    using typename Base::State;
    using typename Base::Vector;
    static constexpr int dim = Base::dim;
    using Coefficient = Lanes[dim];
    static constexpr int max_taylor_order = LaneModel::max_taylor_order;

    LaneTaylorRuns(const LaneModel& model, const typename Base::System* const* systems, int count, Result* results,
                   const Options& options, double t0, double t1)
        : Base(model, systems, count, results, options, t0, t1), rtol_(options.rtol), atol_(std::max(options.atol, 0.0)) {
        const double eps = std::max(rtol_ > 0.0 ? rtol_ : atol_, 1e-300);
        order_ = taylor_detail::order_for(eps, max_taylor_order);
        safety_relative_ = taylor_detail::safety_for(std::max(rtol_, 1e-300), order_);
        safety_absolute_ = taylor_detail::safety_for(std::max(atol_, 1e-300), order_);
        compensated_ = eps < taylor_detail::compensate_below;
        for (Lanes& low : y_low_) low.setZero();
    }

    int prepare(const Vector& y, const Options& /*options*/) {
        norm_ = max_abs<dim>(y.data());
        const auto relative = rtol_ * norm_ > atol_;
        const Lanes log2_norm = fast_log2(norm_);  // (apart: a select's operands are evaluated lane by lane)
        log2_scale_ = relative.select(log2_norm, Lanes::Zero());
        safety_ = relative.select(Lanes::Constant(safety_relative_), Lanes::Constant(safety_absolute_));
        return order_;
    }
    template <int Order>
    void coefficients(const Lanes& /*t*/, const Vector& y, Coefficient* c) const {
        for (int i = 0; i < dim; ++i) c[0][i] = y[i];
        this->model().template taylor<Order>(c);
    }
    /// h = safety · min(ρ_{p−1}, ρ_p), ρ_m = (scale / ‖c_m‖)^{1/m} (a zero coefficient: no limit),
    /// in base-2 logarithms to ~2e-4 as the scalar path's (taylor_detail::step_size).
    template <int Order>
    Lanes step_size(const Coefficient* c) const {
        constexpr double inf = std::numeric_limits<double>::infinity();
        const Lanes c_low = max_abs<dim>(c[Order - 1]), c_high = max_abs<dim>(c[Order]);
        const Lanes low = (log2_scale_ - fast_log2(c_low)) * (1.0 / (Order - 1));
        const Lanes high = (log2_scale_ - fast_log2(c_high)) * (1.0 / Order);
        const Lanes exponent = (c_low == 0.0).select(Lanes::Constant(inf), low).min((c_high == 0.0).select(Lanes::Constant(inf), high));
        return safety_ * fast_exp2(exponent);
    }
    bool finite(int l, const Coefficient& c_last, const Lanes& h) const {
        bool finite = std::isfinite(norm_[l]) && !std::isnan(h[l]);
        for (int i = 0; i < dim && finite; ++i) finite = std::isfinite(c_last[i][l]);
        return finite;
    }
    /// (min_step(t) ≤ 10 ulp(t) ≤ 10·2⁻⁵²|t| for a normal t: a step above that bound needs no nextafter.)
    static bool too_small(double t, double step, double remaining, double direction) {
        if (step > 10.0 * 0x1p-52 * std::abs(t) + 1e-300) return false;
        return step < min_step(t, direction) && step != remaining;
    }
    /// Horner at each lane's own step (dt = 0 leaves a finished lane where it is); the outputs
    /// inside each lane's step from its polynomial.
    template <int Order>
    void advance(Lanes& t, Vector& y, const Coefficient* c, const Lanes& dt, double t1) {
        Vector y_new;
        const Vector low_start = y_low_;
        // Σ_{n ≥ lowest} c_n dt^{n − lowest} by Horner's scheme, the components' chains side by side
        const int lowest = compensated_ ? 2 : 0;
        Vector horner;
        for (int i = 0; i < dim; ++i) horner[i] = c[Order][i];
        for (int n = Order - 1; n >= lowest; --n)
            for (int i = 0; i < dim; ++i) horner[i] = horner[i] * dt + c[n][i];
        for (int i = 0; i < dim; ++i) {
            if (compensated_) {  // c_0 + c_1 dt + dt²(c_2 + c_3 dt + …) + low, as advance_compensated
                const Lanes rest = horner[i] * (dt * dt);
                Lanes first = c[1][i] * dt;
                as_stored(first);
                const Lanes partial = c[0][i] + first;
                const Lanes low = (taylor_detail::two_sum_error(c[0][i], first, partial) + product_error(c[1][i], dt, first)) +
                                  y_low_[i];
                const Lanes b = rest + low;
                y_new[i] = partial + b;
                y_low_[i] = taylor_detail::two_sum_error(partial, b, y_new[i]);
            } else {
                y_new[i] = horner[i];
            }
        }
        for (int l = 0; l < this->count(); ++l) {
            if (!this->active(l)) continue;
            const double t_new = (std::abs(t1 - t[l]) <= std::abs(dt[l])) ? t1 : t[l] + dt[l];
            this->inside(l, t_new, [&](double time) {
                const double s = time - t[l];
                State v;
                for (int i = 0; i < dim; ++i) {
                    double x = c[Order][i][l];
                    if (compensated_) {  // c_0 + (Σ_{n≥1} c_n sⁿ + low), as taylor_detail::evaluate_step
                        for (int n = Order - 1; n >= 1; --n) x = x * s + c[n][i][l];
                        v[i] = c[0][i][l] + (x * s + low_start[i][l]);
                    } else {
                        for (int n = Order - 1; n >= 0; --n) x = x * s + c[n][i][l];
                        v[i] = x;
                    }
                }
                return v;
            });
            Stats& stats = this->stats(l);
            ++stats.steps;
            ++stats.rhs_evals;  // one evaluation of the coefficient recursion per step
            stats.last_step = std::abs(dt[l]);
            t[l] = t_new;
        }
        if (compensated_) {  // the components the projection moves drop their low part (project_compensated)
            const Vector before = y_new;
            this->project(y_new);
            for (int i = 0; i < dim; ++i) y_low_[i] = (y_new[i] == before[i]).select(y_low_[i], Lanes::Zero());
        } else {
            this->project(y_new);
        }
        for (int l = 0; l < W; ++l) {
            if (!this->active(l)) {  // a lane that is done follows an active one (fill_done_lanes), its low part 0
                for (int i = 0; i < dim; ++i) y_low_[i][l] = 0.0;
                continue;
            }
            Base::copy_lane(y, y_new, l);
            this->at_end(l, t[l], y, 0.0);
        }
    }

private:
    double rtol_, atol_, safety_relative_ = 0.0, safety_absolute_ = 0.0;
    int order_ = 0;
    bool compensated_ = false;
    Lanes norm_, log2_scale_, safety_;
    Vector y_low_;  // the state's rounding error, carried between steps where compensated_
};

/// Integrates `count` ≤ W members in one batch with options.method (taylor or dop853; see
/// `applies`): results[0..count).
template <class System>
void solve_lanes(const System* const* members, int count, const typename System::State* y0, double t0, double t1,
                 const Options& options, const Control* control, Result* results) {
    const System* padded[W];
    for (int l = 0; l < W; ++l) padded[l] = members[std::min(l, count - 1)];
    using LaneModel = typename System::LaneModel;
    const LaneModel model(padded);
    if constexpr (model::system::has_taylor<LaneModel>::value) {
        if (options.method == Method::Taylor) {
            LaneTaylorRuns<LaneModel> run(model, padded, count, results, options, t0, t1);
            return taylor_steps(run, t0, run.load(y0), t1, options, control);
        }
    }
    LaneRuns<LaneModel> run(model, padded, count, results, options, t0, t1);
    dop853_steps(run, t0, run.load(y0), t1, options, control);
}

}  // namespace gyrostat::integrate::batch
