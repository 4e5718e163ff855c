// Unit vectors without overflow or underflow: every direction the library normalises (a torque's
// axis, an orbit's normal, the attitude quaternion given or integrated).
//
// |v| = √(v·v) overflows when a component exceeds ~1e154 (v·v > 1.8e308) and underflows when
// every component is below ~1e-154 (v·v < 2.2e-308): v / |v| is then 0 or not a unit vector, a
// wrong answer without an error. Dividing by the largest |v_i| first brings the largest
// component to 1, so that 1 ≤ v·v ≤ n whatever the scale v was given at.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "gyrostat/body.hpp"

namespace gyrostat {

/// v / |v| computed as u / |u|, u = v / max|v_i|: no overflow or underflow for any finite,
/// non-zero v (the caller checks that it is: unit_direction below, unit_quaternion).
template <class Derived>
typename Derived::PlainObject scaled_unit(const Eigen::MatrixBase<Derived>& v) {
    const typename Derived::PlainObject u = v / v.cwiseAbs().maxCoeff();
    return u / u.norm();
}

/// v ← v / |v| in place, for states kept on the unit sphere (the integrated quaternion's
/// projection): Eigen's normalize(), bit for bit, where v·v is a normal number, and scaled_unit
/// where it overflows or underflows (an initial quaternion given at any scale). A zero or
/// non-finite v is left as it is: the run reports a state that is not finite, never a direction
/// it made up.
template <class V>
void normalize_in_place(V&& v) {
    const double squares = v.squaredNorm();
    if (squares >= std::numeric_limits<double>::min() && squares <= std::numeric_limits<double>::max()) {
        v /= std::sqrt(squares);
        return;
    }
    if (!v.allFinite()) return;
    if (v.cwiseAbs().maxCoeff() > 0.0) v = scaled_unit(v);
}

/// "[x, y, z]" (each component as format_value writes it), for the messages naming a vector.
template <class Derived>
std::string format_vector(const Eigen::MatrixBase<Derived>& v) {
    std::string text = "[";
    for (Eigen::Index i = 0; i < v.size(); ++i) text += (i ? ", " : "") + format_value(v[i]);
    return text + "]";
}

/// The unit vector along a direction the user gives, whose length does not matter (`what`: the
/// parameter, "GravityGradient: orbit_normal"; `meaning`: what the direction is, for the message).
/// Throws std::invalid_argument "<what> = [...] must not be zero (<meaning>)" for v = 0 and
/// "<what> = [...] must be finite (<meaning>)" for a NaN or infinite component.
template <class Derived>
typename Derived::PlainObject unit_direction(const Eigen::MatrixBase<Derived>& v, const std::string& what,
                                             const std::string& meaning) {
    const std::string why = meaning.empty() ? "" : " (" + meaning + ")";
    if (!v.allFinite()) throw std::invalid_argument(what + " = " + format_vector(v) + " must be finite" + why);
    if (!(v.cwiseAbs().maxCoeff() > 0.0)) throw std::invalid_argument(what + " = " + format_vector(v) + " must not be zero" + why);
    return scaled_unit(v);
}

}  // namespace gyrostat
