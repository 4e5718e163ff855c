// Why did an explicit method fail? Estimates the stiffness of the problem at the failure point.
#pragma once

#include <Eigen/Eigenvalues>
#include <cmath>
#include <complex>
#include <string>

#include "gyrostat/integrate/recorder.hpp"

namespace gyrostat::integrate {

/// The eigenvalue of largest modulus of ∂f/∂y at (t, y): from the analytic Jacobian where the
/// system has one, otherwise from forward differences. NaN when it cannot be computed.
template <class System>
std::complex<double> dominant_eigenvalue(const System& system, double t, const typename System::State& y) {
    using State = typename System::State;
    Eigen::Matrix<double, System::dim, System::dim> jac;
    if constexpr (model::system::has_jacobian<System>::value) {
        system.jacobian(t, y, jac);
    } else {
        State f0, f1, yp = y;
        system.rhs(t, y, f0);
        for (int j = 0; j < System::dim; ++j) {
            const double dy = std::sqrt(std::numeric_limits<double>::epsilon()) * std::max(1.0, std::abs(y[j]));
            yp[j] = y[j] + dy;
            system.rhs(t, yp, f1);
            jac.col(j) = (f1 - f0) / dy;
            yp[j] = y[j];
        }
    }
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (!jac.allFinite()) return {nan, nan};
    Eigen::MatrixXd dynamic = jac;
    Eigen::EigenSolver<Eigen::MatrixXd> solver(dynamic, false);
    if (solver.info() != Eigen::Success) return {nan, nan};
    Eigen::Index k = 0;
    solver.eigenvalues().cwiseAbs().maxCoeff(&k);
    return solver.eigenvalues()[k];
}

/// λ as "a + bi" (or "a − bi") with `precision` significant digits, for messages.
inline std::string format_eigenvalue(std::complex<double> lambda, int precision = 6) {
    return format_number(lambda.real(), precision) + (lambda.imag() >= 0 ? " + " : " − ") +
           format_number(std::abs(lambda.imag()), precision) + "i";
}

/// Whether the eigenvalue λ is mainly decaying (Re λ < −|λ|/2): the mode an implicit method
/// damps at any step, and an explicit one only below its stability boundary in h·|λ|. (An
/// oscillatory mode limits BDF too: its orders 3–5 lose stability near the imaginary axis.)
inline bool decaying(std::complex<double> lambda) { return lambda.real() < -0.5 * std::abs(lambda); }

/// A sentence for the failure message of a non-stiff method whose steps collapsed. The problem
/// is called stiff when the dominant eigenvalue λ of the Jacobian is mainly decaying
/// (Re λ < −|λ|/2), the step has shrunk to the order of its time scale (h·|λ| ≥ 0.1: explicit
/// stability regions end at |hλ| ≈ 0.3–6) and the interval spans many such time scales
/// (|λ|·span ≥ 1000). Then the step is limited by stability, not accuracy.
template <class System>
std::string stiffness_hint(const System& system, double t, const typename System::State& y, double h, double span) {
    const std::complex<double> lambda = dominant_eigenvalue(system, t, y);
    const double rho = std::abs(lambda);
    if (!std::isfinite(rho) || h <= 0.0) return "";
    const double h_rho = h * rho;
    std::string s = " Last step h = " + format_number(h) + "; dominant eigenvalue of the Jacobian λ = " +
                    format_eigenvalue(lambda) + ", h·|λ| = " + format_number(h_rho, 3) + ".";
    if (decaying(lambda) && h_rho >= 0.1 && rho * span >= 1e3)
        s += " The step is held by the explicit stability limit, not by accuracy: the problem is stiff; "
             "use method='cvode_bdf'.";
    return s;
}

}  // namespace gyrostat::integrate
