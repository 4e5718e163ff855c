// The torque-free rigid body in closed form (Euler–Poinsot motion): Jacobi elliptic functions,
// no integration at all. The cheapest answer for a scene with no torque and no rotor.
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <vector>

#include "gyrostat/body.hpp"
#include "gyrostat/numeric/double_double.hpp"
#include "gyrostat/model/system.hpp"

namespace gyrostat::model {

/// How the constants that multiply t are computed (see "Precision" in FreeBodyFlow's comment).
enum class Phases {
    Extended,  ///< double-double (the default): error ~1e-15 at any t up to ~1e15/|ω|
    Double     ///< double: ~1e-16·|ω|·t, for the short sub-steps of a splitting (|ω| h ~ 1)
};

/// The constants of the closed form, computed once from the exact double inputs (moments, ω0)
/// in double-double (or double, Phases::Double); those that multiply t are kept as double-double,
/// the others (used on a bounded argument only) are rounded to double. One place for
/// TorqueFreeSolution (ω) and FreeBodyFlow (the precession).
struct FreeBodyConstants {
    bool constant = true;                  ///< at rest, spherical, or a permanent rotation
    int axis[3] = {0, 1, 2};               ///< body index of axes 1', 2', 3' (3': the polhode's axis)
    double a = 0, b = 0, c = 0, m = 0, sign3 = 1;
    double m1 = 1;                         ///< 1 − m from its own formula (every digit next to m = 1)
    DoubleDouble nu, K;                    ///< ν and K(m) (K = ∞ on the separatrix m = 1)
    // with the precession (FreeBodyFlow): |G|, |G|/C, |G|(C − A)/(C A ν), Π(N | m), N
    DoubleDouble G, rate, coeff, Pi_complete;
    double N = 0;
};

/// ω(t) of a free rigid body (rotor k = 0) from ω(t0) = ω0.
///
/// With the axes relabelled (1', 2', 3') so that the polhode encircles axis 3' (the axis of the
/// largest moment when D = G²/2T > A2, of the smallest otherwise), and A, B, C the moments on
/// those axes:
///   ω1' = a cn(u, m),  ω2' = b sn(u, m),  ω3' = ±c dn(u, m),  u = ν (t − t0) + u0,
///   a² = (2TC − G²)/(A(C − A)),  b² = (2TC − G²)/(B(C − B)),  c² = (G² − 2TA)/(C(C − A)),
///   m = k² = (B − A)(2TC − G²)/((C − B)(G² − 2TA)),  ν = σ (C − B) b c/(A a),
/// with σ = ±1 from the sign of ω3' and the parity of the relabelling, and u0 the argument at
/// which sn = ω2'(t0)/b, cn = ω1'(t0)/a, dn = |ω3'(t0)|/c (u0 = F(φ0, k), φ0 = atan2(sn, cn);
/// Landau & Lifshitz, Mechanics §37). Next to the separatrix m = 1 − m1 with m1 below the
/// rounding of 1 (1 − k² = 1e-30 is reached from ω0 = (1e-15, 1, 1e-15)): m1 is formed as
/// (C − A)(A(A − B)ω1² + C(C − B)ω3²)/((C − B)(G² − 2TA)), a sum of components, never as 1 − m,
/// and both sn, cn, dn(u | m) and u0 are evaluated from m1 (elliptic.hpp), with dn u0 taken from
/// ω3' itself rather than from √(1 − m sn²).
/// Permanent rotations (a = b = 0) and the spherical body give a constant ω. The argument u is
/// reduced to r ∈ [−K, K] (u = 2jK + r; sn, cn change sign with j, dn does not) so that the
/// cost does not depend on t. ν and K (FreeBodyConstants) are computed in double-double from the
/// exact inputs, and u = ν (t − t0) + u0 − 2jK is formed in double-double (t − t0 exactly) before
/// sn, cn, dn are evaluated in double on r: the phase keeps ~1e-16 absolute accuracy at any t
/// (see "Precision" in FreeBodyFlow's comment). The attitude is FreeBodyFlow's (below).
class TorqueFreeSolution {
public:
    /// Throws std::invalid_argument when the body has a rotor (k ≠ 0: the Zhukovsky–Volterra
    /// gyrostat has no such closed form here) or ω0 is not finite. `precession` also computes
    /// FreeBodyFlow's constants (G, rate, coeff, Π(N | m)).
    TorqueFreeSolution(const Body& body, const Vec3& omega0, double t0 = 0.0, Phases phases = Phases::Extended,
                       bool precession = false);
    TorqueFreeSolution() = default;  ///< at rest (a placeholder)

    Vec3 omega(double t) const;
    Vec3 at(double t) const { return omega(t); }                          ///< the flow's state at t
    std::vector<double> omega(const std::vector<double>& times) const;  ///< n×3, row-major

    double modulus_squared() const { return k_.m; }           ///< m = k² (0 for permanent rotation)
    double complementary_parameter() const { return k_.m1; }  ///< 1 − k², to full relative accuracy
    double frequency() const { return double(k_.nu); }        ///< ν (rad/s of the argument u)
    double period() const;                                     ///< of ω(t): 4K(m)/|ν| (∞ when constant)
    /// The longest piece over which an event search may assume at most one crossing of a smooth
    /// function of ω: 1/32 of the period (∞ when ω is constant).
    double event_step() const { return period() / 32.0; }
    bool is_constant() const { return k_.constant; }

    /// u(t) = 2jK + r, |r| ≤ K: (j, sn r, cn r, dn r) (on the separatrix m = 1: r = u, and j = 0,
    /// or 1 on the mirrored orbit where ω1' < 0).
    struct Reduced {
        double j, sn, cn, dn;
    };
    Reduced reduced(double t) const { return reduced_since(two_diff(t, t0_)); }
    /// The same at t = t0 + τ, τ given in double-double (FreeBodyFlow's scaled time).
    Reduced reduced_since(const DoubleDouble& tau) const;
    /// ω at t = t0 + τ from the reduced argument (one place for the signs of the pieces).
    Vec3 omega(const Reduced& z) const;
    const FreeBodyConstants& constants() const { return k_; }
    /// The relabelling: body index of axes 1', 2', 3' (3' is the axis the polhode encircles).
    const int* axes() const { return k_.axis; }
    double a() const { return k_.a; }
    double b() const { return k_.b; }
    double c() const { return k_.c; }
    double sign3() const { return k_.sign3; }
    double argument0() const { return u0_; }  ///< u0 = u(t0)

private:
    Vec3 omega0_ = Vec3::Zero();
    double t0_ = 0.0, u0_ = 0.0;
    double branch_ = 0.0;  ///< on the separatrix: 1 for the mirrored orbit (ω1' < 0), else 0
    FreeBodyConstants k_;
};

// ---------------------------------------------------------------------------------------------
// The exact free-body flow with attitude
// ---------------------------------------------------------------------------------------------
//
// Conventions: the quaternion q = (w, x, y, z) rotates BODY axes into INERTIAL axes,
// x_inertial = q ⊗ (0, x_body) ⊗ q* = R(q) x_body (attitude.hpp, python/gyrostat/attitude.py); ω is
// in body axes; the inertial angular momentum G_in = R(q) (J ω + k) is constant.
//
// Derivation (rigid body, k = 0, asymmetric; Landau & Lifshitz §37, Celledoni, Fassò, Säfström
// & Zanna, SIAM J. Sci. Comput. 30 (2008) 2084, §2–3; van Zon & Schofield, J. Comput. Phys. 225
// (2007) 145). Take the relabelled axes (1', 2', 3') of TorqueFreeSolution, 3' the axis the
// polhode encircles, made RIGHT-HANDED by e2' = s e_{axis 1'}, s = +1 for a cyclic relabelling and
// −1 for an odd one: x' = S x_body with S a proper signed permutation (the paper's case-by-case
// sign conventions, and the corrections published to it, were not checked here: this explicit S
// and the tests against integrated quaternions for both parities stand instead). Let Z be the
// inertial axis along G_in and
// g' = S J ω / |G| the unit vector of G in primed body axes. The z-x-z Euler angles (φ, θ, ψ)
// of the primed body axes relative to a frame with z along G satisfy
//   g' = (sin θ sin ψ, sin θ cos ψ, cos θ)          (θ, ψ: ω alone fixes them),
// i.e. W(t) = Rx(θ) Rz(ψ) maps g' to e_z. The kinematic equations ω'1 = φ̇ sin θ sin ψ + θ̇ cos ψ,
// ω'2 = φ̇ sin θ cos ψ − θ̇ sin ψ give φ̇ sin²θ |G| = A ω'1² + B ω'2², so, with
// A²ω'1² + B²ω'2² = G² − C²ω'3² and A ω'1² + B ω'2² = 2T − C ω'3²,
//   φ̇ = |G| (2T − C ω'3²) / (G² − C² ω'3²) = |G|/C + |G| (2TC − G²) / (C (G² − C² ω'3²)).
// With ω'3 = ±c dn u, dn² = 1 − m sn², G² − C²c² = A²a² (the value at sn = 0):
//   G² − C² ω'3² = A² a² (1 − N sn² u),   N = −C² c² m / (A² a²) = −C (B − A) / (A (C − B)) ≤ 0,
// and (2TC − G²)/(A² a²) = (C − A)/A, so with du = ν dt
//   φ(t) − φ(t0) = |G| (t − t0)/C + |G| (C − A) / (C A ν) · [Π̃(u) − Π̃(u0)],
//   Π̃(u) = ∫_0^u dv / (1 − N sn² v) = 2j Π(N | m) + Π(N; am r | m),  u = 2jK + r, |r| ≤ K,
// the incomplete integral of the third kind by Carlson's R_F, R_J (elliptic.hpp). N ≤ 0: no
// pole, for both orderings (rotation about the largest axis, C > B > A, and about the smallest,
// C < B < A: then C − A < 0 and φ̇ = |G|/A > 0 at sn = 0 as well). On the separatrix (m = 1,
// K = ∞) nothing is reduced and the same formulas hold with sn = tanh, cn = dn = sech.
// ψ is made continuous across the pieces of u: ψ = atan2(A a cn r, s B b sn r) − s j π.
// Then, body → inertial,
//   R(t) = R_in Rz(φ(t) − φ(t0)) Rx(θ(t)) Rz(ψ(t)) S,   R_in = R(q0) Sᵀ (Rx(θ0) Rz(ψ0))ᵀ,
// in quaternions q(t) = q_in ⊗ q_z(Δφ) ⊗ q_x(θ) ⊗ q_z(ψ) ⊗ q_S, continuous in t (no sign jumps):
// R(t) J ω(t) = |G| R_in e_z is constant, as it must be.
//
// Symmetric body (two equal moments A, symmetry axis e, moment C) with a rotor along e, or a
// spherical body with any rotor (the gyrostat cases with a closed form here): ω = G_b/A − λ,
// λ = ((C − A) ω·e + k·e)/A e (λ = k/A for the sphere), so ω̇ = λ × ω and
//   ω(t) = exp(Δt [λ]×) ω0,   R(t) = exp(Δt |G|/A [n]×) R0 exp(−Δt [λ]×),  n = G_in/|G|.
// Constant ω (at rest, a permanent rotation): R(t) = R0 exp(Δt [ω0]×).
// Any other gyrostat (an asymmetric body or a rotor off the symmetry axis) has no closed form
// here: the constructor throws std::invalid_argument naming the body.
//
// Precision. |G| and T are those of ω(t) from the elliptic functions, exact to rounding at any t.
// The phases grow with t: u = ν (t − t0) + u0, the secular part of φ, |G| (t − t0)/C + |G| (C − A)
// /(C A ν) · 2j Π(N | m), and in the symmetric and constant cases the angles |λ| t, |G| t/A, |ω0| t.
// In double, each carries the relative rounding (~1e-16) of its constant (ν, K, |G|/C, Π, computed
// through T, G², m, …) and of the product with t: an error ~1e-16·|ω|·t (9e-10 at t = 1e7 for
// I = (2, 3, 4), |ω0| ≈ 1). Here (Phases::Extended, the default) every constant that multiplies t,
// and everything it is derived from, is computed in double-double (double_double.hpp: 106 bits,
// portable, unlike long double) from the exact double inputs J and ω0 (scaled by a power of two:
// exact), K and Π by Carlson's R_F, R_J at that precision (elliptic.hpp); t − t0 is formed
// exactly; the phases are reduced in double-double (u modulo 2K, φ modulo 4π, j π modulo 4π: 4π
// keeps q continuous, q_z(φ + 2π) = −q_z(φ)), and only the reduced arguments are rounded to double
// for sn, cn, dn, Π(N; am r | m) and the quaternion's sines. The phase error is then ~1e-30·|ω| t
// (+ rounding ~1e-16 of the bounded parts): ≤ 1.1e-15 measured up to t = 1e9 (bench/long_horizon.py),
// i.e. the error of a double evaluation at any t up to ~1e15/|ω|, where t itself stops being
// resolved. The cost of one evaluation does not depend on t (0.7 µs at t = 1e3, 1e7, 1e9); the
// constructor's double-double constants cost once 12 µs with attitude (the R_J of Π), 2.3 µs
// without (measured; 2.0 and 0.65 µs in double). Phases::Double keeps them in double for the
// splitting's sub-steps, where |ω| h ~ 1 keeps the double error at rounding.
class FreeBodyFlow {
public:
    using State = Eigen::Matrix<double, 7, 1>;
    /// From (ω0, q0) at t0. `attitude = false` skips the quaternion's constants (at() then
    /// returns the identity quaternion's flow only in ω: use omega()). Throws
    /// std::invalid_argument for a gyrostat without a closed form here (see above) or a
    /// non-finite input.
    FreeBodyFlow(const Body& body, const Vec3& omega0, const Eigen::Vector4d& q0, double t0 = 0.0, bool attitude = true,
                 Phases phases = Phases::Extended);

    /// Throws std::invalid_argument naming the body when its free flow has no closed form here.
    static void require_closed_form(const Body& body, const char* who);

    Vec3 omega(double t) const;
    Eigen::Vector4d quaternion(double t) const;
    State at(double t) const;
    double period() const;
    double event_step() const;

private:
    /// The rotation by rate·τ about a fixed unit axis, the angle formed and reduced modulo 4π in
    /// double-double (q_rot(θ + 4π) = q_rot(θ)).
    struct Spin {
        Vec3 axis = Vec3::UnitZ();
        DoubleDouble rate;
        Eigen::Vector4d quaternion(const DoubleDouble& tau) const;
    };
    Eigen::Vector4d elliptic_quaternion(const DoubleDouble& tau, const TorqueFreeSolution::Reduced& z) const;
    enum class Kind { Constant, Symmetric, Elliptic };
    Kind kind_ = Kind::Constant;
    double t0_;
    Vec3 omega0_;
    Eigen::Vector4d q0_;
    TorqueFreeSolution elliptic_;
    // Constant: ω0 t; symmetric: ω̇ = λ × ω and the precession about G_in at |G|/A.
    Spin spin_, precession_;
    // Elliptic: the constants of the derivation, for ω0/scale_ and the time scale_ (t − t0)
    // (scale_ a power of two: exact). φ(τ) − φ(0) = rate τ + drift (j − j0) + coeff (Π̃(r) − Π̃(r0)).
    Eigen::Vector4d q_in_ = Eigen::Vector4d(1, 0, 0, 0), q_s_ = Eigen::Vector4d(1, 0, 0, 0);
    Mat3 S_ = Mat3::Identity();
    double scale_ = 1, s_ = 1, G_ = 0, A_ = 0, B_ = 0, C_ = 0, coeff_ = 0, j0_ = 0, Pi_r0_ = 0;
    DoubleDouble rate_, drift_;
};

/// q0 ⊗ q_rot(v), q_rot(v) = (cos |v|/2, sin(|v|/2) v/|v|): the rotation by the vector v.
Eigen::Vector4d rotation_quaternion(const Vec3& v);

/// The torque-free rigid body (or symmetric gyrostat with an axial rotor) as a model that needs
/// no integration (model/system.hpp, `flow`): state ω, or ω and the quaternion; outputs |G| and
/// T (conserved exactly: the closed form keeps them to rounding), with attitude the Euler angles.
template <bool WithAttitude>
class TorqueFreeBody : public RateAttitude<TorqueFreeBody<WithAttitude>, WithAttitude ? 7 : 3, WithAttitude> {
public:
    static constexpr int dim = WithAttitude ? 7 : 3;
    static constexpr const char* model_name = "TorqueFree";
    using State = Eigen::Matrix<double, dim, 1>;
    static constexpr const char* family = "torque_free";
    static constexpr auto states = rate_states<WithAttitude>();

    /// Throws std::invalid_argument for a gyrostat without a closed form here.
    explicit TorqueFreeBody(Body body) : body_(std::move(body)) {
        FreeBodyFlow::require_closed_form(body_, "TorqueFree");
    }
    const Body& body() const { return body_; }

    struct Flow {
        FreeBodyFlow exact;
        State at(double t) const {
            if constexpr (WithAttitude)
                return exact.at(t);
            else
                return exact.omega(t);
        }
        double event_step() const { return exact.event_step(); }
    };
    Flow flow(double t0, const State& y0) const {
        if constexpr (WithAttitude)
            return {FreeBodyFlow(body_, y0.template head<3>(), y0.template tail<4>(), t0, true)};
        else
            return {FreeBodyFlow(body_, y0, Eigen::Vector4d(1, 0, 0, 0), t0, false)};
    }
    /// ω̇ = J⁻¹ ((Jω + k) × ω), q̇ = ½ q ⊗ (0, ω): for checks and stiffness diagnostics (the solve
    /// never integrates it).
    void rhs(double, const State& y, State& dy) const {
        const Vec3 omega = y.template head<3>();
        dy.template head<3>() = body_.inverse_moments().cwiseProduct(body_.angular_momentum(omega).cross(omega));
        if constexpr (WithAttitude) dy.template segment<4>(3) = quaternion_rate(y.template segment<4>(3), omega);
    }
    static constexpr std::array<OutputInfo, 3> own_outputs{{{"angular_momentum_norm", "kg m^2/s", "|G| = |J omega + k|, the norm of the angular momentum", true, true}, {"kinetic_energy", "J", "T = omega . J omega / 2, the kinetic energy of the rotation", true, true}, nutation_angle_info}};
    static constexpr auto outputs_info = with_euler_outputs<WithAttitude>(own_outputs);
    /// |G|, T, the nutation angle ϑ between body z and G = Jω + k (model/system.hpp:
    /// nutation_angle), then ψ, θ, φ with the attitude.
    void outputs(double, const State& y, double* out) const {
        const Vec3 omega = y.template head<3>();
        const Vec3 G = body_.angular_momentum(omega);
        out[0] = G.norm();
        out[1] = body_.kinetic_energy(omega);
        out[2] = nutation_angle(G);
        this->attitude_outputs(y, out + 3);
    }

private:
    Body body_;
};

using TorqueFree = TorqueFreeBody<false>;
using TorqueFreeAttitude = TorqueFreeBody<true>;

}  // namespace gyrostat::model
