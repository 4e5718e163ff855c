// SIMD lanes: W trajectories integrated side by side, one per lane of a fixed-size Eigen array,
// so that every arithmetic operation of a step acts on W members at once (integrate/batch.hpp).
//
// The width follows the instruction set the library is compiled for: 8 doubles with AVX-512,
// 4 with AVX/AVX2, 4 (two SSE2 registers per operation) on any other x86-64 or other CPU. The
// default build targets the baseline x86-64 CPU, so the package runs everywhere; the opt-in
// native build (CMake option GYROSTAT_NATIVE, README "Native build") compiles for the machine's
// own CPU and widens the lanes there.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <type_traits>

namespace gyrostat::lanes {

#if defined(__AVX512F__)
inline constexpr int width = 8;
inline constexpr const char* instruction_set = "avx512f";
#elif defined(__AVX2__)
inline constexpr int width = 4;
inline constexpr const char* instruction_set = "avx2";
#elif defined(__AVX__)
inline constexpr int width = 4;
inline constexpr const char* instruction_set = "avx";
#elif defined(__SSE2__)
inline constexpr int width = 4;
inline constexpr const char* instruction_set = "sse2";
#else
inline constexpr int width = 4;
inline constexpr const char* instruction_set = "scalar";
#endif

/// W doubles, one per trajectory.
using Lanes = Eigen::Array<double, width, 1>;

/// Whether the lanes fill a register wider than SSE2's (an AVX or AVX-512 build).
#if defined(__AVX__)
inline constexpr bool wide = true;
#else
inline constexpr bool wide = false;
#endif

// One trajectory's value (double) or W of them (Lanes) through the same calls, so that one step
// loop serves both (integrate/dop853.hpp, integrate/taylor.hpp): lane l of a value, and the few
// operations whose spelling differs between a double and an Eigen array.
inline double& lane(double& v, int /*l*/) { return v; }
inline double lane(const double& v, int /*l*/) { return v; }
inline double& lane(Lanes& v, int l) { return v[l]; }
inline double lane(const Lanes& v, int l) { return v[l]; }
inline double sqrt(double x) { return std::sqrt(x); }
inline Lanes sqrt(const Lanes& x) { return x.sqrt(); }
inline double min(double a, double b) { return std::min(a, b); }
inline Lanes min(const Lanes& a, double b) { return a.min(Lanes::Constant(b)); }
/// cond ? a : b (for lanes: lane by lane; both sides are evaluated).
inline double select(bool cond, double a, double b) { return cond ? a : b; }
template <class Cond, class B>
Lanes select(const Eigen::ArrayBase<Cond>& cond, double a, const B& b) {
    return cond.select(Lanes::Constant(a), b);
}

/// The value x in every lane (T = double: x itself), so that one template serves one trajectory
/// and W of them.
template <class T>
T splat(double x) {
    if constexpr (std::is_same_v<T, double>)
        return x;
    else
        return T::Constant(x);
}

}  // namespace gyrostat::lanes
