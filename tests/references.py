"""Independent references for the tests: written here from the textbooks, sharing no code with
the library (SciPy's special functions and solve_ivp only)."""

from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp
from scipy.special import ellipj, ellipkinc, ellipk


def euler_poinsot(moments, omega0, t):
    """ω(t) of a torque-free rigid body (Landau & Lifshitz, Mechanics §37), written for the case
    at hand: axes sorted so that I1 < I2 < I3 and the polhode encircles the axis of the
    *smallest* or *largest* moment, decided by D = G²/2T against I2.

    Case D < I2 (around the smallest axis 1):
        ω1 = ±c1 dn(u), ω2 = c2 sn(u), ω3 = c3 cn(u)  (roles of axes 1 and 3 swapped w.r.t. L&L)
    Case D > I2 (around the largest axis 3):
        ω1 = c1 cn(u), ω2 = c2 sn(u), ω3 = ±c3 dn(u)
    The argument's rate and sign are fixed from the Euler equation for the sn-component and the
    initial phase from the initial values, so any initial condition is covered.
    """
    moments = np.asarray(moments, float)
    omega0 = np.asarray(omega0, float)
    t = np.asarray(t, float)
    order = np.argsort(moments)
    I = moments[order]
    w = omega0[order]
    G2 = np.sum((I * w) ** 2)
    T2 = np.sum(I * w**2)
    I1, I2, I3 = I
    if G2 / T2 > I2:  # around axis 3 (largest)
        amp_cn = np.sqrt((T2 * I3 - G2) / (I1 * (I3 - I1)))
        amp_sn = np.sqrt((T2 * I3 - G2) / (I2 * (I3 - I2)))
        amp_dn = np.sqrt((G2 - T2 * I1) / (I3 * (I3 - I1)))
        m = (I2 - I1) * (T2 * I3 - G2) / ((I3 - I2) * (G2 - T2 * I1))
        i_cn, i_sn, i_dn = 0, 1, 2
    else:  # around axis 1 (smallest)
        amp_cn = np.sqrt((G2 - T2 * I1) / (I3 * (I3 - I1)))
        amp_sn = np.sqrt((G2 - T2 * I1) / (I2 * (I2 - I1)))
        amp_dn = np.sqrt((T2 * I3 - G2) / (I1 * (I3 - I1)))
        m = (I3 - I2) * (G2 - T2 * I1) / ((I2 - I1) * (T2 * I3 - G2))
        i_cn, i_sn, i_dn = 2, 1, 0
    s_dn = np.sign(w[i_dn]) or 1.0
    # d(ω_sn)/dt = (I_other1 - I_other2)/I_sn ω_a ω_b in the sorted, right-handed frame
    # (sorting may reverse handedness: the sign is taken from the Euler equation itself below)
    # ω̇_sn = amp_sn cn dn u̇  must equal  f_sn(ω) at the initial instant's structure:
    #   Euler: I2 ω̇2 = (I3 - I1) ω3 ω1 * parity
    parity = np.linalg.det(np.eye(3)[order])  # +1 if the sorting is a rotation of axes, -1 if a reflection
    rate = parity * (I3 - I1) * (amp_cn * amp_dn * s_dn) / (I2 * amp_sn)
    if i_cn == 2:  # ω3 = amp_cn cn, ω1 = s_dn amp_dn dn: product ω3 ω1 = amp_cn amp_dn s_dn cn dn (same form)
        pass
    phi0 = np.arctan2(w[i_sn] / amp_sn, w[i_cn] / amp_cn)
    n = np.round(phi0 / np.pi)
    u0 = ellipkinc(phi0 - n * np.pi, m) + 2 * n * ellipk(m)
    sn, cn, dn, _ = ellipj(rate * t + u0, m)
    out = np.empty((t.size, 3))
    out[:, order[i_cn]] = amp_cn * cn
    out[:, order[i_sn]] = amp_sn * sn
    out[:, order[i_dn]] = s_dn * amp_dn * dn
    return out


def euler_rhs(moments, rotor, torque):
    """f(t, y) for SciPy: J ω̇ = M(t, ω) − ω × (J ω + k), written out component by component,
    plus q̇ = ½ q ⊗ (0, ω) when y has 7 components."""
    A1, A2, A3 = moments
    k1, k2, k3 = rotor

    def f(t, y):
        p, q, r = y[:3]
        M1, M2, M3 = torque(t, y[:3])
        G1, G2, G3 = A1 * p + k1, A2 * q + k2, A3 * r + k3
        dp = (M1 - (q * G3 - r * G2)) / A1
        dq = (M2 - (r * G1 - p * G3)) / A2
        dr = (M3 - (p * G2 - q * G1)) / A3
        if len(y) == 3:
            return [dp, dq, dr]
        w, x, yy, z = y[3:]
        return [dp, dq, dr,
                0.5 * (-x * p - yy * q - z * r),
                0.5 * (w * p + yy * r - z * q),
                0.5 * (w * q + z * p - x * r),
                0.5 * (w * r + x * q - yy * p)]

    return f


def rotation(q):
    """R(q): body → inertial, q = (w, x, y, z) normalised first (x_inertial = R x_body)."""
    w, x, y, z = np.asarray(q, float) / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def quaternion_rate(q, w):
    """q̇ = ½ q ⊗ (0, ω), ω in body axes."""
    qw, qx, qy, qz = q
    p, r2, r3 = w
    return 0.5 * np.array([-(qx * p + qy * r2 + qz * r3), qw * p + qy * r3 - qz * r2,
                           qw * r2 + qz * p - qx * r3, qw * r3 + qx * r2 - qy * p])


def scipy_reference(moments, rotor, torque, y0, t_eval, rtol=1e-12, atol=1e-14):
    """A SciPy DOP853 run at tight tolerance: the reference for forced cases."""
    sol = solve_ivp(euler_rhs(moments, rotor, torque), (t_eval[0], t_eval[-1]), y0, method="DOP853",
                    t_eval=t_eval, rtol=rtol, atol=atol)
    assert sol.success, sol.message
    return sol.y.T


def cavity_torque(w, moments, kappa):
    """Chernousko's viscous-cavity torque for P = P0·I, κ = ρP0/ν (paper 002 eq. (1))."""
    A, B, C = moments
    p, q, r = w
    k = kappa / (A * B * C)
    return np.array([
        k * p * (C * (A - C) * (A + C - B) * r * r + B * (A - B) * (A + B - C) * q * q),
        k * q * (A * (B - A) * (B + A - C) * p * p + C * (B - C) * (B + C - A) * r * r),
        k * r * (B * (C - B) * (C + B - A) * q * q + A * (C - A) * (C + A - B) * p * p),
    ])


def damper_torque_symmetric(w, A, C, mass_arm2, omega2, lam):
    """Paper 001 eqs. (2)–(3): L = μρ² C (A²p² + A²q² + C²r²)/(A³Ω²), S = μρ²λ C³(A − C)/(A⁴Ω⁴)."""
    p, q, r = w
    L = mass_arm2 / omega2 * C / A**3 * (A * A * (p * p + q * q) + C * C * r * r)
    S = mass_arm2 * lam / omega2**2 * C**3 * (A - C) / A**4
    return np.array([L * q * r + S * p * r**4, -L * p * r + S * q * r**4, -(A / C) * S * r**3 * (p * p + q * q)])


def damper_torque_series(w, moments, arm, mass, omega2, lam, order=6):
    """The quasi-static reduction evaluated by Taylor series along the unperturbed Euler flow
    (any J): u1 = −(ω(ω·d0) − d0|ω|² + ω̇ × d0)/Ω², u2 = −(λ/Ω²) u̇1,
    ΔK(u) = μ[2(d0·u)ω − d0(u·ω) − u(d0·ω) + d0 × u̇], T = −(ΔK̇ + ω × ΔK), M = T(u1) + T(u2).
    Series arithmetic on coefficient arrays (row n: n-th normalised Taylor coefficient)."""
    J = np.asarray(moments, float)

    def cauchy(f, a, b):
        out = np.zeros((order + 1,) + np.shape(f(a[0], b[0])))
        for k in range(order + 1):
            for i in range(k + 1):
                out[k] += f(a[i], b[k - i])
        return out

    def der(a):
        out = np.zeros_like(a)
        out[:-1] = (np.arange(1, order + 1)[:, None]) * a[1:]
        return out

    W = np.zeros((order + 1, 3))
    W[0] = w
    for k in range(order):
        s = np.zeros(3)
        for i in range(k + 1):
            s += np.cross(J * W[i], W[k - i])
        W[k + 1] = s / J / (k + 1)
    D0 = np.zeros((order + 1, 3))
    D0[0] = [0.0, 0.0, arm]
    dot = lambda a, b: cauchy(np.dot, a, b)[:, None]  # noqa: E731
    smul = lambda s, a: cauchy(lambda x, y: x * y, s[:, 0], a)  # noqa: E731
    cross = lambda a, b: cauchy(np.cross, a, b)  # noqa: E731
    u1 = -(smul(dot(W, D0), W) - smul(dot(W, W), D0) + cross(der(W), D0)) / omega2
    u2 = -(lam / omega2) * der(u1)
    total = np.zeros(3)
    for u in (u1, u2):
        dK = mass * (2 * smul(dot(D0, u), W) - smul(dot(u, W), D0) - smul(dot(D0, W), u) + cross(D0, der(u)))
        total += -(der(dK)[0] + np.cross(W[0], dK[0]))
    return total


def moving_mass_rhs(moments, mu, rho, omega2, lam, damping=None):
    """The explicit body + point mass model (docs/papers/001_moving_mass.md §C), in vector form:
    state (ω, u, v), the mass at d = (0, 0, ρ) + u with velocity v relative to the body,
    J_B = J − diag(μρ², μρ², 0) the carrier's moments, K = J_B ω + μ d × (ω × d + v),
    R = −2 ω × v − ω × (ω × d) − Ω² u − λ v; linear resistance −Dω on the body if given."""
    JB = np.asarray(moments, float) - np.array([mu * rho**2, mu * rho**2, 0.0])
    D = np.zeros((3, 3)) if damping is None else np.asarray(damping, float)

    def f(t, y):
        w, u, v = y[:3], y[3:6], y[6:]
        d = np.array([0, 0, rho]) + u
        K = JB * w + mu * np.cross(d, np.cross(w, d) + v)
        R = -2 * np.cross(w, v) - np.cross(w, np.cross(w, d)) - omega2 * u - lam * v
        wd = (-D @ w - np.cross(w, K) - mu * (2 * (d @ v) * w - v * (d @ w) - d * (v @ w)) - mu * np.cross(d, R)) / JB
        return np.concatenate([wd, v, R - np.cross(wd, d)])
    return f


def attitude_reference(moments, rotor, torque, omega0, q0, t_eval, rtol=1e-13, atol=1e-14):
    """(ω, q) of the Euler equations and q̇ = ½ q ⊗ (0, ω) integrated here (euler_rhs, SciPy
    DOP853, never normalised during the run: the kinematics, not a projection), q normalised at
    the end and its sign aligned with q0's branch by continuity (q and −q are one rotation)."""
    y = scipy_reference(moments, rotor, torque, np.concatenate([omega0, q0]), np.asarray(t_eval, float), rtol, atol)
    y[:, 3:] /= np.linalg.norm(y[:, 3:], axis=1)[:, None]
    return y


def quaternion_distance(q, q_ref):
    """max over rows of |q − q_ref| with each row's sign aligned with the reference's."""
    q, q_ref = np.atleast_2d(q), np.atleast_2d(q_ref)
    return float(np.max(np.abs(q * np.sign(np.sum(q * q_ref, axis=1))[:, None] - q_ref)))
