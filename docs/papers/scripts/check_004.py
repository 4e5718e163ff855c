#!/usr/bin/env python3
"""Independent numerical check of paper 004 (Makeev, gyrostat under a torque
orthogonal to G and omega).  Self-contained: NumPy + SciPy only.

Run:  OMP_NUM_THREADS=1 python3 check_004.py
Every number quoted in docs/papers/004_orthogonal_torque.md is printed here.
Sections:
  A  triaxial gyrostat, full model in natural time t: invariants (5),(6),
     relation (8), time change (10), omega(t) == omega_ZV(tau(t)),
     theta/phi map through tau, the inertial direction of G does NOT stay fixed.
  B  1 - L/|Q| changing sign: frozen points |Q| = L, backward time.
  C  |Q| -> 0 (permanent rotation): raw vs regularised torque.
  D  Euler-angle system (16) vs ZV + attitude; (22) coefficients; zeroth and
     first approximations for several mu.
  E  quadratures (24)-(26) (mu = 0, k3 = 0).
  F  k = 0 / k != 0 tests of (29)-(34).
"""
import os
os.environ.setdefault("OMP_NUM_THREADS", "1")
import time
import numpy as np
from scipy.integrate import solve_ivp, quad

RTOL, ATOL = 1e-11, 1e-12
T0 = time.time()


def hat(v):
    return np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])


def qmul(a, b):
    a0, a1, a2, a3 = a
    b0, b1, b2, b3 = b
    return np.array([a0*b0 - a1*b1 - a2*b2 - a3*b3,
                     a0*b1 + a1*b0 + a2*b3 - a3*b2,
                     a0*b2 - a1*b3 + a2*b0 + a3*b1,
                     a0*b3 + a1*b2 - a2*b1 + a3*b0])


def qrot(q):
    """rotation matrix body->inertial of unit quaternion q=(w,x,y,z)"""
    w, x, y, z = q / np.linalg.norm(q)
    return np.array([[1-2*(y*y+z*z), 2*(x*y-w*z), 2*(x*z+w*y)],
                     [2*(x*y+w*z), 1-2*(x*x+z*z), 2*(y*z-w*x)],
                     [2*(x*z-w*y), 2*(y*z+w*x), 1-2*(x*x+y*y)]])


def Rz(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def Rx(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])


def R313(psi, th, ph):
    """body->inertial, 3-1-3 (psi precession, theta nutation, phi spin);
    inertial z3 in body axes = (sin th sin ph, sin th cos ph, cos th) = (15)."""
    return Rz(psi) @ Rx(th) @ Rz(ph)


def euler_from_R(R):
    th = np.arccos(np.clip(R[2, 2], -1, 1))
    ph = np.arctan2(R[2, 0], R[2, 1])
    ps = np.arctan2(R[0, 2], -R[1, 2])
    return th, ph, ps


def mat2quat(R):
    w = np.sqrt(max(0.0, 1 + np.trace(R))) / 2
    if w > 1e-6:
        return np.array([w, (R[2, 1]-R[1, 2])/(4*w), (R[0, 2]-R[2, 0])/(4*w),
                         (R[1, 0]-R[0, 1])/(4*w)])
    raise ValueError


# ---------------------------------------------------------------- models
class Gyro:
    def __init__(s, A, k):
        s.A = np.asarray(A, float)
        s.k = np.asarray(k, float)

    def G(s, w):
        return s.A*w + s.k

    def Q(s, w):
        return np.cross(w, s.A*w + s.k)

    def zv(s, tau, y):
        """Zhukovsky-Volterra (11)/(12): A w' = -(w x (A w + k)) = G x w"""
        w = y[:3]
        dw = -np.cross(w, s.A*w + s.k)/s.A
        if len(y) == 3:
            return dw
        q = y[3:7]
        dq = 0.5*qmul(q, np.r_[0.0, w])
        return np.r_[dw, dq]

    def full(s, Lfun, delta=0.0):
        """full model (1),(7) in natural time t; state (w, tau, q).
        torque = L(t) Q / sqrt(|Q|^2 + delta^2)  (delta = 0: paper's e_L)."""
        def f(t, y):
            w = y[:3]
            Q = np.cross(w, s.A*w + s.k)
            nQ = np.sqrt(Q @ Q + delta**2)
            L = Lfun(t)
            g = 1.0 - L/nQ                     # d tau / d t
            dw = -g*Q/s.A                      # A w' = -(1 - L/|Q|) Q   (9)
            dq = 0.5*qmul(y[4:8], np.r_[0.0, w])
            return np.r_[dw, g, dq]
        return f


def invariants(g, w):
    G = g.G(w)
    H2 = G @ G
    h = w @ (g.A*w)
    Q = g.Q(w)
    q2 = Q @ Q
    F = h**2 + 2*h*(w @ g.k) + (w @ g.k)**2
    rel8 = (w @ w)*H2 - F                  # (8) right-hand side
    return H2, h, q2, rel8


def run_full(g, w0, Lfun, T, delta=0.0, npts=2001, q0=None, **kw):
    if q0 is None:
        q0 = np.array([1.0, 0, 0, 0])
    y0 = np.r_[w0, 0.0, q0]
    ts = np.linspace(0, T, npts)
    sol = solve_ivp(g.full(Lfun, delta), (0, T), y0, method="DOP853",
                    rtol=RTOL, atol=ATOL, t_eval=ts, **kw)
    return sol


def zv_dense(g, w0, tmin, tmax):
    """dense ZV solution on [tmin, tmax] (tmin <= 0 <= tmax)"""
    out = []
    for tb in (tmax, tmin):
        if abs(tb) < 1e-14:
            out.append(None)
            continue
        out.append(solve_ivp(g.zv, (0, tb), w0, method="DOP853", rtol=RTOL,
                             atol=ATOL, dense_output=True).sol)

    def ev(tau):
        tau = np.atleast_1d(tau)
        r = np.empty((3, tau.size))
        for i, t in enumerate(tau):
            r[:, i] = out[0](t) if (t > 0 or (t == 0 and out[0] is not None)) else out[1](t)
        return r
    return ev


def qrange(g, w0, Tspan=200.0):
    s = solve_ivp(g.zv, (0, Tspan), w0, method="DOP853", rtol=RTOL, atol=ATOL,
                  t_eval=np.linspace(0, Tspan, 20001))
    qn = np.linalg.norm(np.cross(s.y.T, (g.A*s.y.T + g.k)), axis=1)
    return qn.min(), qn.max()


def section(name):
    print("\n" + "=" * 78 + "\n" + name + "\n" + "=" * 78)


# ====================================================================== A
section("A  triaxial gyrostat: invariants, (8), tau(t), omega(t)=omega_ZV(tau(t))")
gA = Gyro([2.0, 3.0, 4.0], [0.3, -0.2, 0.5])
wA = np.array([1.0, 0.5, -0.8])
qmin, qmax = qrange(gA, wA)
print(f"scene A: A=(2,3,4) k=(0.3,-0.2,0.5) w0=(1,0.5,-0.8)")
H2, h, q2, r8 = invariants(gA, wA)
print(f"  |G|^2=H^2={H2:.10f}  h={h:.10f}  |Q0|={np.sqrt(q2):.6f}")
print(f"  |Q| along the torque-free (ZV) orbit: min={qmin:.6f} max={qmax:.6f}")

scenesA = {
    "A1 L=0.15 const": lambda t: 0.15,
    "A2 L=0.1+0.1 sin(1.3t)": lambda t: 0.1 + 0.1*np.sin(1.3*t),
    "A3 L=-0.5 (accelerates)": lambda t: -0.5,
    "B1 L=0.4 const (min|Q|<L<max|Q|)": lambda t: 0.4,
    "B2 L=3.0 const (L>max|Q|)": lambda t: 3.0,
    "B3 L=0.3+0.2 sin(1.3t) (crosses)": lambda t: 0.3 + 0.2*np.sin(1.3*t),
}
TA = 60.0
for name, Lf in scenesA.items():
    if name.startswith("B1"):
        section("B  1 - L/|Q| reaching zero / negative (same gyrostat, same w0)")
    sol = run_full(gA, wA, Lf, TA)
    W = sol.y[:3]
    tau = sol.y[3]
    inv = np.array([invariants(gA, W[:, i]) for i in range(W.shape[1])])
    dH2 = np.max(np.abs(inv[:, 0] - H2))
    dh = np.max(np.abs(inv[:, 1] - h))
    d8 = np.max(np.abs(inv[:, 2] - inv[:, 3]))
    ev = zv_dense(gA, wA, min(tau.min(), 0), max(tau.max(), 0))
    Wz = ev(tau)
    err = np.max(np.abs(W - Wz))
    # Euler angles theta, phi of G in body axes: map through tau
    # inertial direction of G in the full model
    Gin = np.array([qrot(sol.y[4:8, i]) @ gA.G(W[:, i]) for i in range(W.shape[1])])
    ang = np.degrees(np.arccos(np.clip(Gin @ Gin[0] / H2, -1, 1)))
    print(f" {name}: steps={sol.t.size}/nfev={sol.nfev}  tau(T={TA})={tau[-1]:.6f}"
          f"  min dtau/dt={np.min(1-np.array([Lf(t) for t in sol.t])/np.sqrt(inv[:,2])):.4f}")
    print(f"    max| |G|^2-H^2 |={dH2:.2e}  max|h(t)-h|={dh:.2e}  "
          f"max| |Q|^2-(w^2H^2-F) |={d8:.2e}")
    print(f"    max|w(t)-w_ZV(tau(t))|={err:.2e}   inertial G direction drift:"
          f" max angle={ang.max():.2f} deg")
    if name[0] == "B":
        qf = np.sqrt(inv[-1, 2])
        print(f"    tau range [{tau.min():.4f},{tau.max():.4f}]  |Q(T)|={qf:.8f} L(T)={Lf(TA):.4f}"
              f"  |w'(T)|={np.linalg.norm(gA.full(Lf)(TA, sol.y[:, -1])[:3]):.2e}")
# paper's printed alternative check: omega.G not constant -> (13) is not an integral
sol = run_full(gA, wA, scenesA["A1 L=0.15 const"], TA)
wk = gA.k @ sol.y[:3]
print(f"  (13) check: w.k along scene A1 varies in [{wk.min():.4f}, {wk.max():.4f}]"
      f"  (not conserved)")
# identity D = h^2+(2h+m)m = (h+m)^2
m = 0.37
print(f"  (14) D=h^2+(2h+m)m - (h+m)^2 = {h**2+(2*h+m)*m-(h+m)**2:.1e}")
# k.A^{-1}Q, the quantity that must vanish for (13) to survive
print(f"  k.A^-1 Q at t=0 = {gA.k @ (gA.Q(wA)/gA.A):.4f} (must be 0 for (13) to persist)")

# ====================================================================== C
section("C  |Q| -> 0 near a permanent rotation: raw e_L vs regularised torque")
gC = Gyro([2.0, 3.0, 4.0], [0.0, 0.0, 0.5])
LC = lambda t: 0.1
TC = 10.0
for eps in (1e-2, 1e-3, 1e-4):
    w0 = np.array([eps, 0.0, 1.0])
    Gn = np.linalg.norm(gC.G(w0))
    qmn, qmx = qrange(gC, w0, 50.0)
    line = f"  eps={eps:.0e}: |Q| on ZV orbit in [{qmn:.2e},{qmx:.2e}]"
    t1 = time.time()
    sr = run_full(gC, w0, LC, TC, npts=11)
    line += f" | raw: nfev={sr.nfev} tau(T)={sr.y[3,-1]:.3f}"
    for eta in (1e-3,):
        d = eta*np.linalg.norm(w0)*Gn
        sg = run_full(gC, w0, LC, TC, delta=d, npts=201)
        W = sg.y[:3]
        tau = sg.y[3]
        inv = np.array([invariants(gC, W[:, i]) for i in range(W.shape[1])])
        ev = zv_dense(gC, w0, min(tau.min(), 0), max(tau.max(), 0))
        err = np.max(np.abs(W - ev(tau)))
        line += (f" | reg(eta={eta:g}): nfev={sg.nfev} tau(T)={tau[-1]:.3f}"
                 f" dInv={max(np.ptp(inv[:,0]), np.ptp(inv[:,1])):.1e}"
                 f" |w-wZV(tau)|={err:.1e}")
    print(line)
# exactly on the permanent rotation: Q = 0, regularised torque = 0 -> equilibrium
w0 = np.array([0.0, 0.0, 1.0])
sg = run_full(gC, w0, LC, TC, delta=1e-3*4.5, npts=11)
print(f"  eps=0 (Q=0 exactly), regularised: max|w-w0|={np.max(np.abs(sg.y[:3]-w0[:,None])):.1e}"
      f" tau(T)={sg.y[3,-1]:.4f} (=T(1-L/delta))")

# ====================================================================== D
section("D  Euler-angle system (16), nearly spherical gyrostat (18)-(22)")


def wrap(x):
    return (x + np.pi) % (2*np.pi) - np.pi


def f16(a, k, G):
    a = np.asarray(a, float)
    B = a*np.asarray(k, float)

    def f(t, y):
        th, ph, ps = y[:3]
        s, c = np.sin(ph), np.cos(ph)
        I1 = B[0]*c - B[1]*s
        I2 = a[0]*s*s + a[1]*c*c
        I3 = B[0]*s + B[1]*c
        return [(a[0]-a[1])*G*np.sin(th)*s*c - I1,
                (a[2]-I2)*G*np.cos(th) + I3/np.tan(th) - B[2],
                I2*G - I3/np.sin(th)]
    return f


def f0_21(J, k, G):
    k1, k2, k3 = k

    def f(t, y):
        th, ph, ps = y[:3]
        N1 = k1*np.sin(ph) + k2*np.cos(ph)
        N2 = k1*np.cos(ph) - k2*np.sin(ph)
        return np.array([-N2, N1/np.tan(th) - k3, G - N1/np.sin(th)])/J
    return f


def f1_22(J, b, k, G, printed=False):
    """mu-coefficient of (16); printed=True uses the printed J*P*G in psi'"""
    b1, b2, b3 = b
    k1, k2, k3 = k
    D1 = (b2 - b1)*G

    def f(t, y):
        th, ph, ps = y[:3]
        s, c = np.sin(ph), np.cos(ph)
        P = b1*s*s + b2*c*c
        Q1 = b1*k1*s + b2*k2*c
        Q2 = b1*k1*c - b2*k2*s
        return np.array([D1*np.sin(th)*s*c + Q2,
                         (P - b3)*G*np.cos(th) - Q1/np.tan(th) + b3*k3,
                         Q1/np.sin(th) - (J if printed else 1.0)*P*G])/J
    return f


def Df0(J, k, G, y):
    th, ph = y[0], y[1]
    k1, k2, k3 = k
    N1 = k1*np.sin(ph) + k2*np.cos(ph)
    N2 = k1*np.cos(ph) - k2*np.sin(ph)
    st, ct = np.sin(th), np.cos(th)
    return np.array([[0, N1, 0],
                     [-N1/st**2, N2*ct/st, 0],
                     [N1*ct/st**2, -N2/st, 0]])/J


def integ(f, y0, T, ts):
    return solve_ivp(f, (0, T), y0, method="DOP853", rtol=RTOL, atol=ATOL,
                     t_eval=ts).y


JN, JjN = 2.0, np.array([1.0, -0.6, 1.6])
bN = JjN/JN
kN = np.array([0.6, 0.8, 0.0])
GN = 2.0
phk = np.arctan2(kN[0], kN[1])
Y0 = np.array([1.0, phk + 0.5, 0.0])
print(f"scene N: J={JN} J_j={JjN.tolist()} (b={bN.tolist()}) k={kN.tolist()} |G|={GN}"
      f" theta0=1.0 phi0={Y0[1]:.4f} psi0=0")

# --- (16) against ZV + attitude (quaternion), mu = 0.1
mu = 0.1
AN = JN + mu*JjN
gN = Gyro(AN, kN)
Rm0 = R313(Y0[2], Y0[0], Y0[1])
s0 = Rm0[2, :]                                   # inertial z3 in body axes
w0 = (GN*s0 - kN)/AN
print(f"  check (15): R^T e3 == (sin th sin ph, sin th cos ph, cos th): "
      f"{np.max(np.abs(s0 - [np.sin(1.0)*np.sin(Y0[1]), np.sin(1.0)*np.cos(Y0[1]), np.cos(1.0)])):.1e}")
Tz = 50.0
ts = np.linspace(0, Tz, 501)
sz = solve_ivp(gN.zv, (0, Tz), np.r_[w0, mat2quat(Rm0)], method="DOP853",
               rtol=RTOL, atol=ATOL, t_eval=ts)
E = np.array([euler_from_R(qrot(sz.y[3:7, i])) for i in range(ts.size)])
Y16 = integ(f16(1/AN, kN, GN), Y0, Tz, ts)
print(f"  (16) vs ZV+quaternion, mu=0.1, tau in [0,50]: max|dtheta|="
      f"{np.max(np.abs(E[:,0]-Y16[0])):.1e} max|dphi|={np.max(np.abs(wrap(E[:,1]-Y16[1]))):.1e}"
      f" max|dpsi|={np.max(np.abs(wrap(E[:,2]-Y16[2]))):.1e}")
# inertial G stays on z3 in ZV
print(f"  ZV: |R G - |G| e3| max = "
      f"{max(np.linalg.norm(qrot(sz.y[3:7,i]) @ gN.G(sz.y[:3,i]) - [0,0,GN]) for i in range(ts.size)):.1e}")

# --- (22): coefficient check (16) = (21) + mu (22) + O(mu^2)
rng = np.random.default_rng(4)
pts = np.c_[rng.uniform(0.4, 2.7, 50), rng.uniform(-np.pi, np.pi, 50), np.zeros(50)]
for kk in (kN, np.array([0.6, 0.8, 0.4])):
    res = {}
    for m_ in (1e-3, 1e-4):
        fa = f16(1/(JN + m_*JjN), kk, GN)
        r_c = max(np.max(np.abs((np.array(fa(0, p)) - f0_21(JN, kk, GN)(0, p))/m_
                                - f1_22(JN, bN, kk, GN)(0, p))) for p in pts)
        r_p = max(np.max(np.abs((np.array(fa(0, p)) - f0_21(JN, kk, GN)(0, p))/m_
                                - f1_22(JN, bN, kk, GN, printed=True)(0, p))) for p in pts)
        res[m_] = (r_c, r_p)
    print(f"  k={kk.tolist()}: max|((16)-(21))/mu - (22)| over 50 pts: "
          f"corrected: mu=1e-3 {res[1e-3][0]:.2e}, 1e-4 {res[1e-4][0]:.2e};"
          f"  printed (J P G): {res[1e-3][1]:.2e}, {res[1e-4][1]:.2e}")

# --- zeroth and first approximations vs (16)
MUS = (0.1, 0.05, 0.02, 0.01)
Tfix = 10.0
rows = []
for mu in MUS:
    fa = f16(1/(JN + mu*JjN), kN, GN)
    Tl = 1.0/mu
    ts = np.linspace(0, Tl, 2001)
    ts = np.unique(np.r_[ts, Tfix])
    ifix = np.searchsorted(ts, Tfix)
    Yex = integ(fa, Y0, Tl, ts)
    f0 = f0_21(JN, kN, GN)
    f1 = f1_22(JN, bN, kN, GN)
    f1p = f1_22(JN, bN, kN, GN, printed=True)
    Y0a = integ(f0, Y0, Tl, ts)
    Ytr = integ(lambda t, y: f0(t, y) + mu*f1(t, y), Y0, Tl, ts)
    Ypr = integ(lambda t, y: f0(t, y) + mu*f1p(t, y), Y0, Tl, ts)

    def var(t, z):
        y, y1 = z[:3], z[3:]
        return np.r_[f0(t, y), Df0(JN, kN, GN, y) @ y1 + f1(t, y)]
    Z = integ(var, np.r_[Y0, 0, 0, 0], Tl, ts)
    Yexp = Z[:3] + mu*Z[3:]

    def errs(Y):
        d = np.abs(np.c_[Y[0]-Yex[0], wrap(Y[1]-Yex[1]), wrap(Y[2]-Yex[2])].T)
        return d[:, ifix], d.max(axis=1)
    rows.append((mu, errs(Y0a), errs(Ytr), errs(Ypr), errs(Yexp)))

names = ["zeroth (21)", "f0+mu*f1 (22 corrected)", "f0+mu*f1 (22 printed)",
         "Phi0+mu*Phi1 (variational)"]
for j, nm in enumerate(names):
    print(f"  {nm}:")
    for i, lab in enumerate(("theta", "phi", "psi")):
        e_fix = np.array([r[1+j][0][i] for r in rows])
        e_long = np.array([r[1+j][1][i] for r in rows])
        sl_f = np.polyfit(np.log(MUS), np.log(e_fix), 1)[0]
        sl_l = np.polyfit(np.log(MUS), np.log(e_long), 1)[0]
        print(f"    {lab:5s} err@tau=10: " + " ".join(f"{e:.2e}" for e in e_fix) +
              f" slope {sl_f:.2f} | max on [0,1/mu]: " +
              " ".join(f"{e:.2e}" for e in e_long) + f" slope {sl_l:.2f}")
print(f"  (mu = {MUS})")
print(f"  [t={time.time()-T0:.1f}s]")

# ====================================================================== E
section("E  zeroth approximation, quadratures (24)-(26) (mu=0, k3=0)")
f0 = f0_21(JN, kN, GN)
TE = 40.0
sE = solve_ivp(f0, (0, TE), Y0, method="DOP853", rtol=RTOL, atol=ATOL,
               dense_output=True, t_eval=np.linspace(0, TE, 4001))
th, ph, ps = sE.y
N1 = kN[0]*np.sin(ph) + kN[1]*np.cos(ph)
Cc = N1*np.sin(th)
print(f"  C = N1 sin(theta): C0={Cc[0]:.10f}, max drift {np.ptp(Cc):.1e}"
      f"  (= s.k, cone half-angle {np.degrees(np.arccos(Cc[0]/np.linalg.norm(kN))):.2f} deg)")
# general k3: s.k = N1 sin th + k3 cos th is the integral
k3v = np.array([0.6, 0.8, 0.4])
y3 = integ(f0_21(JN, k3v, GN), Y0, TE, np.linspace(0, TE, 2001))
c3 = (k3v[0]*np.sin(y3[1]) + k3v[1]*np.cos(y3[1]))*np.sin(y3[0]) + k3v[2]*np.cos(y3[0])
c3b = (k3v[0]*np.sin(y3[1]) + k3v[1]*np.cos(y3[1]))*np.sin(y3[0])
print(f"  k3=0.4: drift of N1 sin th + k3 cos th = {np.ptp(c3):.1e};"
      f" drift of N1 sin th alone = {np.ptp(c3b):.3f}")
# the spherical gyrostat solution: s rotates about k with rate |k|/J
kh = kN/np.linalg.norm(kN)
s0 = np.array([np.sin(Y0[0])*np.sin(Y0[1]), np.sin(Y0[0])*np.cos(Y0[1]), np.cos(Y0[0])])


def rodr(v, ax, a):
    return v*np.cos(a) + np.cross(ax, v)*np.sin(a) + ax*(ax @ v)*(1-np.cos(a))


sA = np.array([rodr(s0, kh, np.linalg.norm(kN)*t/JN) for t in sE.t])
sN = np.c_[np.sin(th)*np.sin(ph), np.sin(th)*np.cos(ph), np.cos(th)]
print(f"  s(tau) = Rot(k^, |k| tau/J) s0 vs (21): max err {np.max(np.abs(sA-sN)):.1e}")
# first turning point of phi (cos theta = 0, N1^2 = C^2)
ct = np.cos(th)
itp = np.argmax(np.sign(ct) != np.sign(ct[0]))
ttp = sE.t[itp]
print(f"  phi is not monotone: first turning point (cos th = 0, N1^2=C^2) near tau={ttp:.3f};"
      f" phi range on [0,{TE:.0f}]: [{ph.min():.3f},{ph.max():.3f}]")
C0 = Cc[0]
sg = np.sign(ct[0])
errs24 = []
for tq in np.linspace(0.2, 0.95, 4)*ttp:
    phq = sE.sol(tq)[1]
    # (24):  J^-1 tau = C int ds / (N1 sqrt(N1^2 - C^2)), branch sign = sign(cos th)
    val = quad(lambda x: 1.0/((kN[0]*np.sin(x)+kN[1]*np.cos(x)) *
                              np.sqrt((kN[0]*np.sin(x)+kN[1]*np.cos(x))**2 - C0**2)),
               Y0[1], phq, limit=200)[0]
    errs24.append(abs(JN*C0*val*sg - tq))
print(f"  (24) on the first monotone branch: max |tau_quad - tau| = {max(errs24):.1e}")
# (25), (26) by cumulative trapezoid along the solution
from scipy.integrate import cumulative_trapezoid as ctz
N2 = kN[0]*np.cos(ph) - kN[1]*np.sin(ph)
th25 = Y0[0] - ctz(N2, sE.t, initial=0)/JN
ps26 = Y0[2] + (GN*sE.t - C0*ctz(1/np.sin(th)**2, sE.t, initial=0))/JN
print(f"  (25) max err {np.max(np.abs(th25-th)):.1e}; (26) max err {np.max(np.abs(ps26-ps)):.1e}"
      f" (trapezoid, h={sE.t[1]:.0e})")

# ====================================================================== F
section("F  (28)-(34): Abel equation, approximate solution, mean rates")


def scene_F(label, Jj, th0, k=(0.0, 0.0, 0.0), Tlong=None):
    Jj = np.asarray(Jj, float)
    b = Jj/JN
    k = np.asarray(k, float)
    Ps = 0.5*(b[0]+b[1])
    D1, D2 = (b[1]-b[0])*GN, (Ps-b[2])*GN
    n = D1/(2*D2)
    y0 = np.array([th0, 0.3, 0.0])
    u0 = np.sin(th0)
    print(f" scene {label}: J={JN} J_j={Jj.tolist()} b={b.tolist()} k={k.tolist()} |G|={GN}"
          f" theta0={th0} phi0=0.3; P*={Ps:.3f} D1={D1:.3f} D2={D2:.3f} n={n:.4f}")
    f29 = lambda p: u0*np.exp(n*(np.sin(p)**2 - np.sin(0.3)**2))
    # printed and corrected (31) (k=0 => Q1=0): tau for phi -> phi0 - 2 pi
    I31p = quad(lambda x: 2*f29(x)/((2-f29(x)**2)*(D2*f29(x))), 0.3, 0.3-2*np.pi, limit=200)[0]
    I31c = quad(lambda x: f29(x)/(np.sqrt(1-f29(x)**2)*(D2*f29(x))), 0.3, 0.3-2*np.pi, limit=200)[0]
    # first-order exact quadrature (P(phi) kept, exact orbit u^2 (P-b3) = const)
    cst = u0**2*(b[0]*np.sin(0.3)**2 + b[1]*np.cos(0.3)**2 - b[2])
    Pf = lambda x: b[0]*np.sin(x)**2 + b[1]*np.cos(x)**2
    I31e = quad(lambda x: 1.0/((Pf(x)-b[2])*GN*np.sqrt(1-cst/(Pf(x)-b[2]))), 0.3,
                0.3-2*np.pi, limit=200)[0]
    if not np.any(k):
        print(f"   mu*T_phi (phi0 -> phi0-2pi): (31) printed {JN*I31p:.4f}, (31) with"
              f" sqrt(1-f^2) {JN*I31c:.4f}, exact 1st-order quadrature (P(phi), exact orbit)"
              f" {JN*I31e:.4f}")
    out = []
    for mu in MUS:
        a = 1/(JN + mu*Jj)
        fa = f16(a, k, GN)
        TT = Tlong(mu) if Tlong else 4*JN*2*np.pi/(mu*abs(D2)*np.cos(th0))
        ev = lambda t, y: y[1] - (0.3 - 2*np.pi)
        ev.terminal = False
        so = solve_ivp(fa, (0, TT), y0, method="DOP853", rtol=RTOL, atol=ATOL,
                       events=ev, t_eval=np.linspace(0, TT, 20001))
        thf, phf, psf = so.y
        u = np.sin(thf)
        e29 = np.max(np.abs(u - f29(phf)))
        # exact first-order orbit of (16) with k=0: u^2 (P(phi)-b3) = const
        Pp = b[0]*np.sin(phf)**2 + b[1]*np.cos(phf)**2
        uex = np.sqrt(u0**2*(b[0]*np.sin(0.3)**2+b[1]*np.cos(0.3)**2-b[2])/(Pp-b[2]))
        eor = np.max(np.abs(u - uex))
        spin = (phf[-1]-phf[0])/TT
        prec = (psf[-1]-psf[0])/TT
        r = dict(mu=mu, e29=e29, eor=eor, spin=spin, prec=prec,
                 dth=np.ptp(thf))
        if len(so.t_events[0]):
            r["Tphi"] = so.t_events[0][0]
        out.append(r)
        line = (f"   mu={mu:<5}: max|sin th - (29)|={e29:.2e}  max|sin th - exact orbit|={eor:.2e}"
                f"  theta range={np.ptp(thf):.3f}")
        if "Tphi" in r:
            line += f"  mu*T_phi full={mu*r['Tphi']:.4f}"
        print(line)
        print(f"             mean spin {spin:+.5f}: (34) printed J^-1 D2={D2/JN:+.4f},"
              f" mu J^-1 D2 cos th0={mu*D2*np.cos(th0)/JN:+.5f} | mean precession"
              f" {prec:.5f}: (34) printed J^-1 P* G={Ps*GN/JN:.4f}, (1-mu P*)G/J={(1-mu*Ps)*GN/JN:.5f}")
    return out


FR1 = scene_F("R1 (k=0, n small)", [1.0, 0.8, 2.4], 1.0)
FR2 = scene_F("R2 (k=0, n large)", [1.6, 0.2, 2.4], 0.6)
for F_ in (FR1, FR2):
    x = np.array([r["mu"] for r in F_])
    for key in ("e29", "eor"):
        y = np.array([r[key] for r in F_])
        print(f"  slope log({key}) vs log(mu): {np.polyfit(np.log(x), np.log(y), 1)[0]:.2f}")
    y = np.array([r["mu"]*r["Tphi"] for r in F_])
    print(f"  mu*T_phi linear extrapolation to mu=0: {2*y[3]-y[2]:.4f}")
FR3 = scene_F("R3 (k=(0.6,0.8,0), n small)", [1.0, 0.8, 2.4], 1.0, k=(0.6, 0.8, 0.0),
              Tlong=lambda mu: 200.0)
print(f"  [t={time.time()-T0:.1f}s]")

# mu = 0 limit for R3: zeroth approximation (21), mean precession and spin
kR3 = np.array([0.6, 0.8, 0.0])
T3 = 2*np.pi*JN/np.linalg.norm(kR3)*20
y3 = integ(f0_21(JN, kR3, GN), np.array([1.0, 0.3, 0.0]), T3, np.linspace(0, T3, 3))
print(f"  R3 at mu->0 from (21): mean precession {(y3[2,-1])/T3:.5f}, mean spin {(y3[1,-1]-0.3)/T3:+.5f}"
      f" (20 periods 2 pi J/|k|); (34) does not apply when k != 0")
# (27) can never hold on a full period: Q1^2 + Q2^2 = (b1 k1)^2 + (b2 k2)^2
pp = np.linspace(0, 2*np.pi, 7)
b_ = bN
Q1 = b_[0]*kN[0]*np.sin(pp) + b_[1]*kN[1]*np.cos(pp)
Q2 = b_[0]*kN[0]*np.cos(pp) - b_[1]*kN[1]*np.sin(pp)
print(f"  (27): Q1^2+Q2^2 - (b1k1)^2-(b2k2)^2 on 7 pts: {np.max(np.abs(Q1**2+Q2**2-(b_[0]*kN[0])**2-(b_[1]*kN[1])**2)):.1e}")

# k = mu*kappa: corrected slow orbit equation vs printed (28)/(29)
section("F2 k = mu*kappa: corrected Abel equation  [D2 u + N1] du/dphi = D1 s c u^2 - N2 u")
kap = np.array([0.3, 0.4, 0.0])
JjR = np.array([1.0, 0.8, 2.4])
bR = JjR/JN
PsR = 0.5*(bR[0]+bR[1])
D1R, D2R = (bR[1]-bR[0])*GN, (PsR-bR[2])*GN
nR = D1R/(2*D2R)
th0 = 1.0
yR = np.array([th0, 0.3, 0.0])
print(f" scene R4: J={JN} J_j={JjR.tolist()} k=mu*{kap.tolist()} |G|={GN} theta0=1 phi0=0.3")


def abel_corr(p, u):
    s_, c_ = np.sin(p), np.cos(p)
    N1_ = kap[0]*s_ + kap[1]*c_
    N2_ = kap[0]*c_ - kap[1]*s_
    return (D1R*s_*c_*u**2 - N2_*u)/(D2R*u + N1_)


def abel_corrP(p, u):
    s_, c_ = np.sin(p), np.cos(p)
    P_ = bR[0]*s_**2 + bR[1]*c_**2
    N1_ = kap[0]*s_ + kap[1]*c_
    N2_ = kap[0]*c_ - kap[1]*s_
    return (D1R*s_*c_*u**2 - N2_*u)/((P_ - bR[2])*GN*u + N1_)


def abel_paper(mu):
    def f(p, u):
        s_, c_ = np.sin(p), np.cos(p)
        Q1_ = mu*(bR[0]*kap[0]*s_ + bR[1]*kap[1]*c_)
        return D1R*s_*c_*u**2/(D2R*u - Q1_)
    return f


sa = solve_ivp(abel_corr, (0.3, 0.3-2*np.pi), [np.sin(th0)], method="DOP853", rtol=RTOL,
               atol=ATOL, dense_output=True)
saP = solve_ivp(abel_corrP, (0.3, 0.3-2*np.pi), [np.sin(th0)], method="DOP853", rtol=RTOL,
                atol=ATOL, dense_output=True)
rows4 = []
for mu in MUS:
    k4 = mu*kap
    TT = 1.2*JN*2*np.pi/(mu*abs(D2R)*np.cos(th0))
    so = solve_ivp(f16(1/(JN+mu*JjR), k4, GN), (0, TT), yR, method="DOP853", rtol=RTOL,
                   atol=ATOL, t_eval=np.linspace(0, TT, 4001))
    msk = so.y[1] >= 0.3 - 2*np.pi
    u = np.sin(so.y[0][msk])
    phs = so.y[1][msk]
    sp = solve_ivp(abel_paper(mu), (0.3, 0.3-2*np.pi), [np.sin(th0)], method="DOP853",
                   rtol=RTOL, atol=ATOL, dense_output=True)
    ec = np.max(np.abs(u - sa.sol(phs)[0]))
    ecP = np.max(np.abs(u - saP.sol(phs)[0]))
    ep = np.max(np.abs(u - sp.sol(phs)[0]))
    e29 = np.max(np.abs(u - np.sin(th0)*np.exp(nR*(np.sin(phs)**2-np.sin(0.3)**2))))
    rows4.append((ec, ep, e29, ecP))
    print(f"   mu={mu:<5}: theta in [{so.y[0].min():.3f},{so.y[0].max():.3f}]; orbit error max|sin th - u(phi)| over one phi-turn:"
          f" corrected Abel with P(phi) {ecP:.2e}, corrected Abel with P* {ec:.2e},"
          f" printed (28) {ep:.2e}, (29) {e29:.2e}")
r4 = np.array(rows4)
print(f"   slopes: corrected with P(phi) {np.polyfit(np.log(MUS), np.log(r4[:,3]), 1)[0]:.2f},"
      f" corrected with P* {np.polyfit(np.log(MUS), np.log(r4[:,0]), 1)[0]:.2f},"
      f" printed (28) {np.polyfit(np.log(MUS), np.log(r4[:,1]), 1)[0]:.2f}")

# ====================================================================== G
section("G  proposed scenes: |Q| ranges, dtau/dt margins, full-model check; (17)")
# regular precession (17): a1=a2=a, B1=B2=0
aP = np.array([0.5, 0.5, 0.3]); kP = np.array([0.0, 0.0, 0.4]); GP = 2.0
yP = integ(f16(aP, kP, GP), np.array([0.7, 0.2, 0.0]), 20.0, np.array([0.0, 20.0]))
print(f"  (17) symmetric gyrostat: theta drift {abs(yP[0,-1]-0.7):.1e}; phi rate {(yP[1,-1]-0.2)/20:.10f}"
      f" vs (a3-a)G cos th0 - B3 = {(0.3-0.5)*GP*np.cos(0.7)-0.3*0.4:.10f}; psi rate {yP[2,-1]/20:.10f} vs aG = {0.5*GP}")


def scene_check(label, g, w0, Lf, T):
    qmn, qmx = qrange(g, w0, 200.0)
    sol = run_full(g, w0, Lf, T)
    W, tau = sol.y[:3], sol.y[3]
    ev = zv_dense(g, w0, min(tau.min(), 0), max(tau.max(), 0))
    err = np.max(np.abs(W - ev(tau)))
    qn = np.linalg.norm(np.cross(W.T, g.A*W.T + g.k), axis=1)
    Lv = np.array([Lf(t) for t in sol.t])
    print(f"  {label}: |Q| on ZV orbit [{qmn:.4f},{qmx:.4f}]; min dtau/dt={np.min(1-Lv/qn):+.4f};"
          f" tau(T={T:g})={tau[-1]:.4f}; max|w-w_ZV(tau)|={err:.1e}")
    return qmn, qmx


mu = 0.05
gS = Gyro(JN + mu*JjN, kN)
sS = R313(0.0, 1.0, phk + 0.5)[2, :]
wS = (GN*sS - kN)/gS.A
scene_check("S3 nearly spherical N, mu=0.05, L=0.1 const", gS, wS, lambda t: 0.1, 100.0)
scene_check("S4 nearly spherical N, mu=0.05, L=0.1+0.08 sin(0.5t)", gS, wS,
            lambda t: 0.1 + 0.08*np.sin(0.5*t), 100.0)
scene_check("S5 nearly spherical N, mu=0.05, L=0.3+0.5 sin(0.5t) (sign change)", gS, wS,
            lambda t: 0.3 + 0.5*np.sin(0.5*t), 100.0)
gR = Gyro(JN + mu*np.array([1.0, 0.8, 2.4]), [0, 0, 0])
sR = R313(0.0, 1.0, 0.3)[2, :]
wR = GN*sR/gR.A
scene_check("S6 nearly spherical rigid R1, mu=0.05, L=0.002 const", gR, wR, lambda t: 0.002, 400.0)
print(f"\nTotal run time {time.time()-T0:.1f} s")
