// The torque-free motion of a triaxial rigid body on one level set of (|G|, T): the generating
// motion of the triaxial averaged model (model/averaged_triaxial.hpp) and the motion a torque's
// averaged power is taken over (torque/set.hpp: TorqueSet::averaged_power).
#pragma once

#include <algorithm>
#include <utility>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "gyrostat/body.hpp"
#include "gyrostat/numeric/complete_elliptic.hpp"
#include "gyrostat/numeric/elliptic.hpp"

namespace gyrostat {

/// Euler's equations J ω̇ = Jω × ω without torque keep G² = Σ A_i² ω_i² and 2T = Σ A_i ω_i²
/// (derivation and checks: docs/papers/triaxial_averaging.md §1, tests/triaxial_reference.py).
/// Name the axes by the middle moment A_b and the separatrix distance
///
///   p_b = G² − 2T A_b = Σ A_i (A_i − A_b) ω_i²    (a sum of components: no cancellation),
///
/// a = the axis the body circulates about (ω_a never changes sign): the axis of the largest
/// moment when p_b > 0, of the smallest when p_b < 0; c = the other extreme axis. With
/// p_a = G² − 2T A_c and p_c = 2T A_a − G² (both of the sign of A_a − A_c) and u = 2Kφ/π:
///
///   ω_a = s α_a dn(u, k),   ω_b = −σ s α_b sn(u, k),   ω_c = α_c cn(u, k),
///   α_a² = p_a/(A_a(A_a − A_c)),  α_b² = p_c/(A_b(A_a − A_b)),  α_c² = p_c/(A_c(A_a − A_c)),
///   λ² = (A_a − A_b) p_a/(A_a A_b A_c),
///   k² = (A_b − A_c) p_c/((A_a − A_b) p_a),   k'² = 1 − k² = (A_a − A_c) p_b/((A_a − A_b) p_a),
///   φ̇ = π λ / (2K(k)),   the period of ω: P = 4K/λ,
///
/// s = ±1 the branch (the sign of ω_a), σ = ε_abc sign(A_a − A_c) (ε_abc = +1 when (a, b, c) is a
/// cyclic permutation of (0, 1, 2)). k'² comes from p_b, so K and the Jacobi functions keep every
/// digit next to the separatrix (K = R_F(0, k'², 1), elliptic.hpp). φ = 0 is where ω_b = 0 and ω_c = α_c.
/// A symmetric body is the limit k² = 0 (A_b = A_c): ω_b, ω_c turn on a circle, ω_a is constant.
class EulerPoinsot {
public:
    /// The axes ordered by their moments: (smallest, middle, largest); of two equal moments the
    /// one with the lower index comes first.
    static std::array<int, 3> sorted_axes(const Vec3& J) {
        std::array<int, 3> order{0, 1, 2};  // an insertion sort of three (stable_sort would allocate)
        for (int i = 1; i < 3; ++i)
            for (int j = i; j > 0 && J[order[j]] < J[order[j - 1]]; --j) std::swap(order[j], order[j - 1]);
        return order;
    }
    /// p_b = Σ A_i (A_i − A_b) ω_i² of a body rate ω (A_b the middle moment).
    static double separatrix_distance(const Vec3& J, const Vec3& omega) {
        const double Ab = J[sorted_axes(J)[1]];
        double pb = 0.0;
        for (int i = 0; i < 3; ++i) pb += J[i] * (J[i] - Ab) * omega[i] * omega[i];
        return pb;
    }

    /// The motion with |G|² = G2 and p_b = pb on the branch s = sign(branch). Throws
    /// std::invalid_argument naming the values for a level set no body with moments J has: G2 ≤ 0,
    /// p_b = 0 (the separatrix: the period is infinite), |G|² and p_b out of the range the moments
    /// allow (T out of [G²/(2A_max), G²/(2A_min)]), a permanent rotation about one of two equal
    /// moments. With `on_the_way`, a state a run reached (the right-hand side, its outputs) whose
    /// T lies past the permanent rotation about a (p_c < 0: a damped motion approaching it, pushed
    /// over by the integrator's own error) is taken as that rotation instead of refused.
    EulerPoinsot(const Vec3& J, double G2, double pb, double branch, bool on_the_way = false)
        : branch_(branch >= 0.0 ? 1.0 : -1.0) {
        if (!(G2 > 0.0) || !std::isfinite(G2) || !std::isfinite(pb))
            throw std::invalid_argument("EulerPoinsot: needs |G|^2 > 0 and a finite p_b; got |G|^2 = " +
                                        format_value(G2) + ", p_b = " + format_value(pb));
        if (pb == 0.0)
            throw std::invalid_argument("EulerPoinsot: p_b = G^2 - 2 T A_mid = 0 is the separatrix (|G|^2 = " +
                                        format_value(G2) + "): its period is infinite, there is no motion to average over");
        const std::array<int, 3> order = sorted_axes(J);
        b_ = order[1];
        a_ = pb > 0.0 ? order[2] : order[0];
        c_ = pb > 0.0 ? order[0] : order[2];
        const double Aa = J[a_], Ab = J[b_], Ac = J[c_];
        if (Aa == Ab)
            throw std::invalid_argument("EulerPoinsot: p_b = " + format_value(pb) + " asks for a rotation about the axis of a moment equal to the middle one (" +
                                        format_value(Aa) + "): a permanent rotation, no circulation to average over");
        // A_b p_a and A_b p_c: k² and k'² below take one division from (|G|², p_b), not two (the
        // right-hand side waits on them)
        const double pa_scaled = G2 * (Ab - Ac) + pb * Ac;  // both terms of the sign of A_a − A_c
        double pc_scaled = G2 * (Aa - Ab) - pb * Aa;
        // p_c / (A_a − A_c) ≥ 0 is T ≤ G²/(2A_min) (or ≥ G²/(2A_max)); a rounding below 0 at the
        // permanent rotation about a (p_c = 0) is that rotation
        if (pc_scaled * (Aa - Ac) < 0.0) {
            if (!on_the_way && std::abs(pc_scaled) > 1e-12 * G2 * std::abs(Aa - Ac))
                throw std::invalid_argument("EulerPoinsot: |G|^2 = " + format_value(G2) + " and p_b = " + format_value(pb) +
                                            " give a kinetic energy T = " + format_value(0.5 * (G2 - pb) / Ab) +
                                            " outside [G^2/(2 A_max), G^2/(2 A_min)]: no motion of this body has them");
            pc_scaled = 0.0;
        }
        const double pa = pa_scaled / Ab, pc = pc_scaled / Ab;
        if (!(pa * (Aa - Ac) > 0.0))
            throw std::invalid_argument("EulerPoinsot: |G|^2 = " + format_value(G2) + " and p_b = " + format_value(pb) +
                                        " are not a level set of this body (p_a = " + format_value(pa) + ")");
        alpha_a_ = std::sqrt(pa / (Aa * (Aa - Ac)));
        alpha_b_ = std::sqrt(pc / (Ab * (Aa - Ab)));
        alpha_c_ = std::sqrt(pc / (Ac * (Aa - Ac)));
        lambda_ = std::sqrt((Aa - Ab) * pa / (Aa * Ab * Ac));
        m_ = std::clamp((Ab - Ac) * pc_scaled / ((Aa - Ab) * pa_scaled), 0.0, 1.0);
        m1_ = std::clamp((Aa - Ac) * Ab * pb / ((Aa - Ab) * pa_scaled), 0.0, 1.0);
        if (m1_ == 0.0)
            throw std::invalid_argument("EulerPoinsot: p_b = " + format_value(pb) + " is within rounding of the separatrix "
                                        "(k'^2 underflows): its period is infinite");
        complete_integrals();
        const bool cyclic = (b_ == (a_ + 1) % 3);
        sigma_ = (cyclic ? 1.0 : -1.0) * (Aa > Ac ? 1.0 : -1.0);
    }

    int a() const { return a_; }  ///< the axis circulated about
    int b() const { return b_; }  ///< the middle axis
    int c() const { return c_; }  ///< the other extreme axis
    double branch() const { return branch_; }
    double m() const { return m_; }    ///< k²
    double m1() const { return m1_; }  ///< k'² = 1 − k², from p_b
    double K() const { return K_; }
    double lambda() const { return lambda_; }
    std::array<double, 3> amplitudes() const { return {alpha_a_, alpha_b_, alpha_c_}; }  ///< (α_a, α_b, α_c)
    /// φ̇ = πλ/(2K), rad/s.
    double phase_rate() const { return 0.5 * M_PI * lambda_ / K_; }
    /// P = 4K/λ, the period of ω(t).
    double period() const { return 4.0 * K_ / lambda_; }

    /// ω at the phase φ (any real φ; u = 2Kφ/π reduced to |r| ≤ K by the quarter periods:
    /// sn(K + x) = sn(K − x), cn(K + x) = −cn(K − x), sn, cn change sign over 2K, dn does not).
    Vec3 omega(double phase) const {
        double x = std::fmod(phase, 2.0 * M_PI);
        if (x < 0.0) x += 2.0 * M_PI;
        x *= 2.0 / M_PI;  // in [0, 4): quarter periods
        const int quarter = std::min(3, static_cast<int>(x));
        const double f = x - quarter;
        const bool mirrored = quarter == 1 || quarter == 3;
        const auto [sn0, cn0, dn] = model::jacobi_sn_cn_dn_complementary(K_ * (mirrored ? 1.0 - f : f), m1_);
        const double sn = quarter >= 2 ? -sn0 : sn0;
        const double cn = (quarter == 1 || quarter == 2) ? -cn0 : cn0;
        return omega_of(sn, cn, dn);
    }

    /// Calls visit(ω) at the n phases 2πj/n, j = 0 … n − 1 (n a multiple of 4, as nodes() gives),
    /// in some order: the nodes of the trapezoidal rule over one period. sn, cn, dn are computed
    /// on the first quarter only (u_j = 4Kj/n ≤ K); the phases π − φ, π + φ and 2π − φ have the
    /// same u with the signs of sn and cn changed (the quarter periods of omega()): a quarter of
    /// the elliptic evaluations.
    template <class Visit>
    void for_each_node(int n, Visit&& visit) const {
        const int quarter = n / 4;
        for (int j = 0; j <= quarter; ++j) {
            const auto [sn, cn, dn] = model::jacobi_sn_cn_dn_complementary(K_ * (4.0 * j / n), m1_);
            visit(omega_of(sn, cn, dn));                // φ_j
            visit(omega_of(-sn, -cn, dn));              // π + φ_j
            if (j == 0 || j == quarter) continue;       // π − φ_j and 2π − φ_j: the two above
            visit(omega_of(sn, -cn, dn));               // π − φ_j
            visit(omega_of(-sn, cn, dn));               // 2π − φ_j
        }
    }

    /// The phase φ ∈ [0, 2π) at which omega(φ) = ω, for ω on this motion (sn, cn, dn read off its
    /// components, the argument by elliptic.hpp's jacobi_argument); 0 at a permanent rotation.
    double phase_of(const Vec3& w) const {
        if (alpha_b_ == 0.0 || alpha_c_ == 0.0) return 0.0;
        const double sn = std::clamp(-w[b_] / (sigma_ * branch_ * alpha_b_), -1.0, 1.0);
        const double cn = std::clamp(w[c_] / alpha_c_, -1.0, 1.0);
        const double dn = std::max(std::abs(w[a_]) / alpha_a_, 1e-300);
        double phase = 0.5 * M_PI * model::jacobi_argument(sn, cn, dn, m1_) / K_;
        return phase < 0.0 ? phase + 2.0 * M_PI : phase;
    }

    /// ⟨ω⟩ over a period: s α_a π/(2K) along a (⟨dn⟩ = π/(2K), ⟨sn⟩ = ⟨cn⟩ = 0).
    Vec3 mean_omega() const {
        Vec3 mean = Vec3::Zero();
        mean[a_] = branch_ * alpha_a_ * 0.5 * M_PI / K_;
        return mean;
    }
    /// ⟨ω_i²⟩: ω_i² = c0_i + c1_i sn² (dn² = 1 − k² sn², cn² = 1 − sn²) and ⟨sn²⟩ = S1 =
    /// (K − E)/(k²K) (complete_integrals below, with K):  ⟨ω_a²⟩ = α_a²(1 − k² S1), ⟨ω_b²⟩ = α_b² S1, ⟨ω_c²⟩ = α_c²(1 − S1).
    Vec3 mean_square() const {
        const double S1 = S1_;
        Vec3 mean;
        mean[a_] = alpha_a_ * alpha_a_ * (1.0 - m_ * S1);
        mean[b_] = alpha_b_ * alpha_b_ * S1;
        mean[c_] = alpha_c_ * alpha_c_ * (1.0 - S1);
        return mean;
    }
    /// ⟨ω_i² ω_j²⟩ = c0_i c0_j + (c0_i c1_j + c1_i c0_j) S1 + c1_i c1_j S2, S2 = ⟨sn⁴⟩: from the
    /// recursion 3k² S2 = 2(1 + k²) S1 − 1 for k² ≥ 0.1, by its Maclaurin series below (the recursion
    /// loses ~ε/k² there).
    Mat3 mean_square_products() const {
        const double S1 = S1_;
        const double S2 = m_ >= 0.1 ? (2.0 * (1.0 + m_) * S1 - 1.0) / (3.0 * m_) : mean_sn_fourth_series(m_);
        Vec3 c0, c1;
        c0[a_] = alpha_a_ * alpha_a_, c1[a_] = -m_ * alpha_a_ * alpha_a_;
        c0[b_] = 0.0, c1[b_] = alpha_b_ * alpha_b_;
        c0[c_] = alpha_c_ * alpha_c_, c1[c_] = -alpha_c_ * alpha_c_;
        Mat3 mean;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) mean(i, j) = c0[i] * c0[j] + (c0[i] * c1[j] + c1[i] * c0[j]) * S1 + c1[i] * c1[j] * S2;
        return mean;
    }

    /// ⟨sn⁴⟩ = Σ s_n k^{2n} for k² < 0.1: the coefficients follow exactly (rational) from the series of
    /// K and E (DLMF 19.5.1, 19.5.2) through S1 = (K − E)/(k²K) and 3k² S2 = 2(1 + k²) S1 − 1:
    /// 3/8, 1/16, 35/1024, 47/2048, …; 20 terms leave < 1e-20 at k² = 0.1 (tested against mpmath).
    static double mean_sn_fourth_series(double m) {
        static constexpr double s[20] = {0.375, 0.0625, 0.0341796875, 0.02294921875, 0.016998291015625,
                                         0.0133514404296875, 0.010907262563705444, 0.0091656893491745,
                                         0.007867994718253613, 0.006867431569844484, 0.006074852357414784,
                                         0.005433129454104346, 0.0049040517095590985, 0.004461145476909678,
                                         0.00408552119089349, 0.003763359353690675, 0.0034843297274727704,
                                         0.0032405643745905743, 0.00302597138699181, 0.0028357648061917554};
        double sum = s[19];
        for (int n = 18; n >= 0; --n) sum = sum * m + s[n];
        return sum;
    }

    /// Nodes of the trapezoidal rule in the phase for a relative error ~tolerance on an average of
    /// a function analytic in ω: the integrand is analytic in the strip |Im u| < K' (the poles of
    /// sn, cn, dn), so n nodes err by ~exp(−πK'n/(2K)); n = 4⌈K ln(10³/tolerance)/(2πK')⌉ (10³: the
    /// margin measured for the double poles of ω², docs/papers/triaxial_averaging.md §2(d)), at
    /// least 8, at most 4096; a multiple of 4, for for_each_node's quarters. ~20 nodes at k² = 0.5
    /// and 1e-13, ~100 at k'² = 1e-6.
    int nodes(double tolerance) const {
        if (m_ == 0.0) return 8;  // K' = K(k') = R_F(0, k², 1) = ∞: the integrand is a trigonometric polynomial
        const double K_prime = model::carlson_RF(0.0, m_, 1.0);
        const double n = 4.0 * std::ceil(K_ * std::log(1e3 / tolerance) / (2.0 * M_PI * K_prime));
        return static_cast<int>(std::clamp(n, 8.0, 4096.0));
    }

private:
    /// ω from sn, cn, dn of the motion's argument (the amplitudes, the branch and the axes' order).
    Vec3 omega_of(double sn, double cn, double dn) const {
        Vec3 w;
        w[a_] = branch_ * alpha_a_ * dn;
        w[b_] = -sigma_ * branch_ * alpha_b_ * sn;
        w[c_] = alpha_c_ * cn;
        return w;
    }

    /// K and S1 = ⟨sn²⟩ = (K − E)/(k²K) from the polynomial pieces of numeric/complete_elliptic.hpp:
    /// k² itself up to ½, k'² (from p_b) beyond, so that both keep every digit at k² → 0 and next to
    /// the separatrix. No serial square roots (the AGM took ~log2 ln(4/k') + 4 of them, the rate's
    /// whole elliptic cost: bench/README.md).
    void complete_integrals() {
        const model::CompleteIntegrals integrals = model::complete_integrals(m_, m1_);
        K_ = integrals.K;
        S1_ = integrals.mean_sn_squared;
    }

    double branch_ = 1.0;
    int a_ = 2, b_ = 1, c_ = 0;
    double sigma_ = 1.0, alpha_a_ = 0.0, alpha_b_ = 0.0, alpha_c_ = 0.0, lambda_ = 0.0, m_ = 0.0, m1_ = 1.0, K_ = 0.0;
    double S1_ = 0.5;  ///< ⟨sn²⟩ = R_D(0, k'², 1)/(3 R_F(0, k'², 1)): no cancellation at k² → 0, → 1 at the separatrix
};

}  // namespace gyrostat
