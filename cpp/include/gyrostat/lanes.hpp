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
