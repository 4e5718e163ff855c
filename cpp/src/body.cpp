#include "gyrostat/body.hpp"

#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>

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

std::string Body::describe() const {
    std::ostringstream s;
    s << "Body(A1=" << moments_[0] << ", A2=" << moments_[1] << ", A3=" << moments_[2]
      << ", k=[" << rotor_[0] << ", " << rotor_[1] << ", " << rotor_[2] << "])";
    return s.str();
}

void require_finite(const Eigen::Ref<const Eigen::VectorXd>& v, const std::string& what) {
    for (Eigen::Index i = 0; i < v.size(); ++i)
        if (!std::isfinite(v[i]))
            throw std::invalid_argument(what + ": component " + std::to_string(i) + " = " + format_value(v[i]) +
                                        " is not finite");
}

}  // namespace gyrostat
