// Double-double arithmetic: a value hi + lo held in two doubles, |lo| ≤ ½ ulp(hi), about 106
// significant bits (relative rounding ≈ 2^-104 ≈ 4.9e-32), portable wherever double is IEEE
// binary64 with round-to-nearest (x86-64, aarch64, MSVC: unlike long double, which is double on
// the last two). Used for the constants of the closed forms that multiply t (torque_free.hpp), so
// that the phases ν t and Ω t keep ~1e-16 absolute accuracy up to t ≈ 1e15.
//
// Algorithms (Dekker 1971; Knuth TAOCP vol. 2 §4.2.2; Hida, Li & Bailey, "Library for double-double
// and quad-double arithmetic", 2001, the "sloppy-free" IEEE variants):
//   two_sum(a, b) = (s, e): s = fl(a + b), e = (a − (s − b')) + (b − b'), b' = s − a; s + e = a + b exactly.
//   two_prod(a, b) = (p, e): p = fl(a b), e = fma(a, b, −p); p + e = a b exactly.
// Sums and products of double-doubles are built from these (relative error ≤ ~4·2^-106); division
// by two Newton corrections of the double quotient; sqrt by one Newton (Karp) step from 1/√hi.
// NOT valid under -ffast-math or x87 excess precision (the error terms would be optimised away):
// the build uses neither (SSE2 on x86-64).
#pragma once

#include <cmath>
#include <limits>

namespace gyrostat::model {

struct DoubleDouble {
    double hi = 0.0, lo = 0.0;

    constexpr DoubleDouble() = default;
    constexpr DoubleDouble(double h) : hi(h), lo(0.0) {}  // NOLINT: implicit, as for a wider float
    constexpr DoubleDouble(double h, double l) : hi(h), lo(l) {}

    explicit operator double() const { return hi + lo; }

    /// The relative rounding unit, 2^-104 (Hida, Li & Bailey's dd_real::_eps).
    static constexpr double epsilon = 4.93038065763132e-32;
};

namespace dd_detail {
inline DoubleDouble two_sum(double a, double b) {
    const double s = a + b, bb = s - a;
    return {s, (a - (s - bb)) + (b - bb)};
}
inline DoubleDouble quick_two_sum(double a, double b) {  // |a| ≥ |b|
    const double s = a + b;
    return {s, b - (s - a)};
}
inline DoubleDouble two_prod(double a, double b) {
    const double p = a * b;
    return {p, std::fma(a, b, -p)};
}
}  // namespace dd_detail

/// a·b − p exactly, p = fl(a·b), without a fused multiply-add (Dekker's product: a and b split
/// into halves of 26 bits, whose products are exact), for code compiled for CPUs that may lack
/// FMA (there std::fma, as in two_prod, is a slow library call). T = double or an Eigen vector
/// (component-wise). |a|, |b| must stay below ~1e300 (the split multiplies by 2^27 + 1).
template <class T>
T dekker_product_error(const T& a, double b, const T& p) {
    constexpr double split = 134217729.0;  // 2^27 + 1
    const T a_big = split * a;
    const T a_high = a_big - (a_big - a);
    const T a_low = a - a_high;
    const double b_big = split * b;
    const double b_high = b_big - (b_big - b);
    const double b_low = b - b_high;
    return ((a_high * b_high - p) + a_high * b_low + a_low * b_high) + a_low * b_low;
}

/// a − b exactly (as a double-double): t − t0 without rounding.
inline DoubleDouble two_diff(double a, double b) { return dd_detail::two_sum(a, -b); }

inline DoubleDouble operator-(const DoubleDouble& a) { return {-a.hi, -a.lo}; }

inline DoubleDouble operator+(const DoubleDouble& a, const DoubleDouble& b) {
    DoubleDouble s = dd_detail::two_sum(a.hi, b.hi);
    const DoubleDouble t = dd_detail::two_sum(a.lo, b.lo);
    s.lo += t.hi;
    s = dd_detail::quick_two_sum(s.hi, s.lo);
    s.lo += t.lo;
    return dd_detail::quick_two_sum(s.hi, s.lo);
}
inline DoubleDouble operator-(const DoubleDouble& a, const DoubleDouble& b) { return a + (-b); }

inline DoubleDouble operator*(const DoubleDouble& a, const DoubleDouble& b) {
    DoubleDouble p = dd_detail::two_prod(a.hi, b.hi);
    p.lo += a.hi * b.lo + a.lo * b.hi;
    return dd_detail::quick_two_sum(p.hi, p.lo);
}

// q1 = a.hi/b.hi, then two corrections on the remainder r = a − q b.
inline DoubleDouble operator/(const DoubleDouble& a, const DoubleDouble& b) {
    const double q1 = a.hi / b.hi;
    DoubleDouble r = a - DoubleDouble(q1) * b;
    const double q2 = r.hi / b.hi;
    r = r - DoubleDouble(q2) * b;
    const double q3 = r.hi / b.hi;
    return DoubleDouble(dd_detail::quick_two_sum(q1, q2)) + DoubleDouble(q3);
}

inline DoubleDouble& operator+=(DoubleDouble& a, const DoubleDouble& b) { return a = a + b; }
inline DoubleDouble& operator-=(DoubleDouble& a, const DoubleDouble& b) { return a = a - b; }
inline DoubleDouble& operator*=(DoubleDouble& a, const DoubleDouble& b) { return a = a * b; }
inline DoubleDouble& operator/=(DoubleDouble& a, const DoubleDouble& b) { return a = a / b; }

inline bool operator<(const DoubleDouble& a, const DoubleDouble& b) { return a.hi < b.hi || (a.hi == b.hi && a.lo < b.lo); }
inline bool operator>(const DoubleDouble& a, const DoubleDouble& b) { return b < a; }
inline bool operator<=(const DoubleDouble& a, const DoubleDouble& b) { return !(b < a); }
inline bool operator>=(const DoubleDouble& a, const DoubleDouble& b) { return !(a < b); }
inline bool operator==(const DoubleDouble& a, const DoubleDouble& b) { return a.hi == b.hi && a.lo == b.lo; }
inline bool operator!=(const DoubleDouble& a, const DoubleDouble& b) { return !(a == b); }

inline DoubleDouble abs(const DoubleDouble& a) { return a.hi < 0.0 ? -a : a; }
inline bool isfinite(const DoubleDouble& a) { return std::isfinite(a.hi); }

// √a = x + (a − x²)/(2x) with x = fl(√hi) (Karp & Markstein): one Newton step doubles the digits.
inline DoubleDouble sqrt(const DoubleDouble& a) {
    if (a.hi <= 0.0) return DoubleDouble(a.hi == 0.0 ? 0.0 : std::numeric_limits<double>::quiet_NaN());
    const double inv = 1.0 / std::sqrt(a.hi);
    const double x = a.hi * inv;
    const DoubleDouble x2 = dd_detail::two_prod(x, x);
    return DoubleDouble(x) + DoubleDouble((a - x2).hi * (0.5 * inv));
}

/// The nearest integer (halves away from zero), exact.
inline DoubleDouble nearest_integer(const DoubleDouble& a) {
    const double h = std::round(a.hi);
    if (h == a.hi) return dd_detail::quick_two_sum(h, std::round(a.lo));  // hi already an integer
    if (std::abs(h - a.hi) == 0.5 && a.lo != 0.0) return DoubleDouble(a.lo > 0.0 ? std::ceil(a.hi) : std::floor(a.hi));
    return DoubleDouble(h);
}

/// 2π to 106 bits: 6.283185307179586476925286766559005768…
inline constexpr DoubleDouble two_pi_dd{6.283185307179586232e+00, 2.449293598294706414e-16};

/// x − n P with n = nearest integer of x/P, in double-double: the phase x reduced to [−P/2, P/2],
/// exact up to the rounding of P itself (relative 2^-104) times n. Returns (n, reduced).
struct Reduction {
    double n;
    DoubleDouble r;
};
inline Reduction reduce(const DoubleDouble& x, const DoubleDouble& period) {
    const DoubleDouble n = nearest_integer(x / period);
    return {n.hi + n.lo, x - n * period};
}

}  // namespace gyrostat::model
