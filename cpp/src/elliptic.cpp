// Elliptic functions through GSL, every return code checked (numeric/elliptic.hpp).
#include "gyrostat/numeric/elliptic.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_sf_ellint.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "gyrostat/body.hpp"

namespace gyrostat::model {

namespace {

// GSL's default handler aborts the process; errors are reported through return codes here.
struct GslHandlerOff {
    GslHandlerOff() { gsl_set_error_handler_off(); }
};
const GslHandlerOff gsl_handler_off;

constexpr double inf = std::numeric_limits<double>::infinity();

void require_parameter(double m, const char* what) {
    if (!(m >= 0.0 && m <= 1.0))
        throw std::invalid_argument(std::string(what) + ": the parameter m = k^2 must be in [0, 1]; got m = " +
                                    format_value(m));
}

double checked(int status, const gsl_sf_result& result, const char* what, double m) {
    if (status != GSL_SUCCESS)
        throw std::invalid_argument(std::string(what) + ": GSL failed (" + gsl_strerror(status) + ") at m = " +
                                    format_value(m));
    return result.val;
}

}  // namespace

// K and E through Carlson's forms with the argument 1 − m formed directly: GSL's Kcomp/Ecomp take
// the modulus k = √m and form 1 − k² inside, which loses log10(1/(1 − m)) digits near the
// separatrix (measured: 5e-9 relative at m = 1 − 1e-9). K = R_F(0, 1−m, 1),
// E = R_F(0, 1−m, 1) − (m/3) R_D(0, 1−m, 1).
double elliptic_K(double m) {
    require_parameter(m, "elliptic_K");
    if (m == 1.0) return inf;
    gsl_sf_result rf;
    return checked(gsl_sf_ellint_RF_e(0.0, 1.0 - m, 1.0, GSL_PREC_DOUBLE, &rf), rf, "elliptic_K (R_F)", m);
}

double elliptic_E(double m) {
    require_parameter(m, "elliptic_E");
    if (m == 1.0) return 1.0;
    if (m == 0.0) return 2.0 * std::atan(1.0);  // π/2
    gsl_sf_result rf, rd;
    const double f = checked(gsl_sf_ellint_RF_e(0.0, 1.0 - m, 1.0, GSL_PREC_DOUBLE, &rf), rf, "elliptic_E (R_F)", m);
    const double d = checked(gsl_sf_ellint_RD_e(0.0, 1.0 - m, 1.0, GSL_PREC_DOUBLE, &rd), rd, "elliptic_E (R_D)", m);
    return f - m * d / 3.0;
}

std::array<double, 3> jacobi_sn_cn_dn(double u, double m) {
    require_parameter(m, "jacobi_sn_cn_dn");
    return jacobi_sn_cn_dn_complementary(u, 1.0 - m);
}

// Bulirsch's descending Gauss transformation with the complementary parameter (the derivation is
// in elliptic.hpp). The AGM of (1, √m1) converges quadratically once b/a is near 1 and needs about
// log2 ln(16/m1) steps before that: 12 levels reach m1 = 1e-300; 40 are kept.
std::array<double, 3> jacobi_sn_cn_dn_complementary(double u, double m1) {
    if (!(m1 >= 0.0 && m1 <= 1.0))
        throw std::invalid_argument("jacobi_sn_cn_dn: the complementary parameter m1 = 1 - m must be in [0, 1]; got m1 = " +
                                    format_value(m1));
    if (!std::isfinite(u)) throw std::invalid_argument("jacobi_sn_cn_dn: argument u = " + format_value(u) + " is not finite");
    const double m = 1.0 - m1;
    if (std::abs(u) < 1e-8) return {u, 1.0 - 0.5 * u * u, 1.0 - 0.5 * m * u * u};
    if (m1 == 0.0) {  // the separatrix: sn = tanh u, cn = dn = sech u
        const double sech = 1.0 / std::cosh(u);
        return {std::tanh(u), sech, sech};
    }
    constexpr int levels = 40;
    double a_level[levels], b_level[levels];
    double a = 1.0, b = std::sqrt(m1), mean = 1.0;
    int n = 0;
    for (;;) {
        a_level[n] = a, b_level[n] = b;
        mean = 0.5 * (a + b);
        if (std::abs(a - b) <= 1e-9 * a || n + 1 == levels) break;  // quadratic: the next mean is exact to rounding
        b = std::sqrt(a * b);
        a = mean;
        ++n;
    }
    const double v = mean * u;
    const double s = std::sin(v);
    double dn = 1.0;
    double x = std::cos(v) / s;  // cot v, then the ratio carried down the levels
    double c = mean * x;
    for (int level = n; level >= 0; --level) {
        x *= c;
        c *= dn;
        dn = (b_level[level] + x) / (a_level[level] + x);
        x = c / a_level[level];
    }
    const double sn = std::copysign(1.0 / std::sqrt(c * c + 1.0), s);
    return {sn, c * sn, dn};
}

double jacobi_argument(double sn, double cn, double dn, double m1) {
    if (!(m1 >= 0.0 && m1 <= 1.0))
        throw std::invalid_argument("jacobi_argument: the complementary parameter m1 = 1 - m must be in [0, 1]; got m1 = " +
                                    format_value(m1));
    if (!std::isfinite(sn) || !std::isfinite(cn) || !(dn > 0.0) || !std::isfinite(dn))
        throw std::invalid_argument("jacobi_argument: needs finite sn, cn and dn > 0; got sn = " + format_value(sn) +
                                    ", cn = " + format_value(cn) + ", dn = " + format_value(dn));
    if (sn == 0.0) return cn >= 0.0 ? 0.0 : 2.0 * elliptic_K(1.0 - m1);
    gsl_sf_result rf;
    const double x = cn * cn, y = dn * dn;
    const double F = sn * checked(gsl_sf_ellint_RF_e(x, y, 1.0, GSL_PREC_DOUBLE, &rf), rf, "jacobi_argument (R_F)", 1.0 - m1);
    if (cn >= 0.0) return F;
    gsl_sf_result rk;
    const double K = checked(gsl_sf_ellint_RF_e(0.0, m1, 1.0, GSL_PREC_DOUBLE, &rk), rk, "jacobi_argument (K)", 1.0 - m1);
    return std::copysign(2.0 * K, sn) - F;
}

CompleteIntegrals complete_integrals_checked(double m, double m1) {
    if (!(m >= 0.0 && m <= 1.0 && m1 >= 0.0 && m1 <= 1.0) ||
        std::abs(m + m1 - 1.0) > 4.0 * std::numeric_limits<double>::epsilon())
        throw std::invalid_argument("complete_integrals: needs m = k^2 and m1 = 1 - m in [0, 1] with m + m1 = 1; got m = " +
                                    format_value(m) + ", m1 = " + format_value(m1));
    return complete_integrals(m, m1);
}

double mean_sn_squared(double m) {
    require_parameter(m, "mean_sn_squared");
    if (m == 1.0) return 1.0;
    if (m == 0.0) return 0.5;
    gsl_sf_result rd, rf;
    const double y = 1.0 - m;
    const double d = checked(gsl_sf_ellint_RD_e(0.0, y, 1.0, GSL_PREC_DOUBLE, &rd), rd, "mean_sn_squared (R_D)", m);
    const double f = checked(gsl_sf_ellint_RF_e(0.0, y, 1.0, GSL_PREC_DOUBLE, &rf), rf, "mean_sn_squared (R_F)", m);
    return d / (3.0 * f);
}

double elliptic_F(double phi, double m) {
    require_parameter(m, "elliptic_F");
    if (!std::isfinite(phi)) throw std::invalid_argument("elliptic_F: amplitude phi = " + format_value(phi) + " is not finite");
    // F(φ + nπ | m) = F(φ | m) + 2n K(m), with the reduced amplitude in [−π/2, π/2]
    const double n = std::round(phi / M_PI);
    gsl_sf_result f;
    double value = checked(gsl_sf_ellint_F_e(phi - n * M_PI, std::sqrt(m), GSL_PREC_DOUBLE, &f), f, "elliptic_F", m);
    if (n != 0.0) value += 2.0 * n * elliptic_K(m);
    return value;
}

double elliptic_Pi(double n, double m) {
    require_parameter(m, "elliptic_Pi");
    if (!(n < 1.0)) throw std::invalid_argument("elliptic_Pi: the characteristic n = " + format_value(n) + " must be below 1");
    if (m == 1.0) return inf;
    gsl_sf_result rf, rj;
    const double y = 1.0 - m;
    const double f = checked(gsl_sf_ellint_RF_e(0.0, y, 1.0, GSL_PREC_DOUBLE, &rf), rf, "elliptic_Pi (R_F)", m);
    if (n == 0.0) return f;
    const double j = checked(gsl_sf_ellint_RJ_e(0.0, y, 1.0, 1.0 - n, GSL_PREC_DOUBLE, &rj), rj, "elliptic_Pi (R_J)", m);
    return f + n * j / 3.0;
}

double elliptic_Pi_jacobi(double sn, double cn, double dn, double n, double m) {
    require_parameter(m, "elliptic_Pi_jacobi");
    if (!(n <= 0.0)) throw std::invalid_argument("elliptic_Pi_jacobi: the characteristic n = " + format_value(n) + " must be <= 0");
    if (!(cn >= 0.0) || !std::isfinite(sn) || !std::isfinite(dn))
        throw std::invalid_argument("elliptic_Pi_jacobi: needs |u| <= K (cn >= 0); got sn = " + format_value(sn) +
                                    ", cn = " + format_value(cn));
    if (sn == 0.0) return 0.0;
    gsl_sf_result rf, rj;
    const double x = cn * cn, y = dn * dn;
    const double f = checked(gsl_sf_ellint_RF_e(x, y, 1.0, GSL_PREC_DOUBLE, &rf), rf, "elliptic_Pi_jacobi (R_F)", m);
    if (n == 0.0) return sn * f;
    const double s3 = sn * sn * sn;
    const double j = checked(gsl_sf_ellint_RJ_e(x, y, 1.0, 1.0 - n * sn * sn, GSL_PREC_DOUBLE, &rj), rj,
                             "elliptic_Pi_jacobi (R_J)", m);
    return sn * f + n * s3 * j / 3.0;
}

}  // namespace gyrostat::model
