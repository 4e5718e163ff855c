// Elliptic integrals and Jacobi elliptic functions (GSL, every return code checked), shared by
// the closed forms of the torque-free body and of the Lagrange top.
#pragma once

#include <array>

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
/// (sn, cn, dn)(u | m), 0 ≤ m ≤ 1.
std::array<double, 3> jacobi_sn_cn_dn(double u, double m);
/// W(m) = ⟨sn²⟩ over a period = (K − E)/(m K) = R_D(0, 1−m, 1) / (3 R_F(0, 1−m, 1)):
/// W(0) = ½, W(1) = 1, no 0/0 at m → 0.
double mean_sn_squared(double m);
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

}  // namespace gyrostat::model
