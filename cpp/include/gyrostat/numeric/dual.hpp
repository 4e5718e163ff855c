// Forward-mode derivatives: a number with its gradient, for the exact Jacobian of a right-hand
// side written once as a template over its scalar (no difference quotient, no step to choose).
#pragma once

#include <array>

namespace gyrostat::model {

/// v + Σ d_k ε_k with ε_k ε_l = 0: arithmetic on it carries ∂v/∂y_k along, exactly.
template <int N>
struct Dual {
    double v = 0.0;
    std::array<double, N> d{};

    Dual() = default;
    Dual(double value) : v(value) {}  // NOLINT: a constant has no derivative
    /// The k-th independent variable y_k = value.
    static Dual variable(double value, int k) {
        Dual x(value);
        x.d[k] = 1.0;
        return x;
    }
};

template <int N>
Dual<N> operator+(const Dual<N>& a, const Dual<N>& b) {
    Dual<N> c(a.v + b.v);
    for (int k = 0; k < N; ++k) c.d[k] = a.d[k] + b.d[k];
    return c;
}
template <int N>
Dual<N> operator-(const Dual<N>& a, const Dual<N>& b) {
    Dual<N> c(a.v - b.v);
    for (int k = 0; k < N; ++k) c.d[k] = a.d[k] - b.d[k];
    return c;
}
template <int N>
Dual<N> operator-(const Dual<N>& a) {
    Dual<N> c(-a.v);
    for (int k = 0; k < N; ++k) c.d[k] = -a.d[k];
    return c;
}
template <int N>
Dual<N> operator*(const Dual<N>& a, const Dual<N>& b) {
    Dual<N> c(a.v * b.v);
    for (int k = 0; k < N; ++k) c.d[k] = a.d[k] * b.v + a.v * b.d[k];
    return c;
}
template <int N>
Dual<N> operator/(const Dual<N>& a, double b) {
    Dual<N> c(a.v / b);
    for (int k = 0; k < N; ++k) c.d[k] = a.d[k] / b;
    return c;
}
template <int N>
Dual<N> operator+(const Dual<N>& a, double b) { return a + Dual<N>(b); }
template <int N>
Dual<N> operator+(double a, const Dual<N>& b) { return Dual<N>(a) + b; }
template <int N>
Dual<N> operator-(const Dual<N>& a, double b) { return a - Dual<N>(b); }
template <int N>
Dual<N> operator-(double a, const Dual<N>& b) { return Dual<N>(a) - b; }
template <int N>
Dual<N> operator*(double a, const Dual<N>& b) {
    Dual<N> c(a * b.v);
    for (int k = 0; k < N; ++k) c.d[k] = a * b.d[k];
    return c;
}
template <int N>
Dual<N> operator*(const Dual<N>& a, double b) { return b * a; }

}  // namespace gyrostat::model
