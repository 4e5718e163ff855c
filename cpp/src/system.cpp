// Compiled helpers of the model concept (model/system.hpp).
#include "gyrostat/model/system.hpp"

#include "gyrostat/body.hpp"

namespace gyrostat::model {

void check_quaternion(const Eigen::Vector4d& q, const char* model) {
    if (!q.allFinite() || q.cwiseAbs().maxCoeff() == 0.0)  // (not |q|² = 0: it underflows for |q_i| < 1e-154)
        throw std::invalid_argument(std::string(model) + ": the attitude quaternion (q_w, q_x, q_y, q_z) = (" +
                                    format_value(q[0]) + ", " + format_value(q[1]) + ", " + format_value(q[2]) + ", " +
                                    format_value(q[3]) + ") is not a rotation: it must be finite and non-zero");
}

}  // namespace gyrostat::model
