#!/usr/bin/env python3
"""Independent numerical check of paper 003 (Akulenko, Zinkevich, Kozachenko,
Leshchenko 2017): rigid body near the Lagrange case under a slowly varying
linear dissipative torque, averaged over the nutation phase.

Self-contained (NumPy + SciPy).  Reproduces every number quoted in
docs/papers/003_lagrange_top.md.  Run:  OMP_NUM_THREADS=1 python3 check_003.py
Optional argument "quick" skips the eps = 0.01 runs.
"""
import os
os.environ.setdefault("OMP_NUM_THREADS", "1")
import sys
import time
import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq
from scipy.special import ellipk, ellipe, ellipj, ellipkinc, elliprd, elliprf

T0 = time.time()
A, C, MU = 1.5, 1.0, 0.5          # paper's scene
A1 = B1 = 1.0                      # printed
A0 = B0 = 1.0                      # NOT printed in the paper: our choice
R0 = np.sqrt(3.0)
CASES = {1: 5.0, 2: 60.0, 3: 150.0}   # theta0 in degrees, p0 = q0 = 0

# ----------------------------------------------------------------------------
# Full model: state y = (p, q, r, g1, g2, g3, q0, q1, q2, q3)
#   A p' = (A - C) q r + mu g2 + eps M1
#   A q' = (C - A) p r - mu g1 + eps M2
#   C r' =                       eps M3
#   g'   = g x w        (g = upward vertical in body axes)
#   Q'   = 1/2 Q (x) (0, w)   (body->space quaternion, only for psi)
# ----------------------------------------------------------------------------

def full_rhs(t, y, eps, a0=A0, a1=A1, b0=B0, b1=B1, A=A, C=C, mu=MU):
    p, q, r, g1, g2, g3, w0, x, yy, z = y
    tau = eps * t
    a = a0 + a1 * tau
    b = b0 + b1 * tau
    dp = ((A - C) * q * r + mu * g2 - eps * a * p) / A
    dq = ((C - A) * p * r - mu * g1 - eps * a * q) / A
    dr = -eps * b * r / C
    dg1 = g2 * r - g3 * q
    dg2 = g3 * p - g1 * r
    dg3 = g1 * q - g2 * p
    # quaternion product Q (x) (0, w)
    dw0 = 0.5 * (-x * p - yy * q - z * r)
    dx = 0.5 * (w0 * p + yy * r - z * q)
    dy = 0.5 * (w0 * q + z * p - x * r)
    dz = 0.5 * (w0 * r + x * q - yy * p)
    return [dp, dq, dr, dg1, dg2, dg3, dw0, dx, dy, dz]


def quat_to_R(Q):
    w, x, y, z = Q / np.linalg.norm(Q)
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def euler_from_R(R):
    """z-x-z Euler angles (psi, theta, phi) of R = Rz(psi) Rx(theta) Rz(phi)."""
    theta = np.arctan2(np.hypot(R[0, 2], R[1, 2]), R[2, 2])
    psi = np.arctan2(R[0, 2], -R[1, 2])
    phi = np.arctan2(R[2, 0], R[2, 1])
    return psi, theta, phi


def initial_state(p, q, r, theta, phi, psi=0.0):
    g = [np.sin(theta) * np.sin(phi), np.sin(theta) * np.cos(phi), np.cos(theta)]
    # Q = qz(psi) qx(theta) qz(phi)
    def qz(a):
        return np.array([np.cos(a / 2), 0, 0, np.sin(a / 2)])
    def qx(a):
        return np.array([np.cos(a / 2), np.sin(a / 2), 0, 0])
    def qm(a, b):
        w1, x1, y1, z1 = a
        w2, x2, y2, z2 = b
        return np.array([w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2,
                         w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
                         w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
                         w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2])
    Q = qm(qm(qz(psi), qx(theta)), qz(phi))
    return np.array([p, q, r, *g, *Q])


def integrals(y, A=A, C=C, mu=MU):
    p, q, r, g1, g2, g3 = y[:6]
    G = A * (p * g1 + q * g2) + C * r * g3
    H = 0.5 * (A * (p * p + q * q) + C * r * r) + mu * g3
    return G, H, r

# ----------------------------------------------------------------------------
# Cubic, roots, map (G,H,r) <-> (u1,u2,u3)
# f(u) = A(2H - C r^2 - 2 mu u)(1 - u^2) - (G - C r u)^2 = 2 mu A (u-u1)(u-u2)(u-u3)
# ----------------------------------------------------------------------------

def sym(G, H, r, A=A, C=C, mu=MU):
    s1 = H / mu - C * r * r / (2 * mu) + C * C * r * r / (2 * A * mu)
    s2 = G * C * r / (A * mu) - 1.0
    s3 = -H / mu + C * r * r / (2 * mu) + G * G / (2 * A * mu)
    return s1, s2, s3


def roots(G, H, r, A=A, C=C, mu=MU):
    """u1 <= u2 <= 1 <= u3.  u3 by bracketing on [1, hi] using the factored cubic
    f(u) (f(1) = -(G - C r)^2 <= 0 exactly in floating point), then deflation
    u1 + u2 = s1 - u3, u1 u2 = s3 / u3 (u3 >= 1, no division problem)."""
    s1, s2, s3 = sym(G, H, r, A, C, mu)
    f = lambda u: (A * (2 * H - C * r * r - 2 * mu * u) * (1 - u * u) - (G - C * r * u) ** 2) / (2 * mu * A)
    hi = 2.0 + max(abs(s1), abs(s2), abs(s3))
    f1 = f(1.0)
    if f1 == 0.0 and (3 - 2 * s1 + s2) >= 0.0:   # u = 1 is the largest root
        u3 = 1.0
    else:
        u3 = brentq(f, 1.0, hi, xtol=1e-15, rtol=1e-15)
    B = s1 - u3
    Cq = s3 / u3
    disc = max(B * B - 4 * Cq, 0.0)
    sq = np.sqrt(disc)
    if B >= 0:
        u2 = 0.5 * (B + sq)
        u1 = Cq / u2 if u2 != 0 else 0.5 * (B - sq)
    else:
        u1 = 0.5 * (B - sq)
        u2 = Cq / u1 if u1 != 0 else 0.5 * (B + sq)
    u1, u2 = min(u1, u2), max(u1, u2)
    return u1, u2, u3


def from_roots(u1, u2, u3, sign_r, sign_R, A=A, C=C, mu=MU):
    """Paper's (2.5), derived independently (identical)."""
    s1 = u1 + u2 + u3
    s2 = u1 * u2 + u1 * u3 + u2 * u3
    s3 = u1 * u2 * u3
    R = sign_R * np.sqrt(max((1 - u1 ** 2) * (1 - u2 ** 2) * (u3 ** 2 - 1), 0.0))
    chi = sign_r * np.sqrt(A * mu)
    delta = np.sign(1 + s2)
    G = chi * delta * np.sqrt(max(s1 + s3 + R, 0.0))
    H = 0.5 * mu * ((s1) * (1 + A / C) + (R - s3) * (1 - A / C))
    r = chi / C * np.sqrt(max(s1 + s3 - R, 0.0))
    return G, H, r


def W_of_m(m):
    """<sn^2> = (K - E)/(m K) = R_D(0,1-m,1) / (3 R_F(0,1-m,1)); W(0)=1/2, W(1)=1."""
    if m >= 1.0:
        return 1.0
    return elliprd(0.0, 1.0 - m, 1.0) / (3.0 * elliprf(0.0, 1.0 - m, 1.0))


def nut(G, H, r, A=A, C=C, mu=MU):
    u1, u2, u3 = roots(G, H, r, A, C, mu)
    m = (u2 - u1) / (u3 - u1)
    m = min(max(m, 0.0), 1.0)
    alpha = np.sqrt(mu * (u3 - u1) / (2 * A))
    v = u1 + (u2 - u1) * W_of_m(m)
    return u1, u2, u3, m, alpha, v

# ----------------------------------------------------------------------------
# Averaged systems
# ----------------------------------------------------------------------------

def avg_rhs_GHr(tau, x, a0=A0, a1=A1, b0=B0, b1=B1):
    G, H, r = x
    a = a0 + a1 * tau
    b = b0 + b1 * tau
    v = nut(G, H, r)[5]
    dG = -a * (G - C * r * v) / A - b * r * v
    dH = -a * (2 * H - C * r * r - 2 * MU * v) / A - b * r * r
    dr = -b * r / C
    return [dG, dH, dr]


def avg_rhs_u(tau, uu, sign_r, sign_R, a0=A0, a1=A1, b0=B0, b1=B1):
    """Paper's (3.5) as printed (with (2.5) for G,H,r and fixed signs)."""
    u = list(uu)
    G, H, r = from_roots(*u, sign_r, sign_R)
    a = a0 + a1 * tau
    b = b0 + b1 * tau
    u1, u2, u3 = sorted(u)
    m = min(max((u2 - u1) / (u3 - u1), 0.0), 1.0)
    v = u3 - (u3 - u1) * ellipe(m) / ellipk(m) if m < 1 else u3
    out = []
    for i in range(3):
        ui, uj, uk = u[i], u[(i + 1) % 3], u[(i + 2) % 3]
        D = MU * (ui - uj) * (ui - uk)
        out.append(-1.0 / (A * D) * (
            a * ((G - C * r * ui) * (G - C * r * v) / A + (ui * ui - 1) * (2 * H - C * r * r - 2 * MU * v))
            + b * r * (G - C * r * ui) * (v - ui)))
    return out


def run_avg(G0, H0, r0, tau_max, n=401, **kw):
    ts = np.linspace(0, tau_max, n)
    sol = solve_ivp(lambda t, x: avg_rhs_GHr(t, x, **kw), (0, tau_max), [G0, H0, r0],
                    method="DOP853", rtol=1e-11, atol=1e-13, t_eval=ts)
    return ts, sol.y


def run_full(y0, eps, tau_max, n=None, **kw):
    tmax = tau_max / eps
    if n is None:
        n = int(40 * tmax) + 1       # dense sampling (nutation period >= ~5)
    ts = np.linspace(0, tmax, n)
    sol = solve_ivp(lambda t, y: full_rhs(t, y, eps, **kw), (0, tmax), y0,
                    method="DOP853", rtol=1e-11, atol=1e-13, t_eval=ts)
    return ts, sol.y


def hr(title):
    print("\n" + "=" * 78 + "\n" + title + "\n" + "=" * 78)

# ----------------------------------------------------------------------------
# 1. Torque sign, Euler-angle kinematics, integrals of the full model
# ----------------------------------------------------------------------------
hr("1. Full model: integrals conserved at eps = 0, Euler angles from gamma/quaternion")
y0 = initial_state(0.3, -0.2, 1.2, np.radians(40.0), np.radians(30.0), np.radians(10.0))
sol = solve_ivp(full_rhs, (0, 60), y0, args=(0.0,), method="DOP853", rtol=1e-12, atol=1e-14,
                dense_output=True)
tt = np.linspace(0, 60, 3001)
Y = sol.sol(tt)
GHr = np.array([integrals(Y[:, i]) for i in range(len(tt))])
print("max |G_z - G_z0| = %.2e, max |H - H0| = %.2e, max |r - r0| = %.2e" %
      tuple(np.max(np.abs(GHr - GHr[0]), axis=0)))
# gamma from quaternion = third row of R; compare with integrated gamma
dg = max(np.max(np.abs(quat_to_R(Y[6:, i])[2, :] - Y[3:6, i])) for i in range(len(tt)))
print("max |gamma(integrated) - third row of R(quaternion)| = %.2e" % dg)
# Euler angles from quaternion vs from gamma; check kinematic eq. for psi
i = 1234
psi, th, ph = euler_from_R(quat_to_R(Y[6:, i]))
g = Y[3:6, i]
print("theta from gamma: %.12f  from R: %.12f" % (np.arctan2(np.hypot(g[0], g[1]), g[2]), th))
print("phi   from gamma: %.12f  from R: %.12f" % (np.arctan2(g[0], g[1]), ph))
# psi' = (G - C r u)/(A sin^2 theta), check by finite difference
h = 1e-4
ps = [euler_from_R(quat_to_R(sol.sol(tt[i] + s * h)[6:]))[0] for s in (-1, 1)]
dpsi_fd = (ps[1] - ps[0]) / (2 * h)
G, H, r = integrals(Y[:, i])
print("psi' finite diff = %.10f, (G - C r u)/(A sin^2 th) = %.10f" %
      (dpsi_fd, (G - C * r * g[2]) / (A * (1 - g[2] ** 2))))
# potential: torque = mu * gamma x e3 derives from V = mu*gamma3:  check dH/dt = 0 already

# ----------------------------------------------------------------------------
# 2. Unperturbed solution u(t) = u1 + (u2-u1) sn^2(alpha t + beta, k)
# ----------------------------------------------------------------------------
hr("2. Unperturbed solution vs numerical integration")
G, H, r = integrals(y0)
u1, u2, u3, m, alpha, v = nut(G, H, r)
print("G=%.12f H=%.12f r=%.12f" % (G, H, r))
print("u1=%.12f u2=%.12f u3=%.12f  k^2=%.12f alpha=%.12f" % (u1, u2, u3, m, alpha))
ur = np.sort(np.roots([1, -sym(G, H, r)[0], sym(G, H, r)[1], -sym(G, H, r)[2]]).real)
print("np.roots check: max diff %.2e" % np.max(np.abs(ur - [u1, u2, u3])))
s1, s2, s3 = sym(G, H, r)
fval = [A * (2 * H - C * r * r - 2 * MU * uu) * (1 - uu * uu) - (G - C * r * uu) ** 2 for uu in (u1, u2, u3)]
print("f(u_i) (from (1.4) directly) =", ["%.1e" % x for x in fval])
u0 = y0[5]
udot0 = y0[3] * y0[1] - y0[4] * y0[0]
beta = ellipkinc(np.arcsin(np.sqrt((u0 - u1) / (u2 - u1))), m)
if udot0 < 0:
    beta = -beta
sn = ellipj(alpha * tt + beta, m)[0]
u_an = u1 + (u2 - u1) * sn ** 2
print("max |u_numeric - u_sn| over t in [0,60]: %.2e" % np.max(np.abs(Y[5] - u_an)))
Kk = ellipk(m)
Tper = 2 * Kk / alpha
print("2K/alpha = %.10f,  K/alpha (printed) = %.10f" % (Tper, Kk / alpha))
# measure period: times of successive maxima of u (dense output + root of u')
from scipy.optimize import brentq as _bq
ud = lambda t: (lambda y: y[3] * y[1] - y[4] * y[0])(sol.sol(t))
tz = []
tg = np.linspace(0, 60, 60001)
vals = np.array([ud(t) for t in tg[:20001]])
for j in range(20000):
    if vals[j] > 0 and vals[j + 1] <= 0:
        tz.append(_bq(ud, tg[j], tg[j + 1], xtol=1e-14))
print("measured period of u (max to max): %.10f" % (tz[1] - tz[0]))
# average <u> over one period vs v
from scipy.integrate import quad
uavg = quad(lambda t: sol.sol(t)[5], tz[0], tz[1], epsabs=1e-13, epsrel=1e-13, limit=200)[0] / (tz[1] - tz[0])
print("<u> numeric = %.12f, v = u3-(u3-u1)E/K = %.12f, diff %.1e" %
      (uavg, u3 - (u3 - u1) * ellipe(m) / Kk, uavg - (u3 - (u3 - u1) * ellipe(m) / Kk)))
# averages of the torque contributions (check of averaged G, H rhs)
pg = quad(lambda t: (lambda y: y[0] * y[3] + y[1] * y[4])(sol.sol(t)), tz[0], tz[1], epsabs=1e-13, limit=200)[0] / (tz[1] - tz[0])
pp = quad(lambda t: (lambda y: y[0] ** 2 + y[1] ** 2)(sol.sol(t)), tz[0], tz[1], epsabs=1e-13, limit=200)[0] / (tz[1] - tz[0])
print("<p g1 + q g2> = %.12f vs (G - C r v)/A = %.12f" % (pg, (G - C * r * v) / A))
print("<p^2 + q^2>   = %.12f vs (2H - C r^2 - 2 mu v)/A = %.12f" % (pp, (2 * H - C * r * r - 2 * MU * v) / A))
# Vieta / (2.5) round trip
for sR in (+1, -1):
    print("(2.5) with sign_R=%+d -> G,H,r =" % sR, ["%.12f" % x for x in from_roots(u1, u2, u3, np.sign(r), sR)])
print("sign(G^2 - C^2 r^2) = %+d" % np.sign(G * G - C * C * r * r))
# (2.7): V_i1 = du_i/dG, V_i2 = du_i/dH, V_i3 = du_i/dr (so that du_i/dt = sum V_ij F_j with
# F3 = M3/C = r'/eps).  Finite differences; also with generic (A, C, mu) so that C != 1 is tested.
def check_V(Gx, Hx, rx, Ax, Cx, mux):
    uu0 = np.array(roots(Gx, Hx, rx, Ax, Cx, mux))
    hh = 1e-6
    num = []
    for k in range(3):
        xp = [Gx, Hx, rx]; xm = [Gx, Hx, rx]
        xp[k] += hh; xm[k] -= hh
        num.append((np.array(roots(*xp, Ax, Cx, mux)) - np.array(roots(*xm, Ax, Cx, mux))) / (2 * hh))
    num = np.array(num).T          # num[i, k] = du_i / dx_k
    verr = 0.0
    for i in range(3):
        ui, uj, uk = uu0[i], uu0[(i + 1) % 3], uu0[(i + 2) % 3]
        D = mux * (ui - uj) * (ui - uk)
        V1 = (Gx - Cx * rx * ui) / (Ax * D)
        V2 = (ui * ui - 1) / D
        V3 = Cx / D * ((Cx / Ax - 1) * rx * ui * ui - Gx * ui / Ax + rx)
        verr = max(verr, abs(V1 - num[i, 0]), abs(V2 - num[i, 1]), abs(V3 - num[i, 2]))
    return verr
print("(2.7) V_i1, V_i2, V_i3 vs finite-difference du_i/d(G,H,r): scene %.1e; A=1.3,C=0.7,mu=0.9: %.1e"
      % (check_V(G, H, r, A, C, MU), check_V(0.9, 1.1, 1.2, 1.3, 0.7, 0.9)))
# (3.5) as printed vs chain rule sum_j V_ij <F_j> with generic (A, C, mu), a, b
def check_35(Gx, Hx, rx, Ax, Cx, mux, a, b):
    u = roots(Gx, Hx, rx, Ax, Cx, mux)
    m = (u[1] - u[0]) / (u[2] - u[0])
    v = u[2] - (u[2] - u[0]) * ellipe(m) / ellipk(m)
    F1 = -a * (Gx - Cx * rx * v) / Ax - b * rx * v
    F2 = -a * (2 * Hx - Cx * rx * rx - 2 * mux * v) / Ax - b * rx * rx
    F3 = -b * rx / Cx
    err = 0.0
    for i in range(3):
        ui, uj, uk = u[i], u[(i + 1) % 3], u[(i + 2) % 3]
        D = mux * (ui - uj) * (ui - uk)
        V1 = (Gx - Cx * rx * ui) / (Ax * D)
        V2 = (ui * ui - 1) / D
        V3 = Cx / D * ((Cx / Ax - 1) * rx * ui * ui - Gx * ui / Ax + rx)
        chain = V1 * F1 + V2 * F2 + V3 * F3
        printed = -1.0 / (Ax * D) * (a * ((Gx - Cx * rx * ui) * (Gx - Cx * rx * v) / Ax
                                          + (ui * ui - 1) * (2 * Hx - Cx * rx * rx - 2 * mux * v))
                                     + b * rx * (Gx - Cx * rx * ui) * (v - ui))
        err = max(err, abs(chain - printed))
    return err
print("(3.5) printed vs chain rule with A=1.3, C=0.7, mu=0.9, a=0.8, b=1.7: max diff %.1e"
      % check_35(0.9, 1.1, 1.2, 1.3, 0.7, 0.9, 0.8, 1.7))
# alternative sign bookkeeping: G +- C r from the roots
Sp = np.sign(G + C * r) * np.sqrt(2 * A * MU * (1 + u1) * (1 + u2) * (1 + u3))
Sm = np.sign(G - C * r) * np.sqrt(2 * A * MU * (1 - u1) * (1 - u2) * (u3 - 1))
Galt, ralt = 0.5 * (Sp + Sm), (Sp - Sm) / (2 * C)
Halt = MU * (u1 + u2 + u3) + 0.5 * C * ralt ** 2 * (1 - C / A)
print("sigma+- form: G=%.12f H=%.12f r=%.12f (errors %.1e %.1e %.1e)" %
      (Galt, Halt, ralt, Galt - G, Halt - H, ralt - r))

# ----------------------------------------------------------------------------
# 3. Paper's scene: table of initial roots
# ----------------------------------------------------------------------------
hr("3. Paper's scene: initial roots (p0=q0=0, r0=sqrt3, theta0)")
init = {}
for c, th0 in CASES.items():
    y0c = initial_state(0.0, 0.0, R0, np.radians(th0), 0.0)
    G0, H0, r0 = integrals(y0c)
    uu = nut(G0, H0, r0)
    init[c] = (y0c, G0, H0, r0)
    print("case %d theta0=%5.1f: G0=%.6f H0=%.6f r0=%.6f u=(%.4f, %.4f, %.4f) k^2=%.4f alpha=%.4f T=2K/alpha=%.4f"
          % (c, th0, G0, H0, r0, uu[0], uu[1], uu[2], uu[3], uu[4], 2 * ellipk(uu[3]) / uu[4]))
print("C^2 r0^2 = %.4f, 4 A mu = %.4f (Maiewski threshold of the sleeping top)" % (C * C * R0 ** 2, 4 * A * MU))

# ----------------------------------------------------------------------------
# 4. Averaged evolution of the scene (a0=b0=1), paper's claims
# ----------------------------------------------------------------------------
hr("4. Averaged evolution, a0=b0=%.2f, a1=b1=%.2f" % (A0, B0))
TAU = 4.0
avg = {}
for c in CASES:
    _, G0, H0, r0 = init[c]
    ts, X = run_avg(G0, H0, r0, TAU, n=801)
    U = np.array([nut(*X[:, j])[:4] for j in range(X.shape[1])])
    avg[c] = (ts, X, U)
    r_exact = r0 * np.exp(-(B0 * ts + B1 * ts ** 2 / 2) / C)
    print("case %d: max|r_avg - r_exact(3.3)| = %.1e" % (c, np.max(np.abs(X[2] - r_exact))))
    for tau_p in (0.0, 0.5, 1.0, 2.0, 3.0, 4.0):
        j = np.argmin(np.abs(ts - tau_p))
        print("   tau=%.1f G=%+.5f H=%+.5f r=%.5f u1=%+.5f u2=%+.5f u3=%.5f k^2=%.4f  G^2-C^2r^2=%+.2e"
              % (ts[j], X[0, j], X[1, j], X[2, j], U[j, 0], U[j, 1], U[j, 2], U[j, 3],
                 X[0, j] ** 2 - C * C * X[2, j] ** 2))
    tol = 1e-9
    mono = lambda d: "decr" if np.all(d <= tol) else ("incr" if np.all(d >= -tol) else "non-monotone")
    print("   monotonicity on [0,%g] (tol 1e-9): G %s, H %s, r %s, u1 %s, u2 %s, u3 %s" %
          (TAU, mono(np.diff(X[0])), mono(np.diff(X[1])), mono(np.diff(X[2])),
           mono(np.diff(U[:, 0])), mono(np.diff(U[:, 1])), mono(np.diff(U[:, 2]))))
    inc3 = np.where(np.diff(U[:, 2]) > tol)[0]
    j3 = inc3[0] if len(inc3) else len(ts) - 1
    print("   u3 decreases monotonically until tau=%.3f (u3 there = %.9f); max k^2 = %.4f at tau=%.3f"
          % (ts[j3], U[j3, 2], U[:, 3].max(), ts[np.argmax(U[:, 3])]))
    sgn = np.sign(X[0] ** 2 - C * C * X[2] ** 2)
    ch = np.where(np.diff(sgn) != 0)[0]
    print("   sign changes of G^2 - C^2 r^2 (R of (2.5)) at tau =", ["%.3f" % ts[j] for j in ch],
          " G - C r there:", ["%+.1e" % (X[0, j] - C * X[2, j]) for j in ch])
    Tn = np.array([2 * ellipk(U[j, 3]) / nut(*X[:, j])[4] for j in range(len(ts))])
    print("   nutation period 2K/alpha: at tau=0 %.3f, max %.3f at tau=%.3f, at tau=4 %.3f"
          % (Tn[0], Tn.max(), ts[np.argmax(Tn)], Tn[-1]))
    # sensitivity of the roots to the slow variables: du_i/dH = (u_i^2 - 1)/Delta_i,
    # du_i/dG = (G - C r u_i)/(A Delta_i),  Delta_i = mu (u_i - u_j)(u_i - u_k)
    sens = []
    for j in range(len(ts)):
        Gj, Hj, rj = X[:, j]
        uj = U[j, :3]
        row = []
        for i in range(3):
            D = MU * (uj[i] - uj[(i + 1) % 3]) * (uj[i] - uj[(i + 2) % 3])
            row.append(max(abs((uj[i] ** 2 - 1) / D), abs((Gj - C * rj * uj[i]) / (A * D))))
        sens.append(row)
    sens = np.array(sens)
    print("   max |du_i/d(G,H)| along the orbit: u1 %.1f, u2 %.1f, u3 %.1f (at tau=%.3f)"
          % (*sens.max(axis=0), ts[np.argmax(sens.max(axis=1))]))
    if c == 3:
        jz = np.where(np.diff(np.sign(X[0])) != 0)[0]
        print("   G crosses 0 at tau=%.3f; max G afterwards = %.3e at tau=%.3f (G0 = %.3f)"
              % (ts[jz[0]], X[0].max(), ts[np.argmax(X[0])], X[0, 0]))

# a = b: every averaged RHS is proportional to a(tau) -> the orbit in (G,H,r) does not
# depend on a0 = b0 (only the clock s = int a dtau does).
_, G0, H0, r0 = init[1]
for a0b0 in (0.5, 2.0):
    s_end = A0 * TAU + A1 * TAU ** 2 / 2        # s reached by a0=b0=1 at tau=TAU
    tau_end = (-a0b0 + np.sqrt(a0b0 ** 2 + 2 * A1 * s_end)) / A1
    ts2, X2 = run_avg(G0, H0, r0, tau_end, n=3, a0=a0b0, b0=a0b0)
    print("a0=b0=%.1f: state at equal s = int a dtau differs from a0=b0=1 by %.1e"
          % (a0b0, np.max(np.abs(X2[:, -1] - avg[1][1][:, -1]))))

# a0 != b0: the claims under other choices
for a0x, b0x in ((1.0, 0.5), (0.5, 1.0)):
    for c in CASES:
        _, G0, H0, r0 = init[c]
        tsx, Xx = run_avg(G0, H0, r0, TAU, n=801, a0=a0x, b0=b0x)
        Ux = np.array([nut(*Xx[:, j])[:4] for j in range(Xx.shape[1])])
        tol = 1e-9
        mono = lambda d: "decr" if np.all(d <= tol) else ("incr" if np.all(d >= -tol) else "non-monotone")
        inc3 = np.where(np.diff(Ux[:, 2]) > tol)[0]
        print("a0=%.1f b0=%.1f case %d: G %s, H %s, u1 %s, u2 %s; u3 decreasing until tau=%.3f; max G=%.2e; H(4)=%.4f"
              % (a0x, b0x, c, mono(np.diff(Xx[0])), mono(np.diff(Xx[1])), mono(np.diff(Ux[:, 0])),
                 mono(np.diff(Ux[:, 1])), tsx[inc3[0]] if len(inc3) else TAU, Xx[0].max(), Xx[1, -1]))

# ----------------------------------------------------------------------------
# 5. Paper's u-system (3.5) vs (G,H,r) system; sign bookkeeping of (2.5)
# ----------------------------------------------------------------------------
hr("5. Paper's (3.5) in u_i with fixed signs vs averaged (G,H,r)")
for c in CASES:
    _, G0, H0, r0 = init[c]
    ts, X, U = avg[c]
    u0 = nut(G0, H0, r0)[:3]
    sR = np.sign(G0 * G0 - C * C * r0 * r0)
    evs = []
    def ev(t, uu, *a):
        return min(uu[0] + 1, 1 - uu[1], uu[2] - 1) - 1e-9
    ev.terminal = True
    s = solve_ivp(avg_rhs_u, (0, TAU), list(u0), args=(np.sign(r0), sR), method="DOP853",
                  rtol=1e-11, atol=1e-13, dense_output=True, events=ev)
    tend = s.t[-1]
    tt5 = ts[ts <= tend]
    err = 0.0
    for j, tj in enumerate(tt5):
        err = max(err, np.max(np.abs(np.sort(s.sol(tj)) - U[j, :3])))
    print("case %d: u-system integrated to tau=%.4f (%s); max |u_paper - u_GHr| = %.2e"
          % (c, tend, "stopped: a root reached +-1 (R=0, sign flip needed)" if s.status == 1 else "ok", err))

# ----------------------------------------------------------------------------
# 6. Full vs averaged, orders in eps
# ----------------------------------------------------------------------------
hr("6. Full vs averaged: max error over tau in [0, TAU]")
QUICK = "quick" in sys.argv
EPS = [0.1, 0.05, 0.02, 0.01]
EPS1 = EPS + ([] if QUICK else [0.005, 0.002])   # case 1 needs smaller eps (slow nutation)
TAUF = 3.0
from scipy.interpolate import CubicSpline


def compare(y0c, eps_list, tau_f, label, **kw):
    G0, H0, r0 = integrals(y0c)
    b0 = kw.get("b0", B0); b1 = kw.get("b1", B1)
    tsA, XA = run_avg(G0, H0, r0, tau_f, n=3001, **kw)
    spl = [CubicSpline(tsA, XA[i]) for i in range(3)]
    out = {}
    for eps in eps_list:
        tF, YF = run_full(y0c, eps, tau_f, n=int(20 * tau_f / eps) + 1, **kw)
        tauF = eps * tF
        GHrF = np.array(integrals(YF))
        GHrA = np.array([spl[i](tauF) for i in range(3)])
        e = np.max(np.abs(GHrF - GHrA), axis=1)
        step = max(1, len(tF) // 1500)
        UF = np.array([nut(*GHrF[:, j])[:3] for j in range(0, len(tF), step)])
        UA = np.array([nut(*GHrA[:, j])[:3] for j in range(0, len(tF), step)])
        vF = np.array([nut(*GHrF[:, j])[5] for j in range(0, len(tF), step)])
        vA = np.array([nut(*GHrA[:, j])[5] for j in range(0, len(tF), step)])
        ev = np.max(np.abs(vF - vA))
        eu = np.max(np.abs(UF - UA), axis=0)
        late = tauF[::step] >= 0.5
        eul = np.max(np.abs(UF[late] - UA[late]), axis=0)
        rexact = r0 * np.exp(-(b0 * tauF + b1 * tauF ** 2 / 2) / C)
        gn = np.max(np.abs(np.sum(YF[3:6] ** 2, axis=0) - 1))
        out[eps] = (*e, *eu, *eul, ev)
        print("%s eps=%.3f: err G=%.2e H=%.2e v=%.2e | u1=%.2e u2=%.2e u3=%.2e | tau>=0.5: u1=%.2e u2=%.2e u3=%.2e | r vs (3.3) %.0e | ||g|-1| %.0e"
              % (label, eps, e[0], e[1], ev, *eu, *eul, np.max(np.abs(YF[2] - rexact)), gn))
    return out


def orders(out, label):
    el = sorted(out)
    le = np.log(el)
    names = ["G", "H", "r", "u1", "u2", "u3", "u1(tau>=.5)", "u2(tau>=.5)", "u3(tau>=.5)", "v"]
    txt = []
    for k, nme in enumerate(names):
        if nme == "r":
            continue
        txt.append("%s %.2f" % (nme, np.polyfit(le, np.log([out[e][k] for e in el]), 1)[0]))
    print("   order fit %s over eps=%s: %s" % (label, el, ", ".join(txt)))


res = {}
for c in CASES:
    res[c] = compare(init[c][0], EPS1 if c == 1 else EPS, TAUF, "case %d" % c)
print()
for c in CASES:
    orders({e: res[c][e] for e in EPS}, "case %d" % c)
if not QUICK:
    orders({e: res[1][e] for e in EPS1 if e <= 0.01}, "case 1 (small eps)")

hr("7. Where averaging degrades: near the separatrix k^2 -> 1 and near the triple root")
# S1, S2: r0 = 1 (< Maiewski threshold 2 sqrt(A mu)/C = 1.732), pure spin, theta0 small:
#          u2 = cos theta0, u3 -> 1+, k^2 -> 1 (top falls through the separatrix neighbourhood)
# D:      r0 = sqrt3 (threshold) and theta0 = 1 deg: all three roots near 1, alpha -> 0
for lab, r0s, th in (("S1 r0=1 th0=2deg  ", 1.0, 2.0), ("S2 r0=1 th0=0.2deg", 1.0, 0.2),
                     ("D  r0=v3 th0=1deg ", R0, 1.0)):
    y0s = initial_state(0.0, 0.0, r0s, np.radians(th), 0.0)
    uu = nut(*integrals(y0s))
    print("%s: initial u=(%.6f, %.6f, %.6f) 1-k^2=%.2e alpha=%.4f 2K/alpha=%.2f"
          % (lab, uu[0], uu[1], uu[2], 1 - uu[3], uu[4], 2 * ellipk(uu[3]) / uu[4]))
    o = compare(y0s, [0.1, 0.02, 0.005] if not QUICK else [0.1, 0.02], 2.0, lab)
    orders(o, lab)

print("\ntotal time %.1f s" % (time.time() - T0))
