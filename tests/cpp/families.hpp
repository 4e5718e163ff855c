// One model of every family with an initial state for it, shared by the C++ tests that run
// "every family" (test_core.cpp: the engine and mixed ensembles; test_auto_method.cpp: method
// 'auto'), so that a new family is added to both at once.
#pragma once

#include <cmath>
#include <vector>

#include "gyrostat/engine.hpp"
#include "gyrostat/model/averaged.hpp"
#include "gyrostat/model/gyrostat.hpp"
#include "gyrostat/model/lagrange_averaged.hpp"
#include "gyrostat/model/lagrange_top.hpp"
#include "gyrostat/model/moving_mass.hpp"
#include "gyrostat/model/orbiting.hpp"
#include "gyrostat/model/orthogonal.hpp"
#include "gyrostat/model/torque_free.hpp"

struct EveryFamily {
    std::vector<gyrostat::AnyModel> models;
    std::vector<Eigen::VectorXd> starts;
};

/// In this order: gyrostat, gyrostat with attitude (ω alone given: identity quaternion), averaged
/// (a, r), explicit moving mass (ω = (1, 0, 1), mass at rest), Lagrange top, averaged top (from the
/// full top's state), orthogonal torque without and with attitude (τ(0) = 0 completed), and the
/// gyrostat on a circular orbit under the gravity gradient (ω alone: identity quaternion), and the
/// torque-free closed form last. Body (1, 2, 3) and ω0 = (1, 0.5, −0.3) where a rigid body is needed.
inline EveryFamily every_family() {
    using namespace gyrostat;
    const Body body(Vec3(1.0, 2.0, 3.0)), sym(Vec3(1.5, 1.5, 1.0));
    const Vec3 w0(1.0, 0.5, -0.3);
    const TorqueSet damping({torque::LinearDamping(0.01 * Mat3::Identity())});
    EveryFamily f;
    f.models = {model::Gyrostat<false>(body, damping),
                model::Gyrostat<true>(body, damping),
                model::AveragedSymmetric(Body(Vec3(8.0, 8.0, 4.0)), TorqueSet({torque::ViscousCavity(1260.0, 1000.0, 0.48)})),
                model::MovingMass(Body(Vec3(4.0, 4.0, 2.0)), 1.0, 1.0, 10.0, 98.0, TorqueSet{}),
                model::LagrangeTop(sym, 0.5, damping),
                model::LagrangeAveraged(sym, 0.5, damping),
                model::OrthogonalTorque<false>(Body(Vec3(2.0, 3.0, 4.0)), model::MagnitudeLaw::constant(0.1)),
                model::OrthogonalTorque<true>(Body(Vec3(2.0, 3.0, 4.0)), model::MagnitudeLaw::constant(0.1)),
                model::OrbitingGyrostat(body, TorqueSet({torque::GravityGradient(torque::OrbitOfTorque{})}),
                                        torque::CircularOrbit(0.5, Vec3(0.0, 1.0, 1.0), 0.3, "every_family")),
                model::TorqueFree(body)};
    Eigen::VectorXd top0(7);
    top0 << 0.1, 0.0, 1.7, std::cos(0.25), std::sin(0.25), 0.0, 0.0;
    Eigen::VectorXd mass0 = Eigen::VectorXd::Zero(9);
    mass0.head<3>() = Vec3(1.0, 0.0, 1.0);
    f.starts = {Eigen::Vector3d(w0), Eigen::Vector3d(w0), Eigen::Vector2d(1.0, 1.0), mass0, top0, top0,
                Eigen::Vector3d(w0), Eigen::Vector3d(w0), Eigen::Vector3d(w0), Eigen::Vector3d(w0)};
    return f;
}
