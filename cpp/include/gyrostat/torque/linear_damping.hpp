// A linear damping torque with a full 3x3 coefficient matrix.
#pragma once

#include <Eigen/Core>
#include <array>

#include "gyrostat/body.hpp"
#include "gyrostat/torque/affine.hpp"
#include "gyrostat/torque/parameter.hpp"

namespace gyrostat::torque {

/// M = −D ω with a constant 3×3 matrix D in body axes (paper 001: D = ε diag(I1, I1, I3);
/// paper 002: D = ε I with a full resistance tensor I).
/// D need not be symmetric; its symmetric part decides whether energy is dissipated:
/// d(ω·Jω/2)/dt = −ω·Dω. Assumptions: none; it does not need the attitude.
///
/// Averaged over the symmetric Euler–Poinsot motion:
///   ȧ = −(D11 + D22) a / (2A),   ṙ = −D33 r / C;
/// the off-diagonal entries and D11 − D22 average out (docs/papers/000_002_cavity_and_medium.md).
struct LinearDamping {
    static constexpr const char* name = "linear_damping";
    static constexpr const char* python_name = "LinearDamping";
    static constexpr const char* description = "M = -D omega";
    static constexpr std::array<Parameter, 2> parameters{{
        {"matrix", "matrix D (column-major)", Shape::Matrix3, "N m s", "D (M = -D omega)", Constraint::Finite, 1},
        {"diagonal", "diagonal of D", Shape::Vector3, "N m s", "the diagonal of D", Constraint::Finite, 1, false},
    }};
    /// M is affine in these (a sensitivity's ∂f/∂p is then a one-sided difference, exact).
    static constexpr std::array<const char*, 1> affine_in{{"matrix"}};

    Mat3 matrix = Mat3::Zero();

    explicit LinearDamping(const Mat3& d) : matrix(d) { require(python_name, parameters[0], d); }
    /// D itself, or a diagonal D from its diagonal.
    static LinearDamping from(const Values& v) {
        if (v.has("diagonal")) {
            require(python_name, parameters[1], v.vector("diagonal"));
            return LinearDamping(Mat3(v.vector("diagonal").asDiagonal()));
        }
        return LinearDamping(v.matrix("matrix"));
    }
    Values values() const {
        Values v;
        v.set("matrix", matrix);
        return v;
    }

    Vec3 operator()(double /*t*/, const Vec3& omega, const Vec3& /*moments*/) const { return -matrix * omega; }
    /// D_0 = D (torque/affine.hpp).
    AffineForm affine_form() const { return {Vec3::Zero(), {matrix}}; }
    static constexpr bool constant_coefficients = true;
    /// ∂M/∂ω = −D.
    void add_jacobian(double /*t*/, const Vec3& /*omega*/, const Vec3& /*moments*/, Mat3& dM_domega) const {
        dM_domega -= matrix;
    }
    Eigen::Vector2d averaged(double /*t*/, double a, double r, double A, double C) const {
        return {-(matrix(0, 0) + matrix(1, 1)) * a / (2.0 * A), -matrix(2, 2) * r / C};
    }
    /// Commutes with rotations about body z: D diagonal with D11 = D22.
    bool axisymmetric() const { return is_axisymmetric(matrix); }
};

}  // namespace gyrostat::torque
