// Compiled parts of paper 003's models: the nutation cubic and the unperturbed solution of the
// heavy symmetric top.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "gyrostat/model/lagrange_top.hpp"
#include "gyrostat/numeric/complete_elliptic.hpp"

namespace gyrostat::model {

void check_reachable(double A, double C, double mu, double Gz, double H, double r) {
    if (!(std::isfinite(Gz) && std::isfinite(H) && std::isfinite(r)))
        throw std::invalid_argument("LagrangeAveraged: (G_z, H, r) = (" + format_value(Gz) + ", " + format_value(H) +
                                    ", " + format_value(r) + ") is not finite");
    // The top reaches (G_z, H, r) only if f(u) = A(a − 2μu)(1 − u²) − (G_z − C r u)² ≥ 0 for some
    // u = cos θ in [−1, 1], a = 2H − C r² (f ≥ 0 is p² + q² ≥ 0 written in u). Its maximum on [−1, 1]
    // is at an end or where f'(u) = 6μA u² − 2(A a + C² r²) u + 2(C r G_z − μA) = 0.
    const double a = 2.0 * H - C * r * r;
    const auto f = [&](double u) {
        const double w = Gz - C * r * u;
        return A * (a - 2.0 * mu * u) * (1.0 - u * u) - w * w;
    };
    double best = std::max(f(-1.0), f(1.0));
    const double qa = 6.0 * mu * A, qb = -2.0 * (A * a + C * C * r * r), qc = 2.0 * (C * r * Gz - mu * A);
    const double disc = qb * qb - 4.0 * qa * qc;
    if (disc >= 0.0) {
        for (double sign : {-1.0, 1.0}) {
            const double u = (-qb + sign * std::sqrt(disc)) / (2.0 * qa);
            if (u > -1.0 && u < 1.0) best = std::max(best, f(u));
        }
    }
    const double scale = A * (std::abs(a) + 2.0 * mu) + (std::abs(Gz) + C * std::abs(r)) * (std::abs(Gz) + C * std::abs(r));
    if (best < -1e-12 * scale)
        throw std::invalid_argument("LagrangeAveraged: (G_z, H, r) = (" + format_value(Gz) + ", " + format_value(H) +
                                    ", " + format_value(r) + ") is not a state of the top: p^2 + q^2 would be negative "
                                    "for every cos(theta) in [-1, 1] (max of f(u) = " + format_value(best) +
                                    "); the energy H must be at least C r^2/2 - mu = " +
                                    format_value(0.5 * C * r * r - mu) + " and large enough for G_z");
}

Nutation nutation(double A, double C, double mu, double Gz, double H, double r) {
    if (!(std::isfinite(Gz) && std::isfinite(H) && std::isfinite(r)))
        throw std::invalid_argument("nutation: (G_z, H, r) = (" + format_value(Gz) + ", " + format_value(H) + ", " +
                                    format_value(r) + ") is not finite");
    // Vieta (paper (1.5)): the monic cubic u³ − s1 u² + s2 u − s3 = f(u)/(2μA).
    const double s1 = H / mu - C * r * r / (2.0 * mu) + C * C * r * r / (2.0 * A * mu);
    const double s2 = Gz * C * r / (A * mu) - 1.0;
    const double s3 = -H / mu + C * r * r / (2.0 * mu) + Gz * Gz / (2.0 * A * mu);
    // Factored form: f(1) = −(G_z − C r)² ≤ 0 exactly in floating point.
    const auto f = [&](double u) {
        const double w = Gz - C * r * u;
        return A * (2.0 * H - C * r * r - 2.0 * mu * u) * (1.0 - u * u) - w * w;
    };
    // f'(u) = −2A(μ(1 − u²) + u(2H − C r² − 2μu)) + 2 C r (G_z − C r u)
    const auto slope = [&](double u) {
        return -2.0 * A * (mu * (1.0 - u * u) + u * (2.0 * H - C * r * r - 2.0 * mu * u)) + 2.0 * C * r * (Gz - C * r * u);
    };
    // u3 = the last sign change on [1, hi]: f ≤ 0 on [1, u3] (u2 ≤ 1), f > 0 beyond (Cauchy bound hi).
    double lo = 1.0, hi = 2.0 + std::max({std::abs(s1), std::abs(s2), std::abs(s3)});
    double f_hi = f(hi);
    if (!(f_hi > 0.0))
        throw std::invalid_argument("nutation: the cubic has no root above 1 for (G_z, H, r) = (" + format_value(Gz) +
                                    ", " + format_value(H) + ", " + format_value(r) + ")");
    // Newton's iteration from hi: right of its largest root the cubic rises and is convex (u3 is
    // above the inflection s1/3, the roots' mean), so the iterates fall onto u3 from above, each
    // one a new hi (quadratically; linearly, halving, at the sleeping top's double root u2 = u3
    // = 1). Once a step is below 1e-8 of u3, the root lies within 8 ulps below (quadratic: the
    // next step is ~1e-16) or within twice the step (linear: steps shrinking by less than 0.3):
    // that point, where f ≤ 0, is lo; where f > 0, the next hi. A step that leaves (lo, hi) is a
    // bisection. Then regula falsi (Illinois: the end kept twice has its f halved; a point off
    // (lo, hi) a bisection) closes [lo, hi] onto adjacent doubles, as bisection alone did from
    // [1, hi]: the same root (mean 0.56 ulp from the root in 80-bit arithmetic over 2e5 random
    // tops, either way), in ~28 evaluations of f or f' against ~55, 2.7× faster.
    double previous_step = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 200; ++i) {
        const double d = slope(hi);
        double next = d > 0.0 ? hi - f_hi / d : lo;
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        if (next <= lo || next >= hi) break;
        const double f_next = f(next);
        if (f_next <= 0.0) {
            lo = next;
            break;
        }
        const double step = hi - next;
        hi = next, f_hi = f_next;
        if (step < 1e-8 * hi) {
            const double below = hi - ((step > 0.3 * previous_step ? 2.0 * step : 0.0) +
                                       8.0 * std::numeric_limits<double>::epsilon() * hi);
            if (below <= lo) break;
            const double f_below = f(below);
            if (f_below <= 0.0) {
                lo = below;
                break;
            }
            hi = below, f_hi = f_below;
        }
        previous_step = step;
    }
    double f_lo = f(lo);
    for (int i = 0, kept = 0; i < 200; ++i) {  // kept: −1 lo moved last, +1 hi
        const double mid = 0.5 * (lo + hi);
        if (mid <= lo || mid >= hi) break;
        double x = f_hi > f_lo ? lo - f_lo * (hi - lo) / (f_hi - f_lo) : mid;
        if (!(x > lo && x < hi)) x = mid;
        const double f_x = f(x);
        if (f_x <= 0.0) {
            lo = x, f_lo = f_x;
            if (kept == -1) f_hi *= 0.5;
            kept = -1;
        } else {
            hi = x, f_hi = f_x;
            if (kept == 1) f_lo *= 0.5;
            kept = 1;
        }
    }
    const double u3 = f(lo) == 0.0 ? lo : 0.5 * (lo + hi);
    // Deflation: u1 + u2 = s1 − u3, u1 u2 = s3/u3; the larger root from the formula, the other by division.
    const double B = s1 - u3, c = s3 / u3;
    const double sq = std::sqrt(std::max(B * B - 4.0 * c, 0.0));
    double a1, a2;
    if (B >= 0.0) {
        a2 = 0.5 * (B + sq);
        a1 = a2 != 0.0 ? c / a2 : 0.5 * (B - sq);
    } else {
        a1 = 0.5 * (B - sq);
        a2 = a1 != 0.0 ? c / a1 : 0.5 * (B + sq);
    }
    Nutation n;
    // Physical motions have −1 ≤ u1 ≤ u2 ≤ 1: clamp the rounding.
    n.u1 = std::clamp(std::min(a1, a2), -1.0, 1.0);
    n.u2 = std::clamp(std::max(a1, a2), -1.0, 1.0);
    n.u3 = u3;
    const double span = n.u3 - n.u1;
    n.m = span > 0.0 ? std::clamp((n.u2 - n.u1) / span, 0.0, 1.0) : 0.0;
    // m1 = 1 − m from the roots themselves, (u3 − u2)/(u3 − u1): its digits kept next to the
    // separatrix (u2 → u3), where K and ⟨sn²⟩ read m1 alone (complete_elliptic.hpp: K and ⟨sn²⟩ by
    // polynomial pieces, a few units of rounding, where three Carlson integrals took 3× as long)
    const double m1 = span > 0.0 ? std::clamp((n.u3 - n.u2) / span, 0.0, 1.0) : 1.0;
    n.alpha = std::sqrt(mu * span / (2.0 * A));
    if (n.m < 1.0 && m1 > 0.0) {
        const CompleteIntegrals integrals = complete_integrals(n.m, m1);
        n.v = n.u1 + (n.u2 - n.u1) * integrals.mean_sn_squared;
        n.period = n.alpha > 0.0 ? 2.0 * integrals.K / n.alpha : std::numeric_limits<double>::infinity();
    } else {  // the separatrix: ⟨sn²⟩ = 1, K = ∞
        n.v = n.u2;
        n.period = std::numeric_limits<double>::infinity();
    }
    return n;
}

namespace {
/// Z(m) = (1 − 2W(m))/m, W = (K − E)/(m K): its Taylor coefficients (exact rationals from the
/// series of K and E) below m = 0.05, where 13 terms leave < 1e-19; above, the quotient itself
/// (W to ~1e-16, so Z to ~3e-14).
double one_minus_twice_mean_over_m(double m) {
    static constexpr double z[13] = {-1.0 / 8, -1.0 / 16, -41.0 / 1024, -59.0 / 2048, -727.0 / 32768, -1171.0 / 65536,
                                     -498409.0 / 33554432, -848479.0 / 67108864, -11768921.0 / 1073741824,
                                     -20705249.0 / 2147483648, -2359256231.0 / 274877906944,
                                     -4242171053.0 / 549755813888, -61534748221.0 / 8796093022208};
    if (m >= 0.05) return (1.0 - 2.0 * mean_sn_squared(m)) / m;
    double sum = z[12];
    for (int k = 11; k >= 0; --k) sum = sum * m + z[k];
    return sum;
}
}  // namespace

NutationSlopes nutation_slopes(double A, double C, double mu, double Gz, double /*H: through the roots only*/, double r,
                               const Nutation& n) {
    const double u1 = n.u1, u2 = n.u2, u3 = n.u3, m = n.m, D = u3 - u1;
    const double W = mean_sn_squared(m), Z = one_minus_twice_mean_over_m(m);
    const double W_slope = (Z + W * W) / (2.0 * (1.0 - m));
    const double a = 0.5 * (1.0 + m * m * W_slope), w3 = -m * m * W_slope;
    const double apart = (Z - (2.0 - m) * W_slope) / (2.0 * D);  // ((w1 − w2)/m)/(2D)
    const double d31 = u3 - u1, d32 = u3 - u2, d13 = u1 - u3, d23 = u2 - u3;
    // ∂v/∂θ for g_θ(u) = c0 + c1 u + c2 u² + c3 u³ (the comment above nutation_slopes)
    auto slope = [&](double c0, double c1, double c2, double c3) {
        auto g = [&](double u) { return c0 + u * (c1 + u * (c2 + u * c3)); };
        const double t3 = g(u3) / (d31 * d32);  // (u3 = u2 only at the separatrix, where v's slope is infinite)
        const double second_difference = c2 + c3 * (u1 + u2 + u3);
        return a * (second_difference - t3) - apart * (g(u1) / d13 + g(u2) / d23) + w3 * t3;
    };
    NutationSlopes s;
    s.H = slope(-1.0 / mu, 0.0, 1.0 / mu, 0.0);
    s.Gz = slope(Gz / (mu * A), -C * r / (mu * A), 0.0, 0.0);
    s.r = slope(C * r / mu, -C * Gz / (mu * A), C * r * (C - A) / (mu * A), 0.0);
    s.mu = slope(0.0, 1.0 / mu, 0.0, -1.0 / mu);
    return s;
}

LagrangeUnperturbed::LagrangeUnperturbed(double A, double C, double mu, const Vec3& omega, const Vec3& gamma, double t0)
    : t0_(t0) {
    if (!(mu > 0.0)) throw std::invalid_argument("LagrangeUnperturbed: mu must be positive; got mu = " + format_value(mu));
    require_finite(omega, "LagrangeUnperturbed: omega");
    require_finite(gamma, "LagrangeUnperturbed: gamma");
    if (std::abs(gamma.norm() - 1.0) > 1e-9)
        throw std::invalid_argument("LagrangeUnperturbed: gamma must be a unit vector; |gamma| = " +
                                    format_value(gamma.norm()));
    const double p = omega.x(), q = omega.y();
    r_ = omega.z();
    Gz_ = A * (p * gamma.x() + q * gamma.y()) + C * r_ * gamma.z();
    H_ = 0.5 * (A * (p * p + q * q) + C * r_ * r_) + mu * gamma.z();
    n_ = model::nutation(A, C, mu, Gz_, H_, r_);
    const double width = n_.u2 - n_.u1;
    if (width > 0.0) {
        const double s = std::sqrt(std::clamp((gamma.z() - n_.u1) / width, 0.0, 1.0));
        double F;
        if (n_.m < 1.0) {
            F = elliptic_F(std::asin(s), n_.m);
        } else {
            F = std::atanh(std::min(s, 1.0 - 1e-16));  // F(φ | 1) = artanh(sin φ)
        }
        const double udot = gamma.x() * q - gamma.y() * p;  // γ̇3 = γ1 q − γ2 p
        beta_ = udot < 0.0 ? -F : F;
    }
}

double LagrangeUnperturbed::u(double t) const {
    if (n_.u2 == n_.u1) return n_.u1;
    const double sn = jacobi_sn_cn_dn(n_.alpha * (t - t0_) + beta_, n_.m)[0];
    return n_.u1 + (n_.u2 - n_.u1) * sn * sn;
}

}  // namespace gyrostat::model
