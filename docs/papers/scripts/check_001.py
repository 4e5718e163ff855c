#!/usr/bin/env python3
"""check_001.py -- independent numerical check of paper 001
(Leshchenko & Kozachenko 2023, "Perturbed motions of a rigid body with a movable
mass in a resistive medium").  Self-contained: NumPy + SciPy only.

Reproduces every number quoted in docs/papers/001_moving_mass.md.
Run:  OMP_NUM_THREADS=1 python3 check_001.py        (about 1-2 minutes, one core)

Sections
  [1] reduced damper torque: closed forms (symmetric, triaxial) vs generic
      Taylor-mode quasi-static reduction; invariants of the reduced torque
  [2] explicit model (body + point mass on 3D spring/damper): invariants
  [3] explicit vs reduced: nutation-rate ratio vs condition (4) parameters,
      and vs the frequency-exact ratio R
  [4] paper's scenes: averaged (7), claims, condition (4), explicit model run
  [5] averaged vs full (reduced-torque) model, order in eps
"""
import os
os.environ.setdefault("OMP_NUM_THREADS", "1")
import time
import numpy as np
from scipy.integrate import solve_ivp

np.set_printoptions(precision=6, suppress=False)
T0 = time.time()
E3 = np.array([0.0, 0.0, 1.0])


# ----------------------------------------------------------------------------
# [1] Reduced (quasi-static) damper torque
# ----------------------------------------------------------------------------
def torque_medium(w, I, eps):
    """linear resistive medium torque  M = -eps * I w  (I: 3x3 tensor)"""
    return -eps * (np.asarray(I) @ w)


def torque_damper_sym(w, A, C, mrho2, Om2, lam):
    """Chernousko reduced torque, symmetric body J=diag(A,A,C), mass on axis.
    Returns (T_L, T_S): elastic (conservative) and dissipative parts.
      A p' + (C-A) q r = ... + L q r + S p r^4
      A q' + (A-C) p r = ... - L p r + S q r^4
      C r'             = ...          - (A/C) S r^3 (p^2+q^2)
      L = mrho2/Om2 * C/A^3 * (A^2 p^2 + A^2 q^2 + C^2 r^2)
      S = mrho2*lam/Om2^2 * C^3 (A-C)/A^4
    """
    p, q, r = w
    L = mrho2 / Om2 * C / A**3 * (A * A * (p * p + q * q) + C * C * r * r)
    S = mrho2 * lam / Om2**2 * C**3 * (A - C) / A**4
    TL = np.array([L * q * r, -L * p * r, 0.0])
    TS = np.array([S * p * r**4, S * q * r**4, -(A / C) * S * r**3 * (p * p + q * q)])
    return TL, TS


def torque_damper_triax(w, A, B, C, mrho2, Om2, lam):
    """Reduced damper torque for a triaxial body J=diag(A,B,C), attachment point
    on the principal axis z at distance rho (mrho2 = mu*rho^2). Exact expansion
    (sympy) of the quasi-static reduction; see the .md for the derivation."""
    p, q, r = w
    p2, q2, r2 = p * p, q * q, r * r
    kL = mrho2 / Om2
    kS = mrho2 * lam / Om2**2
    TL0 = kL * q * r * (
        p2 * (7*A**3 - 14*A**2*B + 2*A**2*C + 7*A*B**2 + 8*A*B*C - 9*A*C**2
              - 10*B**2*C + 10*B*C**2) / (A*B*C)
        - (q2 * (A**2*B**2 - 2*A**2*B*C - 2*A*B**3 + 4*A*B**2*C - 2*A*B*C**2
                 + B**4 - 2*B**3*C + B**2*C**2)
           + r2 * (-4*A**2*B*C + 3*A**2*C**2 + 4*A*B**2*C - 2*A*B*C**2
                   - 2*A*C**3 - B**2*C**2 + 2*B*C**3 - C**4)) / (A**2*B*C))
    TL1 = kL * p * r * (
        -q2 * (7*A**2*B - 10*A**2*C - 14*A*B**2 + 8*A*B*C + 10*A*C**2 + 7*B**3
               + 2*B**2*C - 9*B*C**2) / (A*B*C)
        + (p2 * (A**4 - 2*A**3*B - 2*A**3*C + A**2*B**2 + 4*A**2*B*C + A**2*C**2
                 - 2*A*B**2*C - 2*A*B*C**2)
           + r2 * (4*A**2*B*C - A**2*C**2 - 4*A*B**2*C - 2*A*B*C**2 + 2*A*C**3
                   + 3*B**2*C**2 - 2*B*C**3 - C**4)) / (A*B**2*C))
    TS0 = kS * p * (
        -2*q2*r2*(A - B)*(12*A**2*B - 13*A**2*C - 12*A*B**2 + 10*A*B*C + 2*A*C**2
                          + 11*B**2*C - 22*B*C**2 + 11*C**3) / (A**2*B*C)
        - p2*q2*(A - B)*(5*A**3 - 10*A**2*B + 4*A**2*C + 5*A*B**2 + 4*A*B*C
                         - 9*A*C**2 - 8*B**2*C + 8*B*C**2) / (A*B*C**2)
        + 2*p2*r2*(A - B)*(A - C)*(3*A**2 - 3*A*B + A*C + 4*B*C - 4*C**2) / (A*B**2*C)
        + r2*r2*(A - C)*(4*A**2*B - 3*A**2*C - 4*A*B**2 + 2*A*B*C + 2*A*C**2
                         + B**2*C - 2*B*C**2 + C**3) / (A**2*B**2)
        + q2*q2*B*(A - B)*(A - B + C)**2 / (A**2*C**2))
    TS1 = kS * q * (
        -2*p2*r2*(A - B)*(12*A**2*B - 11*A**2*C - 12*A*B**2 - 10*A*B*C + 22*A*C**2
                          + 13*B**2*C - 2*B*C**2 - 11*C**3) / (A*B**2*C)
        + p2*q2*(A - B)*(5*A**2*B - 8*A**2*C - 10*A*B**2 + 4*A*B*C + 8*A*C**2
                         + 5*B**3 + 4*B**2*C - 9*B*C**2) / (A*B*C**2)
        + 2*q2*r2*(A - B)*(B - C)*(3*A*B - 4*A*C - 3*B**2 - B*C + 4*C**2) / (A**2*B*C)
        - r2*r2*(B - C)*(4*A**2*B - A**2*C - 4*A*B**2 - 2*A*B*C + 2*A*C**2
                         + 3*B**2*C - 2*B*C**2 - C**3) / (A**2*B**2)
        - p2*p2*A*(A - B)*(A - B - C)**2 / (B**2*C**2))
    TS2 = kS * r * (A - B - C) * (A - B + C) * (
        p2 * r2 * (A - C) / (A*B**2) + q2 * r2 * (B - C) / (A**2*B))
    return np.array([TL0, TL1, 0.0]), np.array([TS0, TS1, TS2])


# --- generic Taylor-mode reduction (any J, any attachment vector d0) ---------
def _cross_s(a, b):
    n = a.shape[0]
    c = np.zeros_like(a)
    for k in range(n):
        for i in range(k + 1):
            c[k] += np.cross(a[i], b[k - i])
    return c


def _dot_s(a, b):
    n = a.shape[0]
    c = np.zeros(n)
    for k in range(n):
        for i in range(k + 1):
            c[k] += a[i] @ b[k - i]
    return c


def _smul(s, a):  # scalar series * vector series
    n = a.shape[0]
    c = np.zeros_like(a)
    for k in range(n):
        for i in range(k + 1):
            c[k] += s[i] * a[k - i]
    return c


def _der(a):
    n = a.shape[0]
    c = np.zeros_like(a)
    for k in range(n - 1):
        c[k] = (k + 1) * a[k + 1]
    return c


def torque_damper_taylor(w, Jd, d0, mu, Om2, lam, N=6):
    """Quasi-static reduction evaluated by Taylor series along the unperturbed
    Euler flow  J w' = (J w) x w.  u1 = -(w x (w x d0) + w' x d0)/Om2,
    u2 = -(lam/Om2) u1',  T(u) = -(dK/dt + w x dK),
    dK(u) = mu[2(d0.u) w - d0 (u.w) - u (d0.w) + d0 x u'] .
    Returns (T_L, T_S) = (T(u1), T(u2))."""
    Jd = np.asarray(Jd, float)
    W = np.zeros((N + 1, 3))
    W[0] = w
    for k in range(N):
        s = np.zeros(3)
        for i in range(k + 1):
            s += np.cross(Jd * W[i], W[k - i])
        W[k + 1] = s / Jd / (k + 1)
    D0 = np.zeros((N + 1, 3))
    D0[0] = d0
    Wd = _der(W)
    u1 = -(_smul(_dot_s(W, D0), W) - _smul(_dot_s(W, W), D0) + _cross_s(Wd, D0)) / Om2
    u2 = -(lam / Om2) * _der(u1)
    out = []
    for u in (u1, u2):
        ud = _der(u)
        dK = mu * (2 * _smul(_dot_s(D0, u), W) - _smul(_dot_s(u, W), D0)
                   - _smul(_dot_s(D0, W), u) + _cross_s(D0, ud))
        out.append(-(_der(dK)[0] + np.cross(W[0], dK[0])))
    return out[0], out[1]


def section1():
    print("\n[1] reduced damper torque: closed forms vs Taylor-mode reduction")
    rng = np.random.default_rng(1)
    mu, rho, Om2, lam = 0.3, 1.7, 50.0, 7.0
    err_sym = err_tri = 0.0
    for _ in range(20):
        w = rng.normal(size=3)
        A, C = rng.uniform(0.5, 3, 2)
        B = rng.uniform(0.5, 3)
        tl, ts = torque_damper_sym(w, A, C, mu * rho**2, Om2, lam)
        TL, TS = torque_damper_taylor(w, [A, A, C], rho * E3, mu, Om2, lam)
        err_sym = max(err_sym, np.abs(tl - TL).max() / np.abs(TL).max(),
                      np.abs(ts - TS).max() / np.abs(TS).max())
        tl, ts = torque_damper_triax(w, A, B, C, mu * rho**2, Om2, lam)
        TL, TS = torque_damper_taylor(w, [A, B, C], rho * E3, mu, Om2, lam)
        err_tri = max(err_tri, np.abs(tl - TL).max() / np.abs(TL).max(),
                      np.abs(ts - TS).max() / np.abs(TS).max())
    print(f"  max rel. diff closed-form symmetric vs Taylor-mode : {err_sym:.2e}")
    print(f"  max rel. diff closed-form triaxial vs Taylor-mode  : {err_tri:.2e}")
    # invariants of the symmetric reduced torque
    w = np.array([0.7, -0.4, 1.1])
    A, C = 1.5, 1.0
    tl, ts = torque_damper_sym(w, A, C, 1.0, 100.0, 98.0)
    G = np.array([A, A, C]) * w
    print(f"  symmetric: G.T_L={G@tl:.1e}  w.T_L={w@tl:.1e}  G.T_S={G@ts:.1e}  "
          f"w.T_S={w@ts:.3e} (<=0 required)")
    # triaxial: G.T is not zero pointwise, it is -d/dt(G.dK) (zero mean)
    tl, ts = torque_damper_triax(w, 1.5, 1.2, 1.0, 1.0, 100.0, 98.0)
    G = np.array([1.5, 1.2, 1.0]) * w
    print(f"  triaxial (1.5,1.2,1): G.T_L={G@tl:.3e}  G.T_S={G@ts:.3e} (nonzero pointwise)")
    # planar-constrained mass gives a different L: (A^2 a^2 - C^2 r^2) instead of |G|^2
    return err_sym, err_tri


# ----------------------------------------------------------------------------
# [2] Explicit model: rigid body + point mass on isotropic 3D spring + damper
# ----------------------------------------------------------------------------
class Explicit:
    """State y = (w[0:3], u[3:6], v[6:9]) in body axes.
    A, C: principal moments of the WHOLE system (mass at rest position included)
    about the system centre of mass; mu = reduced mass m M/(m+M); rho = distance
    from body centre of mass to attachment point (on z); Om2 = c/mu; lam = delta/mu.
    Medium torque -eps*I*w acts on the body."""

    def __init__(self, A, C, mu, rho, Om2, lam, eps=0.0, I=None):
        self.A, self.C, self.mu, self.rho = A, C, mu, rho
        self.Om2, self.lam, self.eps = Om2, lam, eps
        self.I = np.zeros((3, 3)) if I is None else np.asarray(I, float)
        self.JB = np.array([A - mu * rho**2, A - mu * rho**2, C])
        assert self.JB.min() > 0, "A must exceed mu*rho^2"
        self.d0 = rho * E3

    def rhs(self, t, y):
        # scalar arithmetic (np.cross is slow for 3-vectors)
        p, q, r, u1, u2, u3, v1, v2, v3 = y
        mu, Om2, lam = self.mu, self.Om2, self.lam
        J1, J2, J3 = self.JB
        d1, d2, d3 = u1, u2, self.rho + u3
        # s = w x d + v ;  K = JB w + mu d x s
        s1 = q * d3 - r * d2 + v1
        s2 = r * d1 - p * d3 + v2
        s3 = p * d2 - q * d1 + v3
        K1 = J1 * p + mu * (d2 * s3 - d3 * s2)
        K2 = J2 * q + mu * (d3 * s1 - d1 * s3)
        K3 = J3 * r + mu * (d1 * s2 - d2 * s1)
        # R = -2 w x v - w x (w x d) - Om2 u - lam v
        wd_ = p * d1 + q * d2 + r * d3
        ww = p * p + q * q + r * r
        R1 = -2 * (q * v3 - r * v2) - (p * wd_ - d1 * ww) - Om2 * u1 - lam * v1
        R2 = -2 * (r * v1 - p * v3) - (q * wd_ - d2 * ww) - Om2 * u2 - lam * v2
        R3 = -2 * (p * v2 - q * v1) - (r * wd_ - d3 * ww) - Om2 * u3 - lam * v3
        dv = d1 * v1 + d2 * v2 + d3 * v3
        vw = v1 * p + v2 * q + v3 * r
        I = self.I
        e = self.eps
        M1 = -e * (I[0, 0] * p + I[0, 1] * q + I[0, 2] * r)
        M2 = -e * (I[1, 0] * p + I[1, 1] * q + I[1, 2] * r)
        M3 = -e * (I[2, 0] * p + I[2, 1] * q + I[2, 2] * r)
        f1 = M1 - (q * K3 - r * K2) - mu * (2 * dv * p - v1 * wd_ - d1 * vw) - mu * (d2 * R3 - d3 * R2)
        f2 = M2 - (r * K1 - p * K3) - mu * (2 * dv * q - v2 * wd_ - d2 * vw) - mu * (d3 * R1 - d1 * R3)
        f3 = M3 - (p * K2 - q * K1) - mu * (2 * dv * r - v3 * wd_ - d3 * vw) - mu * (d1 * R2 - d2 * R1)
        a1, a2, a3 = f1 / J1, f2 / J2, f3 / J3
        # v' = R - w' x d
        return np.array([a1, a2, a3, v1, v2, v3,
                         R1 - (a2 * d3 - a3 * d2),
                         R2 - (a3 * d1 - a1 * d3),
                         R3 - (a1 * d2 - a2 * d1)])

    def rhs_vec(self, t, y):
        """reference (vector) form of the same equations, used to test rhs"""
        w, u, v = y[0:3], y[3:6], y[6:9]
        mu = self.mu
        d = self.d0 + u
        K = self.JB * w + mu * np.cross(d, np.cross(w, d) + v)
        R = -2 * np.cross(w, v) - np.cross(w, np.cross(w, d)) - self.Om2 * u - self.lam * v
        rhs_w = (-self.eps * (self.I @ w) - np.cross(w, K)
                 - mu * (2 * (d @ v) * w - v * (d @ w) - d * (v @ w))
                 - mu * np.cross(d, R))
        wd = rhs_w / self.JB
        vd = R - np.cross(wd, d)
        return np.concatenate([wd, v, vd])

    def K(self, y):
        w, u, v = y[0:3], y[3:6], y[6:9]
        d = self.d0 + u
        return self.JB * w + self.mu * np.cross(d, np.cross(w, d) + v)

    def energy(self, y):
        w, u, v = y[0:3], y[3:6], y[6:9]
        d = self.d0 + u
        return (0.5 * w @ (self.JB * w) + 0.5 * self.mu * np.sum((np.cross(w, d) + v)**2)
                + 0.5 * self.mu * self.Om2 * (u @ u))

    def power(self, y):  # exact dE/dt
        w, v = y[0:3], y[6:9]
        return -self.eps * w @ (self.I @ w) - self.mu * self.lam * (v @ v)

    def quasi_static_state(self, w):
        """u, v of the forced quasi-static motion (u = u1+u2, v = u1'+u2')"""
        N = 4
        Jd = np.array([self.A, self.A, self.C])
        W = np.zeros((N + 1, 3)); W[0] = w
        for k in range(N):
            s = np.zeros(3)
            for i in range(k + 1):
                s += np.cross(Jd * W[i], W[k - i])
            W[k + 1] = s / Jd / (k + 1)
        D0 = np.zeros((N + 1, 3)); D0[0] = self.d0
        u1 = -(_smul(_dot_s(W, D0), W) - _smul(_dot_s(W, W), D0)
               + _cross_s(_der(W), D0)) / self.Om2
        u = u1 - self.lam / self.Om2 * _der(u1)
        return u[0], _der(u)[0]


def section2():
    print("\n[2] explicit model invariants (Radau, rtol=1e-10, atol=1e-12; t in [0,40])")
    res = {}
    rng = np.random.default_rng(0)
    M = Explicit(A=1.0, C=1.6, mu=0.18, rho=1.0, Om2=30.0, lam=5.0, eps=0.1,
                 I=rng.random((3, 3)))
    y = rng.random(9)
    print(f"  scalar rhs vs vector rhs: max diff {np.abs(M.rhs(0, y) - M.rhs_vec(0, y)).max():.1e}")
    for tag, eps, lam, Om2 in (("no dissipation", 0.0, 0.0, 30.0),
                               ("damper only", 0.0, 5.0, 30.0),
                               ("stiff damper", 0.0, 400.0, 2000.0),
                               ("damper+medium", 0.1, 5.0, 30.0)):
        M = Explicit(A=1.0, C=1.6, mu=0.18, rho=1.0, Om2=Om2, lam=lam, eps=eps,
                     I=[[1.0, 0.1, 0.0], [0.1, 0.8, 0.05], [0.0, 0.05, 0.6]])
        y0 = np.concatenate([[0.6, 0.2, 1.0], [0.05, -0.02, 0.03], [0.0, 0.1, 0.0], [0.0]])

        def f(t, y):  # augmented with W(t) = int_0^t P dt  (P = exact dE/dt)
            return np.append(M.rhs(t, y[:9]), M.power(y[:9]))
        ts = np.linspace(0, 40, 801)
        sol = solve_ivp(f, (0, 40), y0, method="Radau", rtol=1e-10, atol=1e-12, t_eval=ts)
        Kn = np.array([np.linalg.norm(M.K(y)) for y in sol.y[:9].T])
        E = np.array([M.energy(y) for y in sol.y[:9].T])
        bal = E - E[0] - sol.y[9]
        dE = np.diff(E)
        print(f"  {tag:15s}: max||K|-|K0||/|K0| = {np.abs(Kn-Kn[0]).max()/Kn[0]:.1e}, "
              f"max dE/sample = {dE.max():+.1e}, |E-E0-int P| <= {np.abs(bal).max():.1e}, "
              f"E(40)/E(0) = {E[-1]/E[0]:.4f}, nfev = {sol.nfev}")
        res[tag] = (np.abs(Kn - Kn[0]).max() / Kn[0], dE.max(), np.abs(bal).max())
    return res


# ----------------------------------------------------------------------------
# [3] explicit vs reduced: nutation decay rate
# ----------------------------------------------------------------------------
def reduced_rhs_sym(A, C, mrho2, Om2, lam, eps=0.0, I=None):
    I = np.zeros((3, 3)) if I is None else np.asarray(I, float)
    Jd = np.array([A, A, C])

    def f(t, w):
        tl, ts = torque_damper_sym(w, A, C, mrho2, Om2, lam)
        return (np.cross(Jd * w, w) - eps * (I @ w) + tl + ts) / Jd
    return f


def power_exact(w, A, C, mrho2, Om2, lam, rho=1.0):
    """Frequency-exact quasi-steady dissipation of the damper for the symmetric
    body (u linear, a and r frozen).  In the frame F rotating with (p,q) the
    mass is at rest:  (Om2 I + [W x]^2 + lam*nu [e3 x]) u = -W x (W x d0),
    W = (p, q, C r/A) = G/A,  nu = (C-A) r/A;  power = mu*lam*nu^2*|u_perp|^2."""
    p, q, r = w
    W = np.array([p, q, C * r / A])
    nu = (C - A) * r / A
    Wx = np.array([[0, -W[2], W[1]], [W[2], 0, -W[0]], [-W[1], W[0], 0]])
    e3x = np.array([[0, -1.0, 0], [1.0, 0, 0], [0, 0, 0]])
    M = Om2 * np.eye(3) + Wx @ Wx + lam * nu * e3x
    d0 = rho * E3
    u = np.linalg.solve(M, -np.cross(W, np.cross(W, d0)))
    mu = mrho2 / rho**2
    return mu * lam * nu**2 * (u[0]**2 + u[1]**2)


def power_reduced(w, A, C, mrho2, Om2, lam):
    tl, ts = torque_damper_sym(w, A, C, mrho2, Om2, lam)
    return -(w @ (tl + ts))


def nutation_slope(t, lntan):
    return np.polyfit(t, lntan, 1)[0]


def explicit_vs_reduced(A, C, mu, rho, Om2, lam, w0, Tmin=30.0, Tmax=600.0, dlt=0.08):
    mrho2 = mu * rho**2
    M = Explicit(A, C, mu, rho, Om2, lam)
    Jd = np.array([A, A, C])
    Pr = power_reduced(w0, A, C, mrho2, Om2, lam)
    Pe = power_exact(w0, A, C, mrho2, Om2, lam, rho)
    a0, r0 = np.hypot(w0[0], w0[1]), w0[2]
    G2 = A * A * a0 * a0 + C * C * r0 * r0
    rate_e = Pe * G2 / (C * (A - C) * A * a0 * a0 * r0 * r0)
    T = float(np.clip(abs(dlt / rate_e), Tmin, Tmax))
    # transient: free modes decay like exp(-lam t/2) (underdamped) or exp(-Om2 t/lam)
    slow = lam / 2 if lam * lam < 4 * Om2 else (lam / 2 - np.sqrt(lam * lam / 4 - Om2))
    t0 = float(min(12.0 / slow, 150.0))
    u0, v0 = M.quasi_static_state(w0)
    te = np.linspace(t0, t0 + T, 400)
    se = solve_ivp(M.rhs, (0, t0 + T), np.concatenate([w0, u0, v0]), method="Radau",
                   rtol=1e-9, atol=1e-12, t_eval=te)
    K = np.array([M.K(y) for y in se.y.T])
    lt_e = np.log(np.hypot(K[:, 0], K[:, 1]) / np.abs(K[:, 2]))
    sr = solve_ivp(reduced_rhs_sym(A, C, mrho2, Om2, lam), (0, t0 + T), w0,
                   method="DOP853", rtol=1e-11, atol=1e-13, t_eval=te)
    G = Jd[:, None] * sr.y
    lt_r = np.log(np.hypot(G[0], G[1]) / np.abs(G[2]))
    ratio = nutation_slope(te, lt_e) / nutation_slope(te, lt_r)
    wm = sr.y[:, len(te) // 2]
    nu = (C - A) * wm[2] / A
    RL = 1.0 / (1.0 + (lam * nu / Om2)**2)      # damped-oscillator (Lorentzian) factor
    return ratio, RL, Pe / Pr, T, t0, se.nfev


def section3():
    print("\n[3] explicit (Radau) vs reduced model: nutation rate d ln tan(theta)/dt")
    A, C, mu, rho = 1.0, 1.6, 0.18, 1.0
    w0 = np.array([0.8, 0.0, 1.0])      # tan(theta0)=A a/(C r)=0.5, |w|=1.28
    wn = np.linalg.norm(w0)
    nu = (C - A) * w0[2] / A
    Wf2 = (A * A * 0.64 + C * C) / A**2
    print(f"  body A={A}, C={C}, mu*rho^2={mu*rho**2} (J_body=diag({A-mu*rho**2},{A-mu*rho**2},{C})),"
          f" w0={w0.tolist()}, |w|={wn:.3f}, nu=(C-A)r/A={nu:.2f}, |G|/A={np.sqrt(Wf2):.3f}")
    print("   Om2     lam  | Om2/(lam|w|)  lam/|w| | lam|nu|/Om2 (G/A)^2/Om2 |"
          " ratio expl/red  rel.err(red) | R_L  c=(ratio/R_L-1)/((G/A)^2/Om2) |  T   nfev")
    pts = [(30, 0.3), (30, 1), (30, 3), (30, 10), (30, 30), (30, 100),
           (10, 3), (100, 3), (300, 3),
           (12.8, 1), (128, 10), (384, 30),
           (100, 98 / 1.28), (100, 98), (1000, 98), (1e4, 98)]
    rows = []
    for Om2, lam in pts:
        t1 = time.time()
        ratio, RL, R0, T, t0, nfev = explicit_vs_reduced(A, C, mu, rho, Om2, lam, w0)
        rows.append((Om2, lam, ratio, RL))
        print(f"  {Om2:7.1f} {lam:6.2f} | {Om2/(lam*wn):9.3f} {lam/wn:9.2f} | "
              f"{lam*abs(nu)/Om2:9.3f} {Wf2/Om2:10.4f}  | {ratio:10.4f} {abs(ratio-1):10.2e}    "
              f"| {RL:.4f} {(ratio/RL-1)/(Wf2/Om2):6.3f} | {T:4.0f} {nfev:6d} ({time.time()-t1:.1f}s)")
    r = np.array([(row[2] / row[3] - 1) for row in rows])
    g = np.array([Wf2 / row[0] for row in rows])
    fit = np.array([row[2] for row in rows]) / (np.array([row[3] for row in rows]) * (1 + 0.55 * g)) - 1
    print(f"  law ratio = (1 + c (G/A)^2/Om2)*R_L with c=0.55: max rel. deviation {np.abs(fit).max():.3f}")
    return rows


# ----------------------------------------------------------------------------
# [4] the paper's scenes
# ----------------------------------------------------------------------------
def averaged_xy(A, C, I1, I3, eps, S):
    """system (7): x=a^2, y=r^2 (valid while r>0)"""
    def f(t, z):
        x, y = z
        return [-2 * x * (eps * I1 / A - S * y * y / A),
                -2 * y * (eps * I3 / C + A * S * x * y / C**2)]
    return f


def averaged_xy_cross(A, C, I1, I3, eps, S, mrho2, Om2):
    """(7) plus the eps x elastic cross term (formally O(eps/Om2), dropped in the
    paper):  a a' += 3 eps mrho2 a^2 (2 A^2 I1 a^2 + (A C I3 + C^2 I1) r^2)/(A^4 Om2)"""
    f7 = averaged_xy(A, C, I1, I3, eps, S)

    def f(t, z):
        x, y = z
        dx, dy = f7(t, z)
        return [dx + 6 * eps * mrho2 * x * (2 * A * A * I1 * x + (A * C * I3 + C * C * I1) * y)
                / (A**4 * Om2), dy]
    return f


def S_coef(A, C, mrho2, Om2, lam):
    return mrho2 * lam / Om2**2 * C**3 * (A - C) / A**4


def section4():
    print("\n[4] paper's scenes: x(0)=y(0)=1, rho=m=1, lam=98, Om=10, eps=0.1, I3=1")
    eps, I3, mrho2, Om2, lam = 0.1, 1.0, 1.0, 100.0, 98.0
    tq = np.array([10.0, 20.0, 40.0])
    out = {}
    for A, C, I1 in ((1.5, 1, 1.25), (1.5, 1, 2.5), (4, 2, 1.25), (4, 2, 2.5),
                     (1.5, 1, 1.5), (4, 2, 2.0)):
        S = S_coef(A, C, mrho2, Om2, lam)
        w0 = np.array([1.0, 0.0, 1.0])
        wn = np.sqrt(2.0)
        nu = (C - A) / A
        L0 = mrho2 / Om2 * C / A**3 * (A * A + C * C)
        ts = np.linspace(0, 60, 6001)
        sol = solve_ivp(averaged_xy(A, C, I1, I3, eps, S), (0, 60), [1.0, 1.0],
                        method="DOP853", rtol=1e-12, atol=1e-14, t_eval=ts)
        x, y = sol.y
        x0 = np.exp(-2 * eps * I1 * ts / A)       # medium only (S = 0)
        y0 = np.exp(-2 * eps * I3 * ts / C)
        sgn = np.sign(x[1:] - y[1:])
        rel = {"y faster": bool(np.all(sgn > 0)), "x faster": bool(np.all(sgn < 0))}
        print(f"  A={A} C={C} I1={I1}: A/C={A/C:.3f} I1/I3={I1/I3:.3f}; S={S:.4e}, L(0)={L0:.4e},"
              f" damper/medium at t=0: S/(eps I1)={S/(eps*I1):.4f}, (A S/C^2)/(eps I3/C)={A*S/C/(eps*I3):.4f}")
        print(f"     cond.(4): Om2/(lam|w0|)={Om2/(lam*wn):.3f}, lam|w0|/|w0|^2={lam/wn:.1f};"
              f" lam|nu|/Om2={lam*abs(nu)/Om2:.3f} -> R_L={1/(1+(lam*nu/Om2)**2):.3f};"
              f" |w0|^2/Om2={2/Om2:.3f}; |w| at which Om2=lam|w|: {Om2/lam:.3f}")
        cross = 3 * mrho2 * (2 * A * A * I1 + A * C * I3 + C * C * I1) / (A**3 * I1 * Om2)
        print(f"     |G0|^2/(A^2 Om2)={(A*A+C*C)/(A*A*Om2):.4f}; L(0)/|C-A|={L0/abs(C-A):.4f};"
              f" mu rho^2/A={mrho2/A:.3f}; eps-elastic cross term / medium rate of a at t=0: {cross:.4f}")
        xi = np.interp(tq, ts, x); yi = np.interp(tq, ts, y)
        print(f"     (7): x(10,20,40)={np.array2string(xi, precision=5)}, y={np.array2string(yi, precision=5)};"
              f" max|x-x_medium|={np.abs(x-x0).max():.2e}, max|y-y_medium|={np.abs(y-y0).max():.2e};"
              f" max|x-y|={np.abs(x-y).max():.3e}; sign(x-y) for t>0: {rel}")
        out[(A, C, I1)] = (S, xi, yi, np.abs(x - y).max())
    # x = y requires S = 0 as well as A/C = I1/I3:
    A, C, I1 = 1.5, 1.0, 1.5
    for S in (0.0, S_coef(A, C, mrho2, Om2, lam), 0.01):
        sol = solve_ivp(averaged_xy(A, C, I1, I3, eps, S), (0, 60), [1.0, 1.0],
                        method="DOP853", rtol=1e-12, atol=1e-14, t_eval=np.linspace(0, 60, 601))
        print(f"  x=y test A/C=I1/I3=1.5, S={S:.3e}: max|x-y| = {np.abs(sol.y[0]-sol.y[1]).max():.3e}")
    # 'larger A/C -> slower decay' is about A and C themselves, not A/C:
    for A, C in ((1.5, 1.0), (1.5, 0.75), (3.0, 2.0)):
        I1 = 1.25
        S = S_coef(A, C, mrho2, Om2, lam)
        sol = solve_ivp(averaged_xy(A, C, I1, I3, eps, S), (0, 20), [1.0, 1.0],
                        method="DOP853", rtol=1e-12, atol=1e-14)
        print(f"  A/C test: A={A} C={C} (A/C={A/C:.2f}) I1=1.25: x(20)={sol.y[0,-1]:.4f} y(20)={sol.y[1,-1]:.4f}")

    # explicit model of the paper's scene (M >> m: mu=m=1, rho=1), 3D mass
    print("  explicit model of the scene (mu=m=1, rho=1, J_body=diag(A-1,A-1,C)), "
          "w0=(1,0,1), u,v quasi-static; medium torque -eps diag(I1,I1,I3) w on the body")
    for A, C, I1 in ((1.5, 1, 1.25), (4, 2, 2.5)):
        M = Explicit(A, C, 1.0, 1.0, Om2, lam, eps=eps, I=np.diag([I1, I1, I3]))
        w0 = np.array([1.0, 0.0, 1.0])
        u0, v0 = M.quasi_static_state(w0)
        sol = solve_ivp(M.rhs, (0, 40), np.concatenate([w0, u0, v0]), method="Radau",
                        rtol=1e-10, atol=1e-12, t_eval=tq)
        xe = sol.y[0]**2 + sol.y[1]**2; ye = sol.y[2]**2
        S = S_coef(A, C, mrho2, Om2, lam)
        sa = solve_ivp(averaged_xy(A, C, I1, I3, eps, S), (0, 40), [1.0, 1.0],
                       method="DOP853", rtol=1e-12, atol=1e-14, t_eval=tq)
        sc = solve_ivp(averaged_xy_cross(A, C, I1, I3, eps, S, mrho2, Om2), (0, 40), [1.0, 1.0],
                       method="DOP853", rtol=1e-12, atol=1e-14, t_eval=tq)
        x0 = np.exp(-2 * eps * I1 * tq / A); y0 = np.exp(-2 * eps * I3 * tq / C)
        # damper-induced change of ln x: explicit vs (7)
        dlx_e = np.log(xe / x0); dlx_a = np.log(sa.y[0] / x0)
        dly_e = np.log(ye / y0); dly_a = np.log(sa.y[1] / y0)
        print(f"   A={A} C={C} I1={I1}: explicit x={np.array2string(xe, precision=5)} y={np.array2string(ye, precision=5)}")
        print(f"        (7)      x={np.array2string(sa.y[0], precision=5)} y={np.array2string(sa.y[1], precision=5)}")
        print(f"        damper part of ln x: explicit {np.array2string(dlx_e, precision=5)} vs (7) {np.array2string(dlx_a, precision=5)};"
              f" ln y: {np.array2string(dly_e, precision=5)} vs {np.array2string(dly_a, precision=5)}")
        print(f"        ln(x_expl/x_(7)) = {np.array2string(np.log(xe/sa.y[0]), precision=5)};"
              f" with eps-elastic cross term: ln(x_expl/x_(7c)) = {np.array2string(np.log(xe/sc.y[0]), precision=5)}")
    # damper only (eps=0) on scene geometry: explicit vs (7) for the r-decay
    A, C = 1.5, 1.0
    M = Explicit(A, C, 1.0, 1.0, Om2, lam)
    w0 = np.array([1.0, 0.0, 1.0]); u0, v0 = M.quasi_static_state(w0)
    tt = np.array([10.0, 20.0, 40.0])
    sol = solve_ivp(M.rhs, (0, 40), np.concatenate([w0, u0, v0]), method="Radau",
                    rtol=1e-10, atol=1e-12, t_eval=tt)
    sa = solve_ivp(averaged_xy(A, C, 1.25, I3, 0.0, S_coef(A, C, mrho2, Om2, lam)), (0, 40),
                   [1.0, 1.0], method="DOP853", rtol=1e-12, atol=1e-14, t_eval=tt)
    print(f"  damper only (eps=0), A=1.5,C=1: 1-y explicit {np.array2string(1-sol.y[2]**2, precision=5)}"
          f" vs (7) {np.array2string(1-sa.y[1], precision=5)}  ratio {np.array2string((1-sol.y[2]**2)/(1-sa.y[1]), precision=4)}")
    return out


# ----------------------------------------------------------------------------
# [5] averaged vs full (reduced-torque) model, order in eps
# ----------------------------------------------------------------------------
def averaged_ar(A, C, Imat, eps, S):
    """(6) generalised: medium with full tensor I -> (I11+I22)/2, I33; damper S."""
    Ieq = 0.5 * (Imat[0][0] + Imat[1][1])
    I33 = Imat[2][2]

    def f(t, z):
        a, r = z
        return [-eps * Ieq / A * a + S / A * r**4 * a,
                -eps * I33 / C * r - A / C**2 * S * r**3 * a * a]
    return f


def section5():
    print("\n[5] averaged (a,r) vs full reduced-torque model, t in [0, 3/eps], rtol=1e-10")
    A, C = 1.0, 1.6
    Ifull = np.array([[1.2, 0.3, 0.2], [0.3, 0.7, -0.1], [0.2, -0.1, 0.5]])
    print(f"  A={A}, C={C}, a0=1, r0=1; damper scaled with eps: mu rho^2/Om2 = eps, "
          f"mu rho^2 lam/Om2^2 = eps (mrho2=1, Om2=1/eps, lam=1/eps); eig(I)={np.linalg.eigvalsh(Ifull).round(3)}")
    res = {}
    for tag, Im in (("full tensor I", Ifull), ("diag I, I11=I22", np.diag([0.95, 0.95, 0.5]))):
        errs = []
        for eps in (0.1, 0.05, 0.02, 0.01):
            mrho2, Om2, lam = 1.0, 1.0 / eps, 1.0 / eps
            S = S_coef(A, C, mrho2, Om2, lam)
            T = 3.0 / eps
            te = np.linspace(0, T, 3001)
            sf = solve_ivp(reduced_rhs_sym(A, C, mrho2, Om2, lam, eps, Im), (0, T), [1.0, 0.0, 1.0],
                           method="DOP853", rtol=1e-10, atol=1e-12, t_eval=te)
            sa = solve_ivp(averaged_ar(A, C, Im, eps, S), (0, T), [1.0, 1.0],
                           method="DOP853", rtol=1e-10, atol=1e-12, t_eval=te)
            ea = np.abs(np.hypot(sf.y[0], sf.y[1]) - sa.y[0]).max()
            er = np.abs(sf.y[2] - sa.y[1]).max()
            nu_end = (C - A) * sa.y[1][-1] / A
            errs.append((eps, ea, er))
            print(f"   {tag:16s} eps={eps:5.2f}: max|a-a_avg|={ea:.3e}  max|r-r_avg|={er:.3e}"
                  f"  a(T)={sa.y[0][-1]:.4f} r(T)={sa.y[1][-1]:.4f} nu(T)={nu_end:.3f}")
        e = np.array(errs)
        if e[:, 1].min() > 1e-8:
            pa = np.polyfit(np.log(e[:, 0]), np.log(e[:, 1]), 1)[0]
            pr = np.polyfit(np.log(e[:, 0]), np.log(e[:, 2]), 1)[0]
            print(f"   -> fitted order: a: {pa:.3f}, r: {pr:.3f}")
        res[tag] = e
    # slowly varying tensor I(tau) = I0 + tau*I1, tau = eps t (coefficients frozen in averaging)
    I1m = np.array([[0.5, -0.2, 0.0], [-0.2, 0.3, 0.1], [0.0, 0.1, 0.4]])
    errs = []
    Jd = np.array([A, A, C])
    for eps in (0.1, 0.05, 0.02, 0.01):
        mrho2, Om2, lam = 1.0, 1.0 / eps, 1.0 / eps
        S = S_coef(A, C, mrho2, Om2, lam)

        def ff(t, w):
            tl, ts = torque_damper_sym(w, A, C, mrho2, Om2, lam)
            return (np.cross(Jd * w, w) - eps * ((Ifull + eps * t * I1m) @ w) + tl + ts) / Jd

        def fa(t, z):
            a, r = z
            I = Ifull + eps * t * I1m
            return [-eps * 0.5 * (I[0, 0] + I[1, 1]) / A * a + S / A * r**4 * a,
                    -eps * I[2, 2] / C * r - A / C**2 * S * r**3 * a * a]
        T = 3.0 / eps
        te = np.linspace(0, T, 3001)
        sf = solve_ivp(ff, (0, T), [1.0, 0.0, 1.0], method="DOP853", rtol=1e-10, atol=1e-12, t_eval=te)
        sa = solve_ivp(fa, (0, T), [1.0, 1.0], method="DOP853", rtol=1e-10, atol=1e-12, t_eval=te)
        ea = np.abs(np.hypot(sf.y[0], sf.y[1]) - sa.y[0]).max()
        er = np.abs(sf.y[2] - sa.y[1]).max()
        errs.append((eps, ea, er))
        print(f"   I(tau)=I+tau*I1m   eps={eps:5.2f}: max|a-a_avg|={ea:.3e}  max|r-r_avg|={er:.3e}")
    e = np.array(errs)
    print(f"   -> fitted order: a: {np.polyfit(np.log(e[:,0]), np.log(e[:,1]), 1)[0]:.3f},"
          f" r: {np.polyfit(np.log(e[:,0]), np.log(e[:,2]), 1)[0]:.3f}")
    res["I(tau)"] = e
    return res


if __name__ == "__main__":
    section1()
    section2()
    section3()
    section4()
    section5()
    print(f"\nruntime so far {time.time()-T0:.1f} s")
