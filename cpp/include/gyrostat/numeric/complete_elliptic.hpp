// K(m) and ⟨sn²⟩ = (K − E)/(m K) by polynomial pieces: what the triaxial averaged model's
// right-hand side needs at every call (euler_poinsot.hpp), without the AGM's chain of dependent
// square roots.
#pragma once

#include <cmath>

#include "gyrostat/numeric/complete_elliptic_table.hpp"

namespace gyrostat::model {

/// K(m) and S(m) = (K(m) − E(m))/(m K(m)) = ⟨sn²(·|m)⟩ (S(0) = ½, S(1) = 1).
struct CompleteIntegrals {
    double K;
    double mean_sn_squared;
};

namespace complete_elliptic_detail {
/// The polynomial piece of `table` at x ∈ [0, ½] (complete_elliptic_table.hpp) by Estrin's scheme,
/// Σ c_k t^k = ((c0 + c1 t) + (c2 + c3 t) t²) + ((c4 + c5 t) + (c6 + c7 t) t²) t⁴ + ((c8 + c9 t) + c10 t²) t⁸:
/// four dependent multiply-adds where Horner's rule takes ten (the right-hand side waits on them).
inline double piece(const double (&table)[complete_elliptic_table::intervals][complete_elliptic_table::degree + 1],
                    int i, double t) {
    static_assert(complete_elliptic_table::degree == 10, "Estrin's scheme below is written for degree 10");
    const double* c = table[i];
    const double t2 = t * t, t4 = t2 * t2, t8 = t4 * t4;
    const double low = (c[0] + c[1] * t) + (c[2] + c[3] * t) * t2;
    const double middle = (c[4] + c[5] * t) + (c[6] + c[7] * t) * t2;
    const double high = (c[8] + c[9] * t) + c[10] * t2;
    return (low + middle * t4) + high * t8;
}
}  // namespace complete_elliptic_detail

/// K and S at the parameter m = k², given with its complement m1 = 1 − m (each computed so that it
/// keeps its digits: m1 next to the separatrix, tools/make_complete_elliptic_table.py):
///
///   m ≤ ½:  K = P_K(m),  S = P_S(m);
///   m > ½:  with x = m1, K' = P_K(x), E' = K'(1 − x P_S(x)) (= E(x)), L = ln(16/x),
///           K = K' L/π + P_B(x),   K − E = E' L/π + P_F(x),   S = (K − E)/(m K)
///
/// (DLMF 19.12.1–2: the logarithmic terms of K and E next to m = 1 have the coefficients K(x)/π and
/// (K(x) − E(x))/π, B and F are what remains), P_* the polynomial pieces of the table (degree 10 on
/// eight pieces of [0, ½], Estrin's scheme). m ≤ ½ reads m only; m > ½ reads m1 only, so m1 down to the smallest
/// subnormal keeps its digits in L. Relative error a few units of rounding (tested against mpmath
/// in tests/test_complete_elliptic.py). 0 ≤ m, m1 ≤ 1 is the caller's (EulerPoinsot clamps both).
inline CompleteIntegrals complete_integrals(double m, double m1) {
    namespace table = complete_elliptic_table;
    using complete_elliptic_detail::piece;
    constexpr double pieces_per_unit = 2.0 * table::intervals, per_half_width = 4.0 * table::intervals;
    const bool near_one = m > 0.5;
    const double x = near_one ? m1 : m;
    const double scaled = x * pieces_per_unit;  // the piece; a NaN (no cast of it) gives NaN through piece 0
    const int i = scaled < table::intervals ? (scaled >= 0.0 ? static_cast<int>(scaled) : 0) : table::intervals - 1;
    const double t = (x - (i + 0.5) / pieces_per_unit) * per_half_width;
    const double K = piece(table::K, i, t), S = piece(table::S, i, t);
    if (!near_one) return {K, S};
    const double L = 4.0 * M_LN2 - std::log(x);  // ln(16/x) without overflow at subnormal x
    const double E = K * (1.0 - x * S);          // E(x): E = K(1 − x S)
    const double K_near_one = K * L * M_1_PI + piece(table::B, i, t);
    const double K_minus_E = E * L * M_1_PI + piece(table::F, i, t);
    return {K_near_one, K_minus_E / (m * K_near_one)};
}

}  // namespace gyrostat::model
