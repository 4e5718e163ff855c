#include "gyrostat/body.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "gyrostat/attitude.hpp"

namespace gyrostat {

namespace {
const char* const kAxis[3] = {"A1", "A2", "A3"};
}  // namespace

std::string format_value(double x) {
    if (std::isnan(x)) return "nan";
    if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, x);
    return std::string(buffer, result.ptr);
}

Body::Body(const Vec3& moments, const Vec3& rotor) : moments_(moments), rotor_(rotor) {
    for (int i = 0; i < 3; ++i) {
        if (!std::isfinite(moments[i]))
            throw std::invalid_argument(std::string("Body: principal moment ") + kAxis[i] + " = " +
                                        format_value(moments[i]) + " is not finite");
        if (!(moments[i] > 0.0))
            throw std::invalid_argument(std::string("Body: principal moment ") + kAxis[i] + " = " +
                                        format_value(moments[i]) + " must be positive");
    }
    for (int i = 0; i < 3; ++i) {
        const double others = moments.sum() - moments[i];
        // A relative slack of a few ulps lets flat bodies (equality) through.
        if (moments[i] > others * (1.0 + 8.0 * std::numeric_limits<double>::epsilon()))
            throw std::invalid_argument(std::string("Body: principal moment ") + kAxis[i] + " = " +
                                        format_value(moments[i]) + " exceeds the sum of the other two (" +
                                        format_value(others) +
                                        "); the triangle inequality of inertia is violated");
    }
    require_finite(rotor, "Body: rotor momentum k");
    inverse_moments_ = moments_.cwiseInverse();
}

Body Body::with_rotor(const Vec3& rotor) const {
    require_finite(rotor, "Body: rotor momentum k");
    Body body = *this;
    body.rotor_ = axes_.transpose() * rotor;
    return body;
}

Body Body::from_inertia(const Mat3& inertia, const Vec3& rotor) {
    for (int i = 0; i < 9; ++i)
        if (!std::isfinite(inertia.data()[i]))
            throw std::invalid_argument("Body: inertia tensor entry (" + std::to_string(i % 3) + ", " +
                                        std::to_string(i / 3) + ") = " + format_value(inertia.data()[i]) +
                                        " is not finite");
    const double scale = inertia.cwiseAbs().maxCoeff();
    for (int i = 0; i < 3; ++i)
        for (int j = i + 1; j < 3; ++j)
            if (std::abs(inertia(i, j) - inertia(j, i)) > 1e-12 * scale)
                throw std::invalid_argument("Body: the inertia tensor is not symmetric: I[" + std::to_string(i) + "][" +
                                            std::to_string(j) + "] = " + format_value(inertia(i, j)) + " but I[" +
                                            std::to_string(j) + "][" + std::to_string(i) + "] = " +
                                            format_value(inertia(j, i)));
    const Mat3 symmetric = 0.5 * (inertia + inertia.transpose());
    if (symmetric.isDiagonal(0.0)) return Body(symmetric.diagonal(), rotor);  // already principal: R = I

    const Eigen::SelfAdjointEigenSolver<Mat3> solver(symmetric);
    const Vec3 lambda = solver.eigenvalues();
    const Mat3 V = solver.eigenvectors();
    // Among the relabellings R(:, j) = s_j V(:, π(j)) with det R = +1, the one with the largest
    // trace: the rotation closest to the identity (tr R = 1 + 2 cos(angle)).
    std::array<int, 3> perm{0, 1, 2}, best_perm = perm;
    Vec3 best_signs = Vec3::Ones();
    double best_trace = -std::numeric_limits<double>::infinity();
    do {
        for (int signs = 0; signs < 8; ++signs) {
            Mat3 R;
            Vec3 s;
            for (int j = 0; j < 3; ++j) {
                s[j] = (signs >> j) & 1 ? -1.0 : 1.0;
                R.col(j) = s[j] * V.col(perm[j]);
            }
            if (R.determinant() < 0.0) continue;
            if (R.trace() > best_trace) best_trace = R.trace(), best_perm = perm, best_signs = s;
        }
    } while (std::next_permutation(perm.begin(), perm.end()));
    Mat3 R;
    Vec3 moments;
    for (int j = 0; j < 3; ++j) {
        R.col(j) = best_signs[j] * V.col(best_perm[j]);
        moments[j] = lambda[best_perm[j]];
    }
    R = (R.array() + 0.0).matrix();  // −0 → +0
    require_finite(rotor, "Body: rotor momentum k");
    Body body(moments, R.transpose() * rotor);
    body.principal_ = false;
    body.axes_ = R;
    body.axes_quaternion_ = quaternion_from_matrix(R);
    return body;
}

std::string Body::describe() const {
    std::ostringstream s;
    if (principal_) {
        s << "Body(A1=" << moments_[0] << ", A2=" << moments_[1] << ", A3=" << moments_[2]
          << ", k=[" << rotor_[0] << ", " << rotor_[1] << ", " << rotor_[2] << "])";
        return s.str();
    }
    const Mat3 I = inertia();
    const Vec3 k = axes_ * rotor_;
    s << "Body(inertia=[";
    for (int i = 0; i < 3; ++i) s << (i ? ", [" : "[") << I(i, 0) << ", " << I(i, 1) << ", " << I(i, 2) << "]";
    s << "], k=[" << k[0] << ", " << k[1] << ", " << k[2] << "]; principal A1=" << moments_[0] << ", A2=" << moments_[1]
      << ", A3=" << moments_[2] << ")";
    return s.str();
}

void require_finite(const Eigen::Ref<const Eigen::VectorXd>& v, const std::string& what) {
    for (Eigen::Index i = 0; i < v.size(); ++i)
        if (!std::isfinite(v[i]))
            throw std::invalid_argument(what + ": component " + std::to_string(i) + " = " + format_value(v[i]) +
                                        " is not finite");
}

}  // namespace gyrostat
