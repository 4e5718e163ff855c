// Elliptic integrals and Jacobi elliptic functions (GSL, every return code checked), shared by
// the closed forms of the torque-free body and of the Lagrange top.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <type_traits>

#include "gyrostat/numeric/complete_elliptic.hpp"
#include "gyrostat/numeric/double_double.hpp"

namespace gyrostat::model {

// ---------------------------------------------------------------------------------------------
// Elliptic functions (GSL; compiled in elliptic.cpp). Every function takes the PARAMETER m = k²
// (SciPy's convention and the paper's k²); GSL's complete integrals take the modulus k and are
// called with k = √m inside. Out-of-range arguments throw std::invalid_argument naming the value.
// ---------------------------------------------------------------------------------------------

/// K(m) = ∫_0^{π/2} dϑ / √(1 − m sin²ϑ), 0 ≤ m ≤ 1 (K(1) = +∞).
double elliptic_K(double m);
/// E(m) = ∫_0^{π/2} √(1 − m sin²ϑ) dϑ, 0 ≤ m ≤ 1.
double elliptic_E(double m);
/// (sn, cn, dn)(u | m), 0 ≤ m ≤ 1: jacobi_sn_cn_dn_complementary(u, 1 − m).
std::array<double, 3> jacobi_sn_cn_dn(double u, double m);
/// (sn, cn, dn)(u | m) with the parameter given by its complement m1 = 1 − m, 0 ≤ m1 ≤ 1, so that
/// m next to 1 (the free body next to its separatrix: m1 down to 1e-30 and below) keeps every digit
/// of m1 (1 − m in double would round m1 < 1.1e-16 to 0 or to a multiple of 2^-53).
///
/// Bulirsch's descending Gauss transformation (R. Bulirsch, Numer. Math. 7 (1965) 78, "sncndn";
/// DLMF 22.20(ii)): the AGM a_0 = 1, b_0 = √m1, a_{n+1} = (a_n + b_n)/2, b_{n+1} = √(a_n b_n) to
/// a_N ≈ b_N (= π/2K); with v = a_N u and x_N = cot v the recursion on the cotangent,
///   x_{n−1} = x_n c_n (with the dn of the level above), dn_{n−1} = (b_{n−1} + x)/(a_{n−1} + x),
/// gives sn = ±1/√(1 + c²), cn = c·sn, dn. Absolute error ~1e-16 on every m1 in [0, 1] and every
/// |u| ≤ K (tested against mpmath down to m1 = 1e-30); |u| < 1e-8 takes the Maclaurin terms
/// sn = u, cn = 1 − u²/2, dn = 1 − m u²/2 (next terms below 1e-16 relative); m1 = 0 gives the
/// separatrix's tanh u, sech u, sech u.
std::array<double, 3> jacobi_sn_cn_dn_complementary(double u, double m1);
/// The argument u ∈ (−2K, 2K] at which (sn, cn, dn)(u | 1 − m1) take the given values (which must
/// satisfy sn² + cn² = 1, dn² = cn² + m1 sn² to rounding, dn > 0): u = sn R_F(cn², dn², 1) for
/// cn ≥ 0 (DLMF 19.25.5 with sin φ = sn, cos φ = cn, Δ = dn), and ±2K − sn R_F(cn², dn², 1) for
/// cn < 0 (F(π − φ) = 2K − F(φ)). dn enters as given, not as √(1 − m sn²): next to the
/// separatrix both cn and dn are tiny and only their own values carry their digits. m1 = 0 with
/// cn = dn = 0 (the saddle itself) has no argument: std::invalid_argument.
double jacobi_argument(double sn, double cn, double dn, double m1);
/// W(m) = ⟨sn²⟩ over a period = (K − E)/(m K) = R_D(0, 1−m, 1) / (3 R_F(0, 1−m, 1)):
/// W(0) = ½, W(1) = 1, no 0/0 at m → 0.
double mean_sn_squared(double m);
/// complete_integrals (complete_elliptic.hpp: K and ⟨sn²⟩ by polynomial pieces) with its arguments
/// checked: m and m1 in [0, 1] with m + m1 = 1 to within 4 units of rounding, else
/// std::invalid_argument naming them.
CompleteIntegrals complete_integrals_checked(double m, double m1);
/// F(φ | m) = ∫_0^φ dϑ / √(1 − m sin²ϑ) for any real φ (F(φ + nπ) = F(φ) + 2nK), 0 ≤ m < 1.
double elliptic_F(double phi, double m);
/// Π(n | m) = ∫_0^{π/2} dϑ / ((1 − n sin²ϑ) √(1 − m sin²ϑ)) = R_F(0, 1−m, 1) + (n/3) R_J(0, 1−m, 1, 1−n),
/// n < 1, 0 ≤ m < 1 (Carlson's forms, DLMF 19.25.2).
double elliptic_Pi(double n, double m);
/// The incomplete integral of the third kind in Jacobi's form, ∫_0^u dv / (1 − n sn²(v | m)) =
/// Π(n; am u | m), for |u| ≤ K(m), given by sn, cn (≥ 0) and dn of u:
///   sn R_F(cn², dn², 1) + (n/3) sn³ R_J(cn², dn², 1, 1 − n sn²)      (DLMF 19.25.14),
/// n ≤ 0 here (the free rigid body's characteristic; no pole), 0 ≤ m ≤ 1. Passing cn² and dn²
/// directly (not cos² of the amplitude) keeps full relative accuracy next to the separatrix.
double elliptic_Pi_jacobi(double sn, double cn, double dn, double n, double m);

// ---------------------------------------------------------------------------------------------
// Carlson's symmetric integrals by duplication, templated on the scalar type (double or
// DoubleDouble): the same algorithm converges for any precision, with the tolerance r set to that
// type's rounding unit. B. C. Carlson, "Numerical computation of real or complex elliptic
// integrals", Numer. Algorithms 10 (1995) 13 (Algorithms 1–3; DLMF §19.36(i)). Used where a
// constant must be known beyond double precision (the free body's ν, K, Π multiply t:
// torque_free.cpp); the double-only paths above stay on GSL.
// ---------------------------------------------------------------------------------------------

/// The relative rounding unit the duplication stops at: ε of double, 2^-104 of DoubleDouble.
template <class Real>
constexpr double carlson_tolerance() {
    if constexpr (std::is_same_v<Real, DoubleDouble>)
        return DoubleDouble::epsilon;
    else
        return std::numeric_limits<Real>::epsilon();
}

/// R_F(x, y, z) = ½ ∫_0^∞ dt / √((t+x)(t+y)(t+z)), x, y, z ≥ 0, at most one zero (Algorithm 1):
/// A0 = (x+y+z)/3, Q = (3r)^(-1/6) max|A0 − x_i|; while 4^-n Q ≥ |A_n|: λ = √x√y + √x√z + √y√z,
/// x_i ← (x_i + λ)/4, A ← (A + λ)/4. Then X = (A0 − x)/(4^n A), Y likewise, Z = −X − Y,
/// E2 = XY − Z², E3 = XYZ and R_F = A^(-1/2) (1 − E2/10 + E3/14 + E2²/24 − 3 E2 E3/44) (error < r).
template <class Real>
Real carlson_RF(Real x, Real y, Real z) {
    using std::abs, std::sqrt;
    if (x < Real(0.0) || y < Real(0.0) || z < Real(0.0) || (x + y) == Real(0.0) || (x + z) == Real(0.0) ||
        (y + z) == Real(0.0))
        throw std::invalid_argument("carlson_RF: needs x, y, z >= 0 with at most one of them zero");
    const Real A0 = (x + y + z) / Real(3.0);
    Real A = A0;
    const double Q = std::pow(3.0 * carlson_tolerance<Real>(), -1.0 / 6.0) *
                     double(std::max({abs(A0 - x), abs(A0 - y), abs(A0 - z)}));
    double scale = 1.0;  // 4^-n
    const Real x0 = x, y0 = y;
    while (scale * Q >= double(abs(A))) {
        const Real sx = sqrt(x), sy = sqrt(y), sz = sqrt(z);
        const Real lambda = sx * sy + sx * sz + sy * sz;
        x = (x + lambda) * Real(0.25), y = (y + lambda) * Real(0.25), z = (z + lambda) * Real(0.25);
        A = (A + lambda) * Real(0.25);
        scale *= 0.25;
    }
    const Real X = (A0 - x0) * Real(scale) / A, Y = (A0 - y0) * Real(scale) / A, Z = -(X + Y);
    const Real E2 = X * Y - Z * Z, E3 = X * Y * Z;
    const Real series = Real(1.0) - E2 / Real(10.0) + E3 / Real(14.0) + E2 * E2 / Real(24.0) -
                        Real(3.0) * E2 * E3 / Real(44.0);
    return series / sqrt(A);
}

/// R_C(x, y) = ½ ∫_0^∞ dt / (√(t+x) (t+y)), x ≥ 0, y > 0 (Algorithm 2): A0 = (x + 2y)/3,
/// Q = (3r)^(-1/8) |A0 − x|; while 4^-n Q ≥ |A_n|: λ = 2√x√y + y, x, y, A ← (· + λ)/4. Then
/// s = (y0 − A0)/(4^n A), R_C = A^(-1/2) (1 + 3s²/10 + s³/7 + 3s⁴/8 + 9s⁵/22 + 159s⁶/208 + 9s⁷/8).
template <class Real>
Real carlson_RC(Real x, Real y) {
    using std::abs, std::sqrt;
    if (x < Real(0.0) || !(y > Real(0.0))) throw std::invalid_argument("carlson_RC: needs x >= 0, y > 0");
    const Real A0 = (x + y + y) / Real(3.0);
    Real A = A0;
    const double Q = std::pow(3.0 * carlson_tolerance<Real>(), -1.0 / 8.0) * double(abs(A0 - x));
    double scale = 1.0;
    const Real y0 = y;
    while (scale * Q >= double(abs(A))) {
        const Real lambda = Real(2.0) * sqrt(x) * sqrt(y) + y;
        x = (x + lambda) * Real(0.25), y = (y + lambda) * Real(0.25);
        A = (A + lambda) * Real(0.25);
        scale *= 0.25;
    }
    const Real s = (y0 - A0) * Real(scale) / A;
    const Real series =
        Real(1.0) +
        s * s * (Real(3.0) / Real(10.0) + s * (Real(1.0) / Real(7.0) +
                                  s * (Real(0.375) + s * (Real(9.0) / Real(22.0) +
                                                          s * (Real(159.0) / Real(208.0) + s * Real(1.125))))));
    return series / sqrt(A);
}

/// R_J(x, y, z, p) = (3/2) ∫_0^∞ dt / ((t+p) √((t+x)(t+y)(t+z))), x, y, z ≥ 0 (at most one zero),
/// p > 0 (Algorithm 3): A0 = (x+y+z+2p)/5, δ = (p−x)(p−y)(p−z), Q = (r/4)^(-1/6) max|A0 − x_i|;
/// while 4^-m Q ≥ |A_m|: λ as in R_F, d_m = (√p+√x)(√p+√y)(√p+√z), e_m = 4^-3m δ/d_m²,
/// Σ += 4^-m R_C(1, 1 + e_m)/d_m, x_i, p, A ← (· + λ)/4. Then X, Y, Z = (A0 − x_i)/(4^n A),
/// P = −(X+Y+Z)/2, E2 = XY + XZ + YZ − 3P², E3 = XYZ + 2 E2 P + 4P³, E4 = (2XYZ + E2 P + 3P³) P,
/// E5 = XYZ P², R_J = 4^-n A^(-3/2) (1 − 3E2/14 + E3/6 + 9E2²/88 − 3E4/22 − 9E2E3/52 + 3E5/26) + 6Σ.
template <class Real>
Real carlson_RJ(Real x, Real y, Real z, Real p) {
    using std::abs, std::sqrt;
    if (x < Real(0.0) || y < Real(0.0) || z < Real(0.0) || !(p > Real(0.0)) || (x + y) == Real(0.0) ||
        (x + z) == Real(0.0) || (y + z) == Real(0.0))
        throw std::invalid_argument("carlson_RJ: needs x, y, z >= 0 with at most one of them zero, and p > 0");
    const Real A0 = (x + y + z + p + p) / Real(5.0);
    Real A = A0;
    const Real delta = (p - x) * (p - y) * (p - z);
    const double Q = std::pow(0.25 * carlson_tolerance<Real>(), -1.0 / 6.0) *
                     double(std::max({abs(A0 - x), abs(A0 - y), abs(A0 - z), abs(A0 - p)}));
    double scale = 1.0;  // 4^-m
    const Real x0 = x, y0 = y, z0 = z;
    Real sum(0.0);
    while (scale * Q >= double(abs(A))) {
        const Real sx = sqrt(x), sy = sqrt(y), sz = sqrt(z), sp = sqrt(p);
        const Real lambda = sx * sy + sx * sz + sy * sz;
        const Real d = (sp + sx) * (sp + sy) * (sp + sz);
        const Real e = Real(scale * scale * scale) * delta / (d * d);
        sum += Real(scale) * carlson_RC(Real(1.0), Real(1.0) + e) / d;
        x = (x + lambda) * Real(0.25), y = (y + lambda) * Real(0.25), z = (z + lambda) * Real(0.25);
        p = (p + lambda) * Real(0.25);
        A = (A + lambda) * Real(0.25);
        scale *= 0.25;
    }
    const Real X = (A0 - x0) * Real(scale) / A, Y = (A0 - y0) * Real(scale) / A, Z = (A0 - z0) * Real(scale) / A;
    const Real P = -(X + Y + Z) * Real(0.5);
    const Real XYZ = X * Y * Z, P2 = P * P;
    const Real E2 = X * Y + X * Z + Y * Z - Real(3.0) * P2;
    const Real E3 = XYZ + Real(2.0) * E2 * P + Real(4.0) * P2 * P;
    const Real E4 = (Real(2.0) * XYZ + E2 * P + Real(3.0) * P2 * P) * P;
    const Real E5 = XYZ * P2;
    const Real series = Real(1.0) - Real(3.0) * E2 / Real(14.0) + E3 / Real(6.0) + Real(9.0) * E2 * E2 / Real(88.0) -
                        Real(3.0) * E4 / Real(22.0) - Real(9.0) * E2 * E3 / Real(52.0) + Real(3.0) * E5 / Real(26.0);
    return Real(scale) * series / (A * sqrt(A)) + Real(6.0) * sum;
}

}  // namespace gyrostat::model
