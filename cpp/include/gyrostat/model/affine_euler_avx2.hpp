// The rate part of the affine Euler Taylor recursion (affine_euler.hpp) for one body, compiled for
// AVX2 + FMA and chosen at run time. The default build targets the baseline x86-64 CPU (SSE2):
// only the function below is compiled for AVX2 + FMA (GCC's target attribute), and the Gyrostat
// calls it only where the CPU has both (`affine_euler_avx2_available`, checked once); elsewhere,
// or with the environment variable GYROSTAT_PORTABLE_KERNELS=1, it uses the portable recursion.
// The two agree to rounding (the order of the sums and the fused multiply-adds differ), asserted
// in tests/cpp/test_core.cpp.
//
// Lanes i = 0, 1, 2 of a 4-wide vector hold component i, j = i + 1 or k = i + 2 (mod 3) of a
// coefficient of ω (lane 3 is zero):
//   W[n] = (ω1, ω2, ω3, 0)[n],   U[n] = (ω2, ω3, ω1, 0)[n],   V[n] = (ω3, ω1, ω2, 0)[n],
// so that the three Cauchy products P_i[n] = Σ_m ω_j[m] ω_k[n−m] are one lane-wise sum
//   P[n] = Σ_{m=0}^{n} U[m] ⊙ V[n−m],
// and the affine terms −(ω[n] × k)_i − (D ω[n])_i = k_j ω_k − k_k ω_j − D_ii ω_i − D_ij ω_j − D_ik ω_k
// are lane-wise too:
//   a[n] = L_W ⊙ W[n] + L_U ⊙ U[n] + L_V ⊙ V[n],   L_W = −D_ii,  L_U = −D_ij − k_k,  L_V = −D_ik + k_j.
// The recursion (affine_euler.hpp), with K = (A_j − A_k) J_i⁻¹,
//   W[n+1] = (K ⊙ P[n] + J⁻¹ ⊙ (a[n] + M0 δ_{n0})) / (n + 1),
// is one chain of dependent operations from order to order. The newest coefficient W[n] enters
// order n + 1 only linearly (the terms m = 0 and m = n of P[n], and a[n]), so for n ≥ 1
//   W[n+1] = (K ⊙ Σ_{m=1}^{n−1} U[m] ⊙ V[n−m] + B_W ⊙ W[n] + B_U ⊙ U[n] + B_V ⊙ V[n]) / (n + 1),
//   B_W = J⁻¹ ⊙ L_W,   B_U = K ⊙ V[0] + J⁻¹ ⊙ L_U,   B_V = K ⊙ U[0] + J⁻¹ ⊙ L_V,
// with B_W, B_U, B_V fixed for the whole step: from W[n] to W[n+1] the chain is one permutation
// (U[n], V[n] from W[n]) and two or three fused multiply-adds, while the sum over the older terms
// runs beside it. (The portable recursion's chain is a product, two sums and two products.)
#pragma once

#include <cstdlib>

#include "gyrostat/model/affine_euler.hpp"

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define GYROSTAT_HAS_AVX2_KERNEL 1
#include <immintrin.h>
#endif

namespace gyrostat::model {

/// Whether affine_euler_rate_orders_avx2 may run here: the CPU has AVX2 and FMA, and the
/// environment variable GYROSTAT_PORTABLE_KERNELS is not set to 1 (to time or test the portable
/// recursion on such a CPU). Decided once per process.
inline bool affine_euler_avx2_available() {
#ifdef GYROSTAT_HAS_AVX2_KERNEL
    static const bool available = [] {
        const char* portable = std::getenv("GYROSTAT_PORTABLE_KERNELS");
        if (portable && portable[0] == '1') return false;
        __builtin_cpu_init();
        return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    }();
    return available;
#else
    return false;
#endif
}

#ifdef GYROSTAT_HAS_AVX2_KERNEL
/// to[0 … 2] ← lanes 0 … 2 of w.
__attribute__((target("avx2,fma"), always_inline)) inline void store_rate(double* to, __m256d w) {
    alignas(32) double lanes[4];
    _mm256_store_pd(lanes, w);
    to[0] = lanes[0], to[1] = lanes[1], to[2] = lanes[2];
}

/// The linear part's lane vectors L_W, L_U, L_V (the comment at the top of this file).
__attribute__((target("avx2,fma"), always_inline)) inline void lane_linear_part(const AffineEuler<double>& e,
                                                                                __m256d& l_w, __m256d& l_u,
                                                                                __m256d& l_v) {
    const double* d = e.damping;  // row-major
    const double* rotor = e.rotor;
    l_w = _mm256_setzero_pd(), l_u = l_w, l_v = l_w;
    if (e.damped) {
        l_w = _mm256_setr_pd(-d[0], -d[4], -d[8], 0.0);
        l_u = _mm256_setr_pd(-d[1], -d[5], -d[6], 0.0);
        l_v = _mm256_setr_pd(-d[2], -d[3], -d[7], 0.0);
    }
    if (e.has_rotor) {
        l_u = _mm256_sub_pd(l_u, _mm256_setr_pd(rotor[2], rotor[0], rotor[1], 0.0));
        l_v = _mm256_add_pd(l_v, _mm256_setr_pd(rotor[1], rotor[2], rotor[0], 0.0));
    }
}

/// The rounding error of a + b, lane-wise (Knuth's two-sum, as dd_detail::two_sum).
__attribute__((target("avx2,fma"), always_inline)) inline __m256d lane_sum_error(__m256d a, __m256d b, __m256d sum) {
    const __m256d b_virtual = _mm256_sub_pd(sum, a);
    return _mm256_add_pd(_mm256_sub_pd(a, _mm256_sub_pd(sum, b_virtual)), _mm256_sub_pd(b, b_virtual));
}

/// affine_euler_rate_error (affine_euler.hpp) in lanes, the error-free products by fused
/// multiply-adds: the same quantity to ~2⁻¹⁰⁰ of f. Call only where affine_euler_avx2_available().
__attribute__((target("avx2,fma"))) inline void affine_euler_rate_error_avx2(const AffineEuler<double>& e,
                                                                             const double* w, const double* low,
                                                                             const double* c1, double* error) {
    constexpr int rotate_j = 1 | (2 << 2) | (0 << 4) | (3 << 6);
    constexpr int rotate_k = 2 | (0 << 2) | (1 << 4) | (3 << 6);
    const __m256d W = _mm256_setr_pd(w[0], w[1], w[2], 0.0);
    const __m256d U = _mm256_permute4x64_pd(W, rotate_j), V = _mm256_permute4x64_pd(W, rotate_k);
    const __m256d W_low = _mm256_setr_pd(low[0], low[1], low[2], 0.0);
    const __m256d U_low = _mm256_permute4x64_pd(W_low, rotate_j), V_low = _mm256_permute4x64_pd(W_low, rotate_k);
    const __m256d jinv = _mm256_setr_pd(e.inverse_moments[0], e.inverse_moments[1], e.inverse_moments[2], 0.0);
    const __m256d diff = _mm256_setr_pd(e.differences[0], e.differences[1], e.differences[2], 0.0);
    // f·J = (A_j − A_k) ω_j ω_k + Σ_l A_il ω_l + M0 as sum + sum_low
    const __m256d product = _mm256_mul_pd(U, V);
    const __m256d product_low = _mm256_fmsub_pd(U, V, product);
    __m256d sum = _mm256_mul_pd(diff, product);
    __m256d sum_low = _mm256_fmadd_pd(diff, product_low, _mm256_fmsub_pd(diff, product, sum));
    __m256d linear = _mm256_mul_pd(diff, _mm256_fmadd_pd(U_low, V, _mm256_mul_pd(U, V_low)));
    if (e.damped || e.has_rotor) {
        __m256d l_w, l_u, l_v;
        lane_linear_part(e, l_w, l_u, l_v);
        const __m256d terms[3][3] = {{l_w, W, W_low}, {l_u, U, U_low}, {l_v, V, V_low}};
        for (const auto& t : terms) {
            const __m256d term = _mm256_mul_pd(t[0], t[1]);
            const __m256d next = _mm256_add_pd(sum, term);
            sum_low = _mm256_add_pd(sum_low, _mm256_add_pd(_mm256_fmsub_pd(t[0], t[1], term), lane_sum_error(sum, term, next)));
            sum = next;
            linear = _mm256_fmadd_pd(t[0], t[2], linear);
        }
    }
    const __m256d constant = _mm256_setr_pd(e.constant[0], e.constant[1], e.constant[2], 0.0);
    const __m256d next = _mm256_add_pd(sum, constant);
    sum_low = _mm256_add_pd(sum_low, lane_sum_error(sum, constant, next));
    sum = next;
    const __m256d f = _mm256_mul_pd(jinv, sum);
    const __m256d f_low = _mm256_fmadd_pd(jinv, sum_low, _mm256_fmsub_pd(jinv, sum, f));
    const __m256d result = _mm256_add_pd(_mm256_sub_pd(f, _mm256_setr_pd(c1[0], c1[1], c1[2], 0.0)),
                                         _mm256_fmadd_pd(jinv, linear, f_low));
    store_rate(error, result);
}

/// c[n·stride + i] ← ω_i[n], n = 1 … order, from c[0 … 2] = ω[0] (the comment at the top of this
/// file). Call only where affine_euler_avx2_available().
template <int order>
__attribute__((target("avx2,fma"))) void affine_euler_rate_orders_avx2(const AffineEuler<double>& e, double* c,
                                                                        int stride) {
    // (_mm256_permute4x64_pd's control: lane i of the result takes lane (imm >> 2i) & 3 of the input)
    constexpr int rotate_j = 1 | (2 << 2) | (0 << 4) | (3 << 6);  // (x1, x2, x0, x3): W → U
    constexpr int rotate_k = 2 | (0 << 2) | (1 << 4) | (3 << 6);  // (x2, x0, x1, x3): W → V
    const __m256d jinv = _mm256_setr_pd(e.inverse_moments[0], e.inverse_moments[1], e.inverse_moments[2], 0.0);
    const __m256d k = _mm256_mul_pd(_mm256_setr_pd(e.differences[0], e.differences[1], e.differences[2], 0.0), jinv);
    __m256d l_w, l_u, l_v;
    lane_linear_part(e, l_w, l_u, l_v);
    const bool affine = e.damped || e.has_rotor;

    __m256d W[order + 1], U[order + 1], V[order + 1];
    W[0] = _mm256_setr_pd(c[0], c[1], c[2], 0.0);
    U[0] = _mm256_permute4x64_pd(W[0], rotate_j);
    V[0] = _mm256_permute4x64_pd(W[0], rotate_k);
    const __m256d b_w = _mm256_mul_pd(jinv, l_w);
    const __m256d b_u = _mm256_fmadd_pd(k, V[0], _mm256_mul_pd(jinv, l_u));
    const __m256d b_v = _mm256_fmadd_pd(k, U[0], _mm256_mul_pd(jinv, l_v));
    {  // n = 0: W[1] = K ⊙ U[0] ⊙ V[0] + J⁻¹ ⊙ (a[0] + M0)
        __m256d a = _mm256_setr_pd(e.constant[0], e.constant[1], e.constant[2], 0.0);
        if (affine) a = _mm256_fmadd_pd(l_w, W[0], _mm256_fmadd_pd(l_u, U[0], _mm256_fmadd_pd(l_v, V[0], a)));
        W[1] = _mm256_fmadd_pd(_mm256_mul_pd(k, U[0]), V[0], _mm256_mul_pd(jinv, a));
        U[1] = _mm256_permute4x64_pd(W[1], rotate_j);
        V[1] = _mm256_permute4x64_pd(W[1], rotate_k);
        store_rate(c + stride, W[1]);
    }
#pragma GCC unroll 32
    for (int n = 1; n < order; ++n) {
        // Σ_{m=1}^{n−1} U[m] ⊙ V[n−m] in two sums, from the middle out: the terms of the newest
        // coefficients (m = 1 and m = n − 1) are added last.
        __m256d front = _mm256_setzero_pd(), back = front;
#pragma GCC unroll 16
        for (int m = n / 2; m >= 1; --m) {
            front = _mm256_fmadd_pd(U[m], V[n - m], front);
            if (m != n - m) back = _mm256_fmadd_pd(U[n - m], V[m], back);
        }
        const __m256d inv = _mm256_set1_pd(1.0 / (n + 1));
        __m256d next = _mm256_mul_pd(_mm256_mul_pd(k, inv), _mm256_add_pd(front, back));
        if (affine) next = _mm256_fmadd_pd(_mm256_mul_pd(b_w, inv), W[n], next);
        next = _mm256_fmadd_pd(_mm256_mul_pd(b_u, inv), U[n], next);
        next = _mm256_fmadd_pd(_mm256_mul_pd(b_v, inv), V[n], next);
        W[n + 1] = next;
        U[n + 1] = _mm256_permute4x64_pd(next, rotate_j);
        V[n + 1] = _mm256_permute4x64_pd(next, rotate_k);
        store_rate(c + (n + 1) * stride, next);
    }
}
#endif

}  // namespace gyrostat::model
