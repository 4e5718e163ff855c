// SIMD batches (integrate/batch.hpp) against the scalar path: ensembles with mixed lanes (other
// bodies, rotors and torques per lane; lanes that need very different numbers of steps; a lane
// that overflows while the others finish; a lane that runs out of steps), for taylor and dop853,
// the gyrostat with and without attitude and the averaged symmetric system; the user's vectorised
// compiled torque in the batches.
#include <atomic>
#include <cmath>
#include <memory>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "check.hpp"
#include "gyrostat/engine.hpp"
#include "gyrostat/integrate/batch.hpp"
#include "gyrostat/numeric/lanes.hpp"

using namespace gyrostat;
using integrate::Method;
using integrate::Options;
using integrate::Result;
using integrate::Status;

namespace {

/// max over outputs and components of |a − b| / max(1, |b|).
double difference(const Result& a, const Result& b) {
    if (a.y.size() != b.y.size() || a.t.size() != b.t.size()) return INFINITY;
    double d = 0.0;
    for (std::size_t i = 0; i < a.t.size(); ++i) d = std::max(d, std::abs(a.t[i] - b.t[i]));
    for (std::size_t i = 0; i < a.y.size(); ++i) d = std::max(d, std::abs(a.y[i] - b.y[i]) / std::max(1.0, std::abs(b.y[i])));
    for (std::size_t i = 0; i < a.outputs.size() && i < b.outputs.size(); ++i)
        if (std::isfinite(b.outputs[i]))
            d = std::max(d, std::abs(a.outputs[i] - b.outputs[i]) / std::max(1.0, std::abs(b.outputs[i])));
    return d;
}

/// 13 members (not a multiple of any lane width): bodies, rotors, damping and constant torques
/// vary per member; |ω0| spans 0.05 … 20, so lanes need from a few to thousands of steps.
template <bool A>
std::vector<AnyModel> mixed_gyrostats() {
    std::vector<AnyModel> models;
    for (int i = 0; i < 13; ++i) {
        const Vec3 moments(1.0 + 0.1 * i, 2.0 + 0.05 * i, 3.0 - 0.07 * i);
        const Vec3 rotor = (i % 3 == 0) ? Vec3(0.1, -0.2, 0.05 * i) : Vec3::Zero();
        std::vector<AnyTorque> torques;
        if (i % 2 == 0) torques.push_back(torque::LinearDamping(0.01 * (1 + i) * Mat3::Identity() + 0.001 * Mat3::Ones()));
        if (i % 4 == 1) torques.push_back(torque::Constant(Vec3(0.01, -0.02, 0.03 * i)));
        models.emplace_back(model::Gyrostat<A>(Body(moments, rotor), TorqueSet(torques)));
    }
    return models;
}

std::vector<Eigen::VectorXd> mixed_starts(int n) {
    std::vector<Eigen::VectorXd> starts;
    for (int i = 0; i < n; ++i) {
        const double scale = 0.05 * std::pow(1.6, i);  // 0.05 … 14
        starts.push_back(Eigen::Vector3d(scale * std::cos(i), scale * 0.5, -scale * std::sin(0.7 * i)));
    }
    return starts;
}

std::vector<const AnyModel*> pointers(const std::vector<AnyModel>& models) {
    std::vector<const AnyModel*> p;
    for (const auto& m : models) p.push_back(&m);
    return p;
}

Options options(Method method, double rtol, long n_out) {
    Options o;
    o.method = method;
    o.rtol = rtol;
    o.atol = 1e-12;
    o.n_out = n_out;
    return o;
}

template <bool A>
void batch_equals_scalar(Method method) {
    const std::string label = std::string(A ? "gyrostat with attitude" : "gyrostat") + ", " + integrate::method_name(method);
    const auto models = mixed_gyrostats<A>();
    const auto starts = mixed_starts(static_cast<int>(models.size()));
    const Options o = options(method, 1e-10, 41);
    const auto batched = solve_ensemble(pointers(models), starts, 0.0, 30.0, o, 2, nullptr, true);
    const auto single = solve_ensemble(pointers(models), starts, 0.0, 30.0, o, 2, nullptr, false);
    long fewest = 1L << 60, most = 0;
    for (std::size_t i = 0; i < models.size(); ++i) {
        const std::string what = label + ": member " + std::to_string(i);
        CHECK(batched[i].success() && single[i].success(), what + " succeeds: " + batched[i].message);
        // Both follow the same rules per lane at rtol 1e-10: they differ by rounding (and, for
        // taylor, by the common order of the batch), well inside 100 rtol over the outputs.
        CHECK(difference(batched[i], single[i]) < 100 * o.rtol, what + ": batch vs scalar " +
                                                                     std::to_string(difference(batched[i], single[i])));
        CHECK(batched[i].t_last == 30.0 && batched[i].y_last.size() == static_cast<std::size_t>(A ? 7 : 3), what + ": t_last");
        CHECK(batched[i].method == integrate::method_name(method), what + ": method named");
        // the step counts follow each lane's own step size (within 5 % of the scalar run's); a
        // single Taylor run takes its predicted step where the allowed one is larger (taylor.hpp:
        // OneTaylorRun::step_size), ~5 % more steps on the torque-free body and up to 8.5 % here
        // with the sanitizer builds' coarser orders: at most 15 % more than the lane's, never fewer
        // (beyond one)
        const long lane_steps = batched[i].stats.steps, own_steps = single[i].stats.steps;
        const bool steps_agree = method == Method::Taylor
                                     ? own_steps >= lane_steps - 1 && own_steps <= lane_steps + 1 + 3 * lane_steps / 20
                                     : std::abs(lane_steps - own_steps) <= 1 + own_steps / 20;
        CHECK(steps_agree, what + ": steps " + std::to_string(lane_steps) + " vs " + std::to_string(own_steps));
        const auto alone = solve(models[i], 0.0, starts[i], 30.0, o);
        CHECK(single[i].y == alone.y && single[i].t == alone.t, what + ": batch = false is the single run bit for bit");
        fewest = std::min(fewest, single[i].stats.steps);
        most = std::max(most, single[i].stats.steps);
    }
    CHECK(most > 10 * fewest, label + ": lanes finish at very different step counts (" + std::to_string(fewest) + " … " +
                                  std::to_string(most) + ")");
    if constexpr (A) {  // |q| = 1 at every output of the batch
        double worst = 0.0;
        for (const auto& r : batched)
            for (std::size_t k = 0; k < r.t.size(); ++k)
                worst = std::max(worst, std::abs(Eigen::Map<const Eigen::Vector4d>(&r.y[7 * k + 3]).norm() - 1.0));
        CHECK(worst < 1e-14, label + ": |q| = 1 to rounding");
    }
}

/// A lane that overflows (ω0 = 1e150: the quadratic terms exceed the doubles at once) and a lane
/// that runs out of steps, beside lanes that finish: the others equal their single runs.
void failing_lanes(Method method) {
    const std::string label = std::string("failing lanes, ") + integrate::method_name(method);
    const Body body(Vec3(1.0, 2.0, 3.0));
    std::vector<AnyModel> models(5, AnyModel(model::Gyrostat<false>(body, TorqueSet{})));
    std::vector<Eigen::VectorXd> starts(5, Eigen::Vector3d(1.0, 0.5, -0.3));
    starts[1] = Eigen::Vector3d(1e150, 2e150, -1e150);
    starts[3] = Eigen::Vector3d(400.0, 300.0, -200.0);  // fast: needs far more steps than the others
    Options o;
    o.method = method;
    o.rtol = 1e-9;
    o.atol = 1e-12;
    o.n_out = 11;
    // a budget the slow lanes meet and the fast one does not
    Options probe = o;
    const auto slow = solve(models[0], 0.0, starts[0], 10.0, probe);
    o.max_steps = 3 * slow.stats.steps;
    const auto batched = solve_ensemble(pointers(models), starts, 0.0, 10.0, o, 1, nullptr, true);
    const auto single = solve_ensemble(pointers(models), starts, 0.0, 10.0, o, 1, nullptr, false);
    CHECK(batched[1].status == Status::NonFiniteState, label + ": the overflowing lane fails: " + batched[1].message);
    CHECK(batched[1].status == single[1].status, label + ": as its single run");
    CHECK(batched[3].status == Status::MaxStepsReached && batched[3].stats.steps == o.max_steps,
          label + ": the fast lane runs out of steps: " + batched[3].message);
    CHECK(batched[3].t.size() == single[3].t.size(), label + ": and keeps the outputs up to there");
    for (int i : {0, 2, 4}) {
        CHECK(batched[i].success(), label + ": lane " + std::to_string(i) + " finishes");
        CHECK(difference(batched[i], single[i]) < 100 * o.rtol, label + ": lane " + std::to_string(i) + " equals its single run");
    }
}

void averaged_batch() {
    std::vector<AnyModel> models;
    std::vector<Eigen::VectorXd> starts;
    for (int i = 0; i < 9; ++i) {
        std::vector<AnyTorque> torques{torque::ViscousCavity(1260.0, 1000.0 * (1 + 0.1 * i), 0.48)};
        if (i % 2) torques.push_back(torque::LinearDamping(0.01 * Mat3::Identity()));
        models.emplace_back(model::AveragedSymmetric(Body(Vec3(8.0, 8.0, 4.0 + 0.2 * i)), TorqueSet(torques)));
        starts.push_back(Eigen::Vector2d(1.0 + 0.1 * i, 0.5 - 0.1 * i));
    }
    Options o;
    o.rtol = 1e-10;
    o.atol = 1e-12;
    o.n_out = 21;
    const auto batched = solve_ensemble(pointers(models), starts, 0.0, 50.0, o, 2, nullptr, true);
    const auto single = solve_ensemble(pointers(models), starts, 0.0, 50.0, o, 2, nullptr, false);
    for (std::size_t i = 0; i < models.size(); ++i) {
        CHECK(batched[i].success(), "averaged member " + std::to_string(i) + ": " + batched[i].message);
        CHECK(difference(batched[i], single[i]) < 100 * o.rtol, "averaged member " + std::to_string(i) + " equals its single run");
    }
}

/// A member's batched result does not depend on the members beside it (nor on being alone):
/// ensembles and sweeps give the same numbers however they are chunked.
void independent_of_neighbours(Method method) {
    const std::string label = std::string("neighbours, ") + integrate::method_name(method);
    const auto models = mixed_gyrostats<true>();
    const auto starts = mixed_starts(static_cast<int>(models.size()));
    const Options o = options(method, 1e-9, 11);
    const auto all = solve_ensemble(pointers(models), starts, 0.0, 10.0, o, 1, nullptr, true);
    for (std::size_t i : {0, 4, 12}) {  // first, middle and last of the ensemble, now alone
        const std::vector<const AnyModel*> one{&models[i]};
        const auto alone = solve_ensemble(one, {starts[i]}, 0.0, 10.0, o, 1, nullptr, true);
        CHECK(alone[0].y == all[i].y && alone[0].stats.steps == all[i].stats.steps,
              label + ": member " + std::to_string(i) + " alone = in the ensemble, bit for bit");
    }
    // the members in reverse order: other neighbours, other lanes
    std::vector<const AnyModel*> reversed;
    std::vector<Eigen::VectorXd> reversed_starts;
    for (std::size_t i = models.size(); i-- > 0;) reversed.push_back(&models[i]), reversed_starts.push_back(starts[i]);
    const auto back = solve_ensemble(reversed, reversed_starts, 0.0, 10.0, o, 2, nullptr, true);
    bool same = true;
    for (std::size_t i = 0; i < models.size(); ++i) same = same && back[models.size() - 1 - i].y == all[i].y;
    CHECK(same, label + ": members in reverse order (other lanes, other neighbours): the same bits");
}

/// The widest n a vectorised user torque below was called with.
std::atomic<int> widest_call{0};

/// A user's vectorised torque (torque/custom.hpp), structure of arrays: M = −c ω + (0, 0, a sin t)
/// per member, c = user_data[0], a = user_data[1].
int drag_lanes(int n, const double* t, const double* omega, const double* /*q*/, double* moment, void* data) {
    for (int seen = widest_call.load(); n > seen && !widest_call.compare_exchange_weak(seen, n);) {
    }
    const double* p = static_cast<const double*>(data);
    for (int l = 0; l < n; ++l) {
        for (int i = 0; i < 3; ++i) moment[i * n + l] = -p[0] * omega[i * n + l];
        moment[2 * n + l] += p[1] * std::sin(t[l]);
    }
    return 0;
}

/// The mixed gyrostats with a vectorised user torque each (`data`: one for all, or alternating
/// with `other`): the batches call it with n = W and equal the scalar runs to the tolerance; a
/// member whose lanes hold other user torques (called lane by lane) keeps its bits.
template <bool A>
void user_vector_torque() {
    const std::string label = std::string("vectorised user torque, ") + (A ? "with attitude" : "omega alone");
    static double data[2] = {0.03, 0.02}, other[2] = {0.05, -0.01};
    auto with_user = [&](bool alternate) {
        std::vector<AnyModel> models;
        const auto plain = mixed_gyrostats<A>();
        for (std::size_t i = 0; i < plain.size(); ++i) {
            const auto& m = std::get<model::Gyrostat<A>>(plain[i]);
            std::vector<AnyTorque> torques = m.torques().parts();
            void* user = alternate && i % 2 ? other : data;
            torques.push_back(torque::Custom(std::make_shared<torque::CompiledTorqueFunction>(
                                                 "drag_lanes", torque::VectorForm{&drag_lanes, user}),
                                             "drag_lanes", false));
            models.emplace_back(model::Gyrostat<A>(m.body(), TorqueSet(torques)));
        }
        return models;
    };
    const auto models = with_user(false), mixed = with_user(true);
    const auto starts = mixed_starts(static_cast<int>(models.size()));
    const Options o = options(Method::Dop853, 1e-10, 21);
    widest_call = 0;
    const auto single = solve_ensemble(pointers(models), starts, 0.0, 20.0, o, 2, nullptr, false);
    CHECK(widest_call == 1, label + ": single runs call with n = 1");
    const auto batched = solve_ensemble(pointers(models), starts, 0.0, 20.0, o, 2, nullptr, true);
    CHECK(widest_call == lanes::width, label + ": the batches call with n = W (" + std::to_string(widest_call) + ")");
    for (std::size_t i = 0; i < models.size(); ++i) {
        const std::string what = label + ": member " + std::to_string(i);
        CHECK(batched[i].success() && single[i].success(), what + " succeeds: " + batched[i].message);
        // as batch_equals_scalar: the same rules per lane, other rounding, within 100 rtol
        CHECK(difference(batched[i], single[i]) < 100 * o.rtol,
              what + ": batch vs scalar " + std::to_string(difference(batched[i], single[i])));
    }
    const auto lane_by_lane = solve_ensemble(pointers(mixed), starts, 0.0, 20.0, o, 2, nullptr, true);
    bool same = true;
    for (std::size_t i = 0; i < models.size(); i += 2) same = same && lane_by_lane[i].y == batched[i].y;
    CHECK(same, label + ": a member beside lanes with another user torque keeps its bits");
}

/// Below rtol 1e-12 the Taylor lanes carry the state's rounding error (batch.hpp, as the scalar
/// path): 13 torque-free bodies over t = 200 at rtol 1e-13 against the closed form (the engine's
/// TorqueFree, exact to ~1e-15 here) and against their scalar runs. Measured (this build's SSE2
/// lanes, Dekker's product): the batch 4.6e-14 from the closed form and 5.2e-14 from the scalar
/// runs (the AVX-512 form from Python: 4.5e-14, and 7.2e-14 with the state rounded once per step;
/// Python's tests/test_batch.py tells the two apart on 64 members, here the sanitizers run the path).
void compensated_lanes() {
    std::vector<AnyModel> models, exact_models;
    std::vector<Eigen::VectorXd> starts;
    for (int i = 0; i < 13; ++i) {
        const Body body(Vec3(1.0 + 0.1 * i, 2.0 + 0.05 * i, 3.0 - 0.07 * i));
        models.emplace_back(model::Gyrostat<false>(body, TorqueSet{}));
        exact_models.emplace_back(model::TorqueFree(body));
        starts.push_back(Eigen::Vector3d(0.5 * std::cos(i), 0.5, -0.5 * std::sin(0.7 * i)));
    }
    Options o = options(Method::Taylor, 1e-13, 2);
    o.atol = 1e-16;
    const auto batched = solve_ensemble(pointers(models), starts, 0.0, 200.0, o, 2, nullptr, true);
    const auto single = solve_ensemble(pointers(models), starts, 0.0, 200.0, o, 2, nullptr, false);
    const auto exact = solve_ensemble(pointers(exact_models), starts, 0.0, 200.0, o, 2, nullptr, false);
    auto final_apart = [](const Result& a, const Result& b) -> double {  // |ω_a(t1) − ω_b(t1)|
        if (a.y.size() != 6 || b.y.size() != 6) return INFINITY;
        return std::hypot(a.y[3] - b.y[3], a.y[4] - b.y[4], a.y[5] - b.y[5]);
    };
    double worst = 0.0, apart = 0.0;
    for (std::size_t i = 0; i < models.size(); ++i) {
        CHECK(batched[i].success() && exact[i].success(), "compensated lanes: member " + std::to_string(i) + " succeeds");
        worst = std::max(worst, final_apart(batched[i], exact[i]) / starts[i].norm());
        apart = std::max(apart, final_apart(batched[i], single[i]) / starts[i].norm());
    }
    char measured[96];
    std::snprintf(measured, sizeof measured, "batch vs closed form %.2e, vs scalar %.2e", worst, apart);
    CHECK(worst < 2e-13 && apart < 2e-13, std::string("compensated lanes at rtol 1e-13: ") + measured + " (bound 2e-13)");
}

/// The step size's fast_log2 and fast_exp2 in lanes (batch.hpp, a form the compiler vectorises)
/// give the scalar path's values bit for bit (taylor.hpp), so that a lane's step sizes are the
/// scalar rule's: positive numbers over every exponent (subnormals included), 0, ∞ and NaN for the
/// logarithm; arguments across [−1100, 1100] (both clamps, the integers, ±0), ±∞ and NaN for 2^y;
/// and both within their stated accuracy of libm's (log2 1.4e-3 absolute, 2^y 1.9e-4 relative).
void fast_functions_in_lanes() {
    using integrate::batch::Lanes;
    namespace detail = integrate::taylor_detail;
    auto same = [](double a, double b) { return (std::isnan(a) && std::isnan(b)) || std::memcmp(&a, &b, sizeof a) == 0; };
    std::vector<double> xs{0.0, 5e-324, 1e-310, 2.2250738585072014e-308, INFINITY, NAN, 1.0, 2.0, 0.75, 1.7976931348623157e308};
    for (int e = -1074; e <= 1023; e += 7) xs.push_back(std::ldexp(1.0 + std::fmod(0.618 * (e + 1074), 1.0), e));
    std::vector<double> ys{-INFINITY, INFINITY, NAN, -0.0, 0.0, -1022.0, -1022.5, 1022.0, 1022.999, 1023.0, -1.0, 1.0};
    for (int k = 0; k <= 22000; ++k) ys.push_back(-1100.0 + 0.1 * k + 1e-3 * std::sin(k));
    int log_apart = 0, exp_apart = 0;
    double log_error = 0.0, exp_error = 0.0;
    for (std::size_t i = 0; i < xs.size(); ++i) {
        Lanes x = Lanes::Constant(xs[i]);
        x[0] = xs[(i + 1) % xs.size()];  // the lanes need not agree
        const Lanes out = integrate::batch::fast_log2(x);
        for (int l = 0; l < lanes::width; ++l) log_apart += !same(out[l], detail::fast_log2(x[l]));
        if (xs[i] >= 2.2250738585072014e-308 && std::isfinite(xs[i]))
            log_error = std::max(log_error, std::abs(detail::fast_log2(xs[i]) - std::log2(xs[i])));
    }
    for (std::size_t i = 0; i < ys.size(); ++i) {
        Lanes y = Lanes::Constant(ys[i]);
        y[lanes::width - 1] = ys[(i + 7) % ys.size()];
        const Lanes out = integrate::batch::fast_exp2(y);
        for (int l = 0; l < lanes::width; ++l) exp_apart += !same(out[l], detail::fast_exp2(y[l]));
        if (ys[i] >= -1022.0 && ys[i] < 1023.0)
            exp_error = std::max(exp_error, std::abs(detail::fast_exp2(ys[i]) / std::exp2(ys[i]) - 1.0));
    }
    char measured[128];
    std::snprintf(measured, sizeof measured, "%d and %d lanes apart; log2 within %.2e, exp2 within %.2e", log_apart,
                  exp_apart, log_error, exp_error);
    CHECK(log_apart == 0 && exp_apart == 0 && log_error < 1.4e-3 && exp_error < 1.9e-4,
          std::string("lane fast_log2 / fast_exp2 equal the scalar ones: ") + measured);
}

/// A stop flag set before the run: every lane ends Interrupted with its start recorded.
void interrupted_batch() {
    const auto models = mixed_gyrostats<false>();
    const auto starts = mixed_starts(static_cast<int>(models.size()));
    Options o;
    o.method = Method::Taylor;
    std::atomic<bool> stop{true};
    integrate::Control control;
    control.stop = &stop;
    const auto r = solve_ensemble(pointers(models), starts, 0.0, 30.0, o, 1, &control, true);
    bool all = true;
    for (const auto& x : r) all = all && x.status == Status::Interrupted;
    CHECK(all, "a stopped batch ensemble: every member interrupted");
}

}  // namespace

int main() {
    // The portable recursion for the scalar runs: on a CPU with AVX2 the portable build's ensembles
    // run taylor for ω alone one body at a time (integrate::batch::applies), and these tests are
    // about the batches. (Set before anything asks affine_euler_avx2_available, which decides once.)
    setenv("GYROSTAT_PORTABLE_KERNELS", "1", 1);
    std::printf("SIMD lanes: %d (%s)\n", lanes::width, lanes::instruction_set);
    batch_equals_scalar<false>(Method::Taylor);
    batch_equals_scalar<true>(Method::Taylor);
    batch_equals_scalar<false>(Method::Dop853);
    batch_equals_scalar<true>(Method::Dop853);
    failing_lanes(Method::Taylor);
    failing_lanes(Method::Dop853);
    averaged_batch();
    independent_of_neighbours(Method::Taylor);
    independent_of_neighbours(Method::Dop853);
    interrupted_batch();
    compensated_lanes();
    fast_functions_in_lanes();
    user_vector_torque<false>();
    user_vector_torque<true>();
    std::printf("%d passed, %d failed\n", passes, failures);
    return failures == 0 ? 0 : 1;
}
