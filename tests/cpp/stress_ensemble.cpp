// Ensemble stress test, run plain and under the sanitizers in CI (AddressSanitizer with
// UndefinedBehaviorSanitizer, and ThreadSanitizer): every model family under every method, with
// good members beside members whose state is NaN, huge, blowing up or unreachable, on 4 threads.
// Each good member must equal its single run bit for bit; each bad one must end in a non-success
// status with a message (or succeed with a finite trajectory); the process must live.
// Then fault injection through the real seams: a member whose allocation fails, one whose GSL
// call fails, one whose CVODE solve fails, and (without sanitizers, in a forked child under a
// memory limit) threads that cannot be created and an output buffer that cannot be allocated.
#include <cmath>
#include <cstdio>
#include <iterator>
#include <limits>
#include <new>
#include <string>
#include <vector>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "gyrostat/engine.hpp"
#include "gyrostat/ensemble.hpp"
#include "gyrostat/numeric/elliptic.hpp"

#include "check.hpp"

using namespace gyrostat;
using integrate::Method;
using integrate::Status;


#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
constexpr bool kSanitized = true;  // their shadow memory does not live under RLIMIT_AS
#else
constexpr bool kSanitized = false;
#endif

static bool finite(const std::vector<double>& v) {
    for (double x : v)
        if (!std::isfinite(x)) return false;
    return true;
}

static bool same(const integrate::Result& a, const integrate::Result& b) {
    return a.status == b.status && a.t == b.t && a.y == b.y && a.outputs == b.outputs && a.message == b.message;
}

int main() {
    const Body body(Vec3(1.0, 2.0, 3.0));
    const Body sym(Vec3(1.5, 1.5, 1.0));
    const TorqueSet damping({torque::Constant(Vec3(0.0, 0.0, 0.02)), torque::LinearDamping(0.05 * Mat3::Identity())});
    const TorqueSet growth({torque::LinearDamping(-40.0 * Mat3::Identity())});  // |ω| ~ e^(40 t / A): blows up
    const std::vector<AnyModel> models{
        model::Gyrostat<false>(body, damping),
        model::Gyrostat<true>(body, damping),
        model::Gyrostat<false>(body, growth),
        model::AveragedSymmetric(Body(Vec3(8.0, 8.0, 4.0)), TorqueSet({torque::ViscousCavity(1260.0, 1000.0, 0.48)})),
        model::MovingMass(Body(Vec3(4.0, 4.0, 2.0)), 1.0, 1.0, 10.0, 98.0, TorqueSet{}),
        model::LagrangeTop(sym, 0.5, damping),
        model::LagrangeAveraged(sym, 0.5, damping),
        model::OrthogonalTorque<false>(Body(Vec3(2.0, 3.0, 4.0)), model::MagnitudeLaw::constant(0.1)),
        model::OrthogonalTorque<true>(Body(Vec3(2.0, 3.0, 4.0)), model::MagnitudeLaw::constant(0.1)),
        model::TorqueFree(body),
    };
    const double nan = std::numeric_limits<double>::quiet_NaN();

    // Members: per model, three good states, then NaN, huge and (where the model has one) an
    // unreachable state: a zero quaternion, a < 0 for the averaged model.
    std::vector<const AnyModel*> member_models;
    std::vector<Eigen::VectorXd> starts;
    std::vector<int> kind;  // 0 good, 1 NaN, 2 huge, 3 unreachable
    for (const auto& m : models) {
        const auto names = state_names(m);
        const std::string family = gyrostat::family(m);
        Eigen::VectorXd top(7);  // ω and a unit quaternion (nutation θ ≈ 0.2)
        top << 0.1, -0.2, 1.7, 0.995, 0.0998, 0.0, 0.0;
        top.tail<4>().normalize();
        Eigen::VectorXd good;
        if (family == "averaged_symmetric") good = Eigen::Vector2d(1.0, 1.0);
        else if (family == "lagrange_averaged" || family == "lagrange_top") good = initial_state(m, top);
        else if (family == "moving_mass") good = std::get<model::MovingMass>(m).quasi_static_state(Vec3(1.0, 0.0, 1.0));
        else good = initial_state(m, Eigen::Vector3d(1.0, 0.5, -0.3));
        for (int j = 0; j < 3; ++j) {
            Eigen::VectorXd y = good;
            y[0] += 0.01 * j;
            member_models.push_back(&m), starts.push_back(y), kind.push_back(0);
        }
        Eigen::VectorXd bad = good;
        bad[1] = nan;
        member_models.push_back(&m), starts.push_back(bad), kind.push_back(1);
        Eigen::VectorXd huge = good;
        huge[0] *= 1e150;
        member_models.push_back(&m), starts.push_back(huge), kind.push_back(2);
        if (good.size() >= 7 && names[3] == "q_w") {
            Eigen::VectorXd zero = good;
            zero.segment<4>(3).setZero();
            member_models.push_back(&m), starts.push_back(zero), kind.push_back(3);
        } else if (family == "averaged_symmetric") {
            member_models.push_back(&m), starts.push_back(Eigen::Vector2d(-1.0, 1.0)), kind.push_back(3);
        }
    }

    const Method methods[] = {Method::Dop853, Method::Taylor, Method::CvodeBdf, Method::CvodeAdams,
                              Method::ArkodeFehlberg8, Method::Auto};
    int counts[4][2] = {};  // [kind][success]
    for (Method method : methods) {
        integrate::Options options;
        options.method = method;
        options.rtol = 1e-8;
        options.atol = 1e-10;
        options.n_out = 21;
        // the blowing-up members end here (MaxStepsReached) under every method; 3000 > the 2163
        // steps of the huge member under BDF (it succeeds). 20000 made them ~95 % of the test's
        // time, 53 s under ASan at -O0 and 85 s under TSan, for the same paths.
        options.max_steps = 3000;
        const auto results = solve_ensemble(member_models, starts, 0.0, 2.0, options, 4);
        CHECK(results.size() == starts.size(), "one result per member");
        for (std::size_t i = 0; i < results.size(); ++i) {
            const auto& r = results[i];
            const std::string where = std::string(integrate::method_name(method)) + " member " + std::to_string(i) +
                                      " (" + gyrostat::family(*member_models[i]) + ", kind " + std::to_string(kind[i]) + ")";
            ++counts[kind[i]][r.success()];
            if (r.success()) {
                CHECK(finite(r.y) && !r.t.empty(), "a success is a finite trajectory: " + where);
                CHECK(kind[i] != 1 && kind[i] != 3, "NaN and unreachable states never succeed: " + where);
            } else {
                CHECK(!r.message.empty(), "a failure says why: " + where);
            }
            if (kind[i] == 0 || r.success()) {  // the same member alone
                integrate::Result single;
                try {
                    single = solve(*member_models[i], 0.0, starts[i], 2.0, options);
                } catch (const std::exception& e) {
                    single.status = Status::InvalidInput;
                    single.message = "member " + std::to_string(i) + ": " + e.what();
                }
                if (method == Method::Taylor || method == Method::Dop853) {
                    // members these methods may run in SIMD batches (integrate/batch.hpp): equal to
                    // the single run to the tolerance (rtol 1e-8; 100 rtol over the outputs)
                    bool close = r.status == single.status && r.t == single.t && r.y.size() == single.y.size();
                    for (std::size_t k = 0; close && k < r.y.size(); ++k)
                        close = std::abs(r.y[k] - single.y[k]) <= 1e-6 * std::max(1.0, std::abs(single.y[k]));
                    CHECK(close, "ensemble member = single run to the tolerance: " + where);
                } else {  // bit for bit
                    CHECK(r.status == single.status && r.t == single.t && r.y == single.y && r.outputs == single.outputs,
                          "ensemble member = single run: " + where);
                }
            }
        }
    }
    std::printf("stress: %zu members x %zu methods on 4 threads; good: %d succeeded, %d refused (method does not "
                "apply or the run failed); NaN: %d refused; huge: %d succeeded, %d failed; unreachable: %d refused\n",
                starts.size(), std::size(methods), counts[0][1], counts[0][0], counts[1][0], counts[2][1], counts[2][0],
                counts[3][0]);
    CHECK(counts[1][1] == 0 && counts[3][1] == 0, "no NaN or unreachable member succeeds");
    CHECK(counts[0][1] > 0 && counts[2][0] > 0, "the mix has successes and failures");

    // Fault injection through run_ensemble's own seam: member 3 runs out of memory, member 5's
    // GSL call fails (K(m) for m = 2), member 7's CVODE solve fails (the blowing-up model), member
    // 8 throws something that is not a std::exception; the others finish, equal to their single runs.
    {
        integrate::Options options;
        options.n_out = 11;
        integrate::Options stiff = options;
        stiff.method = Method::CvodeBdf;
        stiff.max_steps = 200;
        const Eigen::VectorXd w0 = Eigen::Vector3d(1.0, 0.5, -0.3);
        auto member = [&](std::size_t i, const integrate::Control* control) {
            if (i == 3) throw std::bad_alloc();
            if (i == 8) throw 42;  // not a std::exception: must not terminate the process
            if (i == 5) (void)model::elliptic_K(2.0);
            if (i == 7) return solve(models[2], 0.0, w0, 50.0, stiff, control);
            return solve(models[0], 0.0, w0, 5.0, options, control);
        };
        const auto results = run_ensemble(10, member, 4);
        const auto reference = solve(models[0], 0.0, w0, 5.0, options);
        for (std::size_t i = 0; i < results.size(); ++i) {
            if (i == 3) {
                CHECK(results[i].status == Status::SolverFailure && results[i].message.find("out of memory") != std::string::npos,
                      "an allocation failure is named: " + results[i].message);
            } else if (i == 5) {
                CHECK(results[i].status == Status::InvalidInput && results[i].message.find("m = 2") != std::string::npos,
                      "a GSL failure is named: " + results[i].message);
            } else if (i == 8) {
                CHECK(results[i].status == Status::SolverFailure && results[i].message.find("unknown exception") != std::string::npos,
                      "a foreign exception is contained: " + results[i].message);
            } else if (i == 7) {
                CHECK(!results[i].success() && !results[i].message.empty(), "a CVODE failure is named: " + results[i].message);
            } else {
                CHECK(same(results[i], reference), "the others finish as if alone");
            }
        }
    }

    // In a forked child under RLIMIT_AS (not with sanitizers: their shadow memory is reserved
    // up front): 64 threads asked for where only a few can be made, and a member whose output
    // buffer cannot be allocated beside one whose can.
    if (!kSanitized) {
        const pid_t child = fork();
        if (child == 0) {
            rlimit limit{};
            long pages = 0, resident = 0;
            if (FILE* f = std::fopen("/proc/self/statm", "r")) {
                if (std::fscanf(f, "%ld %ld", &pages, &resident) != 2) pages = 0;
                std::fclose(f);
            }
            const rlim_t base = static_cast<rlim_t>(pages) * static_cast<rlim_t>(sysconf(_SC_PAGESIZE));
            limit.rlim_cur = limit.rlim_max = base + (1100ull << 20);  // 1.1 GiB above what the child has
            if (setrlimit(RLIMIT_AS, &limit) != 0) _exit(3);
            integrate::Options options;
            options.n_out = 15'000'000;  // moving mass: 12 doubles per output (1.4 GB); gyrostat: 6 (0.7 GB)
            const Eigen::VectorXd w0 = Eigen::Vector3d(1.0, 0.5, -0.3);
            const Eigen::VectorXd mass0 = std::get<model::MovingMass>(models[4]).quasi_static_state(Vec3(1.0, 0.0, 1.0));
            const auto big = solve_ensemble({&models[4], &models[0]}, {mass0, w0}, 0.0, 1.0, options, 1);
            const bool big_ok = big[0].status == Status::SolverFailure && big[0].message.find("out of memory") != std::string::npos &&
                                big[1].success() && big[1].t.size() == 15'000'000;
            std::vector<const AnyModel*> many(64, &models[0]);
            integrate::Options small;
            small.n_out = 5;
            const auto threads = solve_ensemble(many, std::vector<Eigen::VectorXd>(64, w0), 0.0, 1.0, small, 64);
            bool threads_ok = true;
            for (const auto& r : threads) threads_ok = threads_ok && r.success();
            _exit(big_ok && threads_ok ? 0 : 1);
        }
        int status = 0;
        waitpid(child, &status, 0);
        CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 0,
              "under a memory limit: the outputs that fit are computed, the others say out of memory; "
              "the ensemble runs on the threads it can make (child exit " + std::to_string(WEXITSTATUS(status)) + ")");
    }

    std::printf("%d passed, %d failed\n", passes, failures);
    return failures == 0 ? 0 : 1;
}
