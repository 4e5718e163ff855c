// What a torque declares about itself beside its equations: its parameters (name, shape, unit,
// description, constraint) and how it is built from named values. The scene schema, the Python
// classes, their constructors, properties and reprs, the list of valid torques in error messages
// and docs/scenes.md are generated from these declarations (cpp/bindings/expose_body.cpp,
// python/gyrostat/torques.py); nothing about a torque is restated elsewhere.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "gyrostat/body.hpp"

namespace gyrostat::torque {

/// The shape of a parameter's value.
enum class Shape {
    Scalar,    ///< one real number
    Vector3,   ///< three real numbers (body axes)
    Matrix3,   ///< a 3×3 matrix (body axes)
    Matrices,  ///< one or more 3×3 matrices (the coefficients of a polynomial in t)
};

/// The frame a vector or matrix parameter is written in. A body given by its inertia tensor in
/// some frame other than its principal axes (Body::from_inertia) has its torques' body-axes
/// parameters rotated into the principal axes (TorqueSet::in_principal_axes): v → Rᵀ v and
/// D → Rᵀ D R; inertial-axes parameters stay as given.
enum class Axes {
    Body,      ///< the body frame the user gave the body in
    Inertial,  ///< inertial axes
};

/// What a parameter's every component must satisfy.
enum class Constraint {
    Finite,       ///< finite
    Positive,     ///< finite and > 0
    NonNegative,  ///< finite and ≥ 0
};

/// One parameter of a torque. `choice` = 0: required; `choice` = k > 0: exactly one of the
/// parameters with the same k is given (alternative ways to say the same thing, e.g. a matrix or
/// its diagonal); `stored` says whether the torque keeps it (a property in Python) or only
/// builds from it; `default_value`, when given, makes it optional: the value it takes when left
/// out, as a scene writes it ("0", "[0, 0, 1]"; `from` supplies the same value).
struct Parameter {
    const char* name;         ///< its key in a scene and its keyword in Python
    const char* label;        ///< how an error message names it (e.g. "cavity radius b")
    Shape shape;
    const char* unit;         ///< SI unit ("1": dimensionless)
    const char* description;  ///< one line: what it is
    Constraint constraint = Constraint::Finite;
    int choice = 0;
    bool stored = true;
    const char* default_value = nullptr;
    Axes axes = Axes::Body;  ///< for Vector3, Matrix3 and Matrices
};

/// A parameter's value.
using Value = std::variant<double, Vec3, Mat3, std::vector<Mat3>>;

/// Named values of a torque's parameters, as given (a scene table, Python keywords).
class Values {
public:
    Values() = default;
    void set(const std::string& name, Value value) { values_[name] = std::move(value); }
    bool has(const std::string& name) const { return values_.count(name) != 0; }
    const std::map<std::string, Value>& all() const { return values_; }

    double scalar(const std::string& name) const { return std::get<double>(at(name)); }
    const Vec3& vector(const std::string& name) const { return std::get<Vec3>(at(name)); }
    /// An optional parameter's value, or its default when it was left out.
    double scalar_or(const std::string& name, double otherwise) const { return has(name) ? scalar(name) : otherwise; }
    Vec3 vector_or(const std::string& name, const Vec3& otherwise) const { return has(name) ? vector(name) : otherwise; }
    const Mat3& matrix(const std::string& name) const { return std::get<Mat3>(at(name)); }
    const std::vector<Mat3>& matrices(const std::string& name) const { return std::get<std::vector<Mat3>>(at(name)); }

private:
    const Value& at(const std::string& name) const {
        const auto it = values_.find(name);
        if (it == values_.end()) throw std::invalid_argument("missing parameter " + name);
        return it->second;
    }
    std::map<std::string, Value> values_;
};

/// The words of a constraint in messages and docs ("finite and positive").
inline const char* constraint_text(Constraint c) {
    switch (c) {
        case Constraint::Positive: return "finite and positive";
        case Constraint::NonNegative: return "finite and non-negative";
        case Constraint::Finite: break;
    }
    return "finite";
}

/// Whether x satisfies c.
inline bool satisfies(Constraint c, double x) {
    if (!std::isfinite(x)) return false;
    if (c == Constraint::Positive) return x > 0.0;
    if (c == Constraint::NonNegative) return x >= 0.0;
    return true;
}

/// Throws std::invalid_argument "<torque>: <label> = <x> must be <constraint>" unless x satisfies
/// the parameter's constraint: the one rule, used by the constructor (the scene schema applies
/// the same declaration before).
inline void require(const char* torque, const Parameter& p, double x) {
    if (!satisfies(p.constraint, x))
        throw std::invalid_argument(std::string(torque) + ": " + p.label + " = " + format_value(x) + " must be " +
                                    constraint_text(p.constraint));
}
/// The same for every component of a vector or matrix ("component i" in column-major order);
/// `index` ≥ 0 names the matrix of a list (Shape::Matrices: "coefficient 2").
inline void require(const char* torque, const Parameter& p, const Eigen::Ref<const Eigen::MatrixXd>& m, int index = -1) {
    const std::string what = std::string(torque) + ": " + p.label + (index >= 0 ? " " + std::to_string(index) : "");
    for (Eigen::Index i = 0; i < m.size(); ++i)
        if (!satisfies(p.constraint, m.data()[i]))
            throw std::invalid_argument(what + ": component " + std::to_string(i) + " = " +
                                        format_value(m.data()[i]) + " must be " + constraint_text(p.constraint));
}

/// D diagonal with D11 = D22: a linear torque −Dω that commutes with rotations about body z.
inline bool is_axisymmetric(const Mat3& d) {
    return d(0, 1) == 0.0 && d(0, 2) == 0.0 && d(1, 0) == 0.0 && d(1, 2) == 0.0 && d(2, 0) == 0.0 && d(2, 1) == 0.0 &&
           d(0, 0) == d(1, 1);
}

/// The motion a validity check looks at: the largest values over the states checked.
struct Motion {
    Vec3 moments = Vec3::Ones();  ///< (A, B, C)
    double speed = 0.0;           ///< max |ω|
    double momentum = 0.0;        ///< max |J ω|
    double axial_frequency = 0.0; ///< max |(C − A) r / A|, the symmetric body's precession rate ν

    /// From the angular velocities ω_i (rows) of a body with these moments.
    static Motion of(const Vec3& moments, const Eigen::Ref<const Eigen::MatrixX3d>& omegas) {
        Motion m;
        m.moments = moments;
        const double A = moments[0], C = moments[2];
        for (Eigen::Index i = 0; i < omegas.rows(); ++i) {
            const Vec3 w = omegas.row(i).transpose();
            m.speed = std::max(m.speed, w.norm());
            m.momentum = std::max(m.momentum, moments.cwiseProduct(w).norm());
            m.axial_frequency = std::max(m.axial_frequency, std::abs((C - A) * w[2] / A));
        }
        return m;
    }
};

/// One assumption a torque's model rests on, measured: `value` against `limit` (`holds` says
/// whether it does), in the words of the torque's header.
struct Assumption {
    std::string part;       ///< what assumes it ("viscous cavity")
    std::string statement;  ///< the condition ("Reynolds number |ω| b²/ν ≪ 1")
    double value = 0.0;
    double limit = 0.0;
    bool holds = true;
    std::string note;       ///< what the number rests on, or "" 
};

/// "≪ 1" in numbers: the one threshold of every validity check (a ratio that must be small is
/// at most this; one that must be large is at least its inverse).
inline constexpr double kSmall = 0.1;
/// "≫ 1" for the conditions a paper prints as such.
inline constexpr double kLarge = 10.0;

}  // namespace gyrostat::torque
