// A set of perturbation torques acting on one body: composition without virtual calls.
#pragma once

#include <variant>
#include <vector>

#include "gyrostat/body.hpp"
#include "gyrostat/torque/constant.hpp"
#include "gyrostat/torque/linear_damping.hpp"

namespace gyrostat {

/// Every torque type the library knows. Each is a small value type with
///   Vec3 operator()(t, ω)                  the torque in body axes,
///   void add_jacobian(t, ω, Mat3& dM_dω)   its derivative with respect to ω,
///   static name.
using AnyTorque = std::variant<torque::Constant, torque::LinearDamping>;

/// The torques on a body. Torques that are affine in ω (constant, linear damping) are folded at
/// construction into one M0 − D ω, so the hot path costs one 3×3 product whatever their number;
/// the list of parts is kept for reporting and for averaging.
class TorqueSet {
public:
    TorqueSet() = default;
    explicit TorqueSet(std::vector<AnyTorque> parts) : parts_(std::move(parts)) {
        for (const auto& part : parts_) fold(part);
    }

    const std::vector<AnyTorque>& parts() const { return parts_; }
    bool empty() const { return parts_.empty(); }
    bool has_damping() const { return has_damping_; }

    /// Σ M_i(t, ω).
    Vec3 total(double /*t*/, const Vec3& omega) const {
        if (has_damping_) return constant_ - damping_ * omega;
        return constant_;
    }
    /// Σ ∂M_i/∂ω.
    Mat3 jacobian(double /*t*/, const Vec3& /*omega*/) const { return -damping_; }

private:
    void fold(const AnyTorque& part) {
        std::visit(
            [this](const auto& t) {
                using T = std::decay_t<decltype(t)>;
                if constexpr (std::is_same_v<T, torque::Constant>) {
                    constant_ += t.moment;
                } else if constexpr (std::is_same_v<T, torque::LinearDamping>) {
                    damping_ += t.matrix;
                    has_damping_ = true;
                }
            },
            part);
    }

    std::vector<AnyTorque> parts_;
    Vec3 constant_ = Vec3::Zero();
    Mat3 damping_ = Mat3::Zero();
    bool has_damping_ = false;
};

}  // namespace gyrostat
