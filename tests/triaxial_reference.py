"""Pure-Python reference for the averaged model of a triaxial rigid body under small torques fixed in
the body (derivation: docs/papers/triaxial_averaging.md). NumPy/SciPy in double precision, mpmath
where a test needs more digits (``mp=True``).

Conventions. Moments A = (A1, A2, A3) in principal axes, any order, pairwise distinct or with the
two moments on one side of the middle one equal (the symmetric limit). The free motion has the
invariants G² = Σ A_i² ω_i² and 2T = Σ A_i ω_i²; D = G²/(2T) lies between the smallest and largest
moment. The axis the body circulates about ("a", ω_a never changes sign) is the axis of the
largest moment when D > A_mid and of the smallest when D < A_mid; "c" is the other extreme axis,
"b" the middle one. With u = λ t + u0:

    ω_a = s α_a dn(u, k),   ω_b = −σ s α_b sn(u, k),   ω_c = α_c cn(u, k),

    α_a² = (G² − 2T A_c) / (A_a (A_a − A_c)),   α_b² = (2T A_a − G²) / (A_b (A_a − A_b)),
    α_c² = (2T A_a − G²) / (A_c (A_a − A_c)),   λ² = (A_a − A_b)(G² − 2T A_c) / (A_a A_b A_c),
    k²   = (A_b − A_c)(2T A_a − G²) / ((A_a − A_b)(G² − 2T A_c)),
    k'² = 1 − k² = (A_a − A_c)(G² − 2T A_b) / ((A_a − A_b)(G² − 2T A_c)),

s = ±1 the branch (sign of ω_a: which of the two polar regions), σ = ε_abc sign(A_a − A_c) with
ε_abc = +1 if (a, b, c) is a cyclic permutation of (0, 1, 2), −1 otherwise. The phase φ ∈ [0, 2π) is u = 2Kφ/π: period P = 4K/λ,
φ̇ = 2π/P = πλ/(2K).
"""
import math

import mpmath
import numpy as np
from scipy import special

from references import cavity_torque  # noqa: F401  (Chernousko's torque, also for ω of shape (3, n))

# ---------------------------------------------------------------------------------------------
# The generating motion


def axes(A, G, T):
    """The labels (a, b, c) of the axes (circulated, middle, other extreme), σ and D = G²/(2T)."""
    A = np.asarray(A, float)
    order = np.argsort(A)  # smallest, middle, largest
    lo, mid, hi = (int(i) for i in order)
    D = G * G / (2.0 * T)
    a, b, c = (hi, mid, lo) if D > A[mid] or A[mid] == A[lo] else (lo, mid, hi)
    if A[mid] == A[hi] and A[mid] != A[lo]:
        a, b, c = lo, mid, hi  # oblate symmetric: D ≤ A_mid always, rotation about the smallest axis
    sigma = 1 if (a, b, c) in ((0, 1, 2), (1, 2, 0), (2, 0, 1)) else -1
    sigma *= 1 if A[a] > A[c] else -1
    return a, b, c, sigma, D


def parameters(A, G, T, mp=False):
    """dict(a, b, c, sigma, alpha=(α_a, α_b, α_c), lam=λ, m=k², m1=1 − k²) of the free motion.
    With ``mp=True`` every number is an mpmath mpf at the working precision (inputs are converted
    exactly from their double values)."""
    a, b, c, sigma, _ = axes(A, G, T)
    f = mpmath.mpf if mp else float
    sq = mpmath.sqrt if mp else math.sqrt
    Aa, Ab, Ac = f(A[a]), f(A[b]), f(A[c])
    G2, T2 = f(G) ** 2, 2 * f(T)
    pa = G2 - T2 * Ac  # same sign as A_a − A_c
    pc = T2 * Aa - G2
    pb = G2 - T2 * Ab  # distance to the separatrix, same sign as A_a − A_b
    if Aa == Ab:
        raise ValueError("D = A_mid with A_a = A_b: a permanent rotation, no circulation to average over")
    alpha = (sq(pa / (Aa * (Aa - Ac))), sq(pc / (Ab * (Aa - Ab))), sq(pc / (Ac * (Aa - Ac))))
    lam = sq((Aa - Ab) * pa / (Aa * Ab * Ac))
    m = (Ab - Ac) * pc / ((Aa - Ab) * pa)
    m1 = (Aa - Ac) * pb / ((Aa - Ab) * pa)
    return dict(a=a, b=b, c=c, sigma=sigma, alpha=alpha, lam=lam, m=m, m1=m1)


def ellipk_m1(m1, mp=False):
    """K(k) from the complementary parameter m1 = k'² (accurate near the separatrix, m1 → 0)."""
    return mpmath.ellipk(1 - mpmath.mpf(m1)) if mp else float(special.ellipkm1(m1))


def jacobi(u, m, mp=False):
    """(sn, cn, dn)(u | m): SciPy's ellipj in double, mpmath.ellipfun with ``mp=True``."""
    if mp:
        return (np.array([mpmath.ellipfun(f, x, m=m) for x in u]) for f in ("sn", "cn", "dn"))
    sn, cn, dn, _ = special.ellipj(np.asarray(u, float), float(m))
    return sn, cn, dn


def free_motion(A, G, T, phase, branch=1, mp=False):
    """ω (shape (3,) or (3, n)) of the torque-free body with invariants |G|, T at the phase φ
    (u = 2Kφ/π; φ = 0 is where ω_b = 0 and ω_c is largest) on the branch s = sign ω_a."""
    P = parameters(A, G, T, mp)
    K = ellipk_m1(P["m1"], mp)
    scalar = np.ndim(phase) == 0
    phase = np.atleast_1d(phase)
    u = [2 * K * x / mpmath.pi for x in phase] if mp else 2.0 * K * phase / math.pi
    sn, cn, dn = jacobi(u, P["m"], mp)
    w = np.empty((3, len(phase)), dtype=object if mp else float)
    a, b, c = P["a"], P["b"], P["c"]
    w[a] = branch * P["alpha"][0] * dn
    w[b] = -P["sigma"] * branch * P["alpha"][1] * sn
    w[c] = P["alpha"][2] * cn
    return w[:, 0] if scalar else w


def period(A, G, T, mp=False):
    """P = 4K(k)/λ, the period of ω(t) (ω_a has period P/2)."""
    P = parameters(A, G, T, mp)
    return 4 * ellipk_m1(P["m1"], mp) / P["lam"]


def phase_rate(A, G, T, mp=False):
    """φ̇ = 2π/P = πλ/(2K): the fast phase's rate, a function of the slow variables only."""
    return 2 * (mpmath.pi if mp else math.pi) / period(A, G, T, mp)


# ---------------------------------------------------------------------------------------------
# Averages by quadrature (any torque fixed in the body)


def averaged_rates_quadrature(A, G, T, torque, n, branch=1, mp=False):
    """(d|G|²/dt, dT/dt) = (2⟨G·M⟩, ⟨ω·M⟩) by the n-node trapezoidal rule in the phase over one
    period of the free motion; ``torque(w)`` maps ω of shape (3, n) to M of shape (3, n)."""
    phase = [2 * mpmath.pi * j / n for j in range(n)] if mp else 2.0 * np.pi * np.arange(n) / n
    w = free_motion(A, G, T, phase, branch, mp)
    M = torque(w)
    J = np.array([mpmath.mpf(x) for x in A], dtype=object)[:, None] if mp else np.asarray(A, float)[:, None]
    return 2 * np.sum(J * w * M) / n, np.sum(w * M) / n


def nodes_for(m1, tol):
    """Trapezoid nodes for a relative error ~tol: the integrand is analytic in |Im u| < K' with
    spacing h = 4K/n in u, so the error is ~exp(−π K' n/(2K)); n = 2K ln(C/tol)/(π K'), with a
    margin C = 1e3 for the double poles of ω² (measured in the tests), at least 8, even."""
    K, Kp = float(special.ellipkm1(m1)), float(special.ellipk(m1))
    n = 2.0 * K * math.log(1e3 / tol) / (math.pi * Kp)
    return max(8, 2 * math.ceil(n / 2))


# ---------------------------------------------------------------------------------------------
# Closed forms


def sn_moments(m, m1, mp=False):
    """(S0, S1, S2) = (1, ⟨sn²⟩, ⟨sn⁴⟩) over a period. S1 = R_D(0, k'², 1)/(3 R_F(0, k'², 1)) =
    (K − E)/(k² K) without the cancellation at small k²; S2 = (2(1 + k²) S1 − 1)/(3k²) from the
    recursion (2n+1)k² S_{n+1} = 2n(1 + k²) S_n − (2n−1) S_{n−1} (cancels at small k²: use mp or
    the series S2 = 3/8 + k²/16 + ... there)."""
    if mp:
        S1 = mpmath.elliprd(0, m1, 1) / (3 * mpmath.elliprf(0, m1, 1))
    else:
        S1 = float(special.elliprd(0.0, m1, 1.0) / (3.0 * special.elliprf(0.0, m1, 1.0)))
    S2 = (2 * (1 + m) * S1 - 1) / (3 * m) if m != 0 else 3 * (mpmath.mpf(1) if mp else 1.0) / 8
    return 1, S1, S2


def square_coefficients(A, G, T, mp=False):
    """(P, c0, c1): ω_i² = c0_i + c1_i sn²(u) for i = 0, 1, 2 (sn² because dn² = 1 − k² sn²,
    cn² = 1 − sn²)."""
    P = parameters(A, G, T, mp)
    z = mpmath.mpf(0) if mp else 0.0
    c0, c1 = [z, z, z], [z, z, z]
    aa, ab, ac = (x * x for x in P["alpha"])
    c0[P["a"]], c1[P["a"]] = aa, -P["m"] * aa
    c0[P["b"]], c1[P["b"]] = z, ab
    c0[P["c"]], c1[P["c"]] = ac, -ac
    return P, c0, c1


def mean_squares(A, G, T, mp=False):
    """⟨ω_i²⟩, i = 0, 1, 2, in K and E (through S1 = ⟨sn²⟩):
    ⟨ω_a²⟩ = α_a² E/K, ⟨ω_b²⟩ = α_b² (K − E)/(k²K), ⟨ω_c²⟩ = α_c² (E − k'²K)/(k²K)."""
    P, c0, c1 = square_coefficients(A, G, T, mp)
    _, S1, _ = sn_moments(P["m"], P["m1"], mp)
    return [c0[i] + c1[i] * S1 for i in range(3)]


def averaged_rates_closed_form_linear_damping(A, D, G, T, mp=False):
    """(d|G|²/dt, dT/dt) for M = −D ω: −2 Σ A_i D_ii ⟨ω_i²⟩ and −Σ D_ii ⟨ω_i²⟩ (the off-diagonal
    entries average to zero: ⟨ω_i ω_j⟩ = 0 for i ≠ j). D in principal axes."""
    s = mean_squares(A, G, T, mp)
    Dd = [mpmath.mpf(float(D[i][i])) if mp else float(D[i][i]) for i in range(3)]
    Af = [mpmath.mpf(float(x)) if mp else float(x) for x in A]
    return -2 * sum(Af[i] * Dd[i] * s[i] for i in range(3)), -sum(Dd[i] * s[i] for i in range(3))


def averaged_rates_closed_form_constant(A, moment, G, T, branch=1, mp=False):
    """(d|G|²/dt, dT/dt) for a constant body torque M: ⟨ω⟩ = s α_a π/(2K) e_a (⟨sn⟩ = ⟨cn⟩ = 0,
    ⟨dn⟩ = π/(2K)), so dT/dt = s α_a M_a π/(2K) and d|G|²/dt = 2 A_a dT/dt."""
    P = parameters(A, G, T, mp)
    pi = mpmath.pi if mp else math.pi
    mean_a = branch * P["alpha"][0] * pi / (2 * ellipk_m1(P["m1"], mp))
    Ma = mpmath.mpf(float(moment[P["a"]])) if mp else float(moment[P["a"]])
    Aa = mpmath.mpf(float(A[P["a"]])) if mp else float(A[P["a"]])
    return 2 * Aa * Ma * mean_a, Ma * mean_a


def averaged_rates_closed_form_cavity(A, kappa, G, T, mp=False):
    """(d|G|²/dt, dT/dt) for the viscous cavity: G·M ≡ 0 and
    ω·M = −(κ/(A1A2A3)) Σ_{i<j} (A_i − A_j)² (A_i + A_j − A_k) ω_i² ω_j²,
    with ⟨ω_i² ω_j²⟩ = c0_i c0_j + (c0_i c1_j + c1_i c0_j) S1 + c1_i c1_j S2."""
    P, c0, c1 = square_coefficients(A, G, T, mp)
    _, S1, S2 = sn_moments(P["m"], P["m1"], mp)
    Af = [mpmath.mpf(float(x)) if mp else float(x) for x in A]
    kap = mpmath.mpf(float(kappa)) if mp else float(kappa)
    total = 0
    for i, j, k in ((0, 1, 2), (1, 2, 0), (0, 2, 1)):
        mean = c0[i] * c0[j] + (c0[i] * c1[j] + c1[i] * c0[j]) * S1 + c1[i] * c1[j] * S2
        total += (Af[i] - Af[j]) ** 2 * (Af[i] + Af[j] - Af[k]) * mean
    return 0 * kap, -kap / (Af[0] * Af[1] * Af[2]) * total


def invariants_at(A, m, T=1.0, side="largest"):
    """(|G|, T) whose motion has k² = m, about the axis of the largest or the smallest moment:
    D = [(A_b − A_c) A_a + k² (A_a − A_b) A_c] / [(A_b − A_c) + k² (A_a − A_b)]."""
    lo, mid, hi = sorted(A)
    Aa, Ac = (hi, lo) if side == "largest" else (lo, hi)
    D = ((mid - Ac) * Aa + m * (Aa - mid) * Ac) / ((mid - Ac) + m * (Aa - mid))
    return math.sqrt(2.0 * T * D), T
