"""The slopes of the averaged top's v = <cos theta> (model::nutation_slopes, lagrange_top.hpp) against
mpmath: v recomputed at 50 digits from the nutation cubic's roots and K, E, and differentiated
numerically, on generic states, through the double root (regular precession, m = k^2 -> 0, where
each root's slope grows as 1/(u2 - u1) and only their weighted sum stays finite) and towards the
separatrix (m -> 1, where v's slope grows without bound and the roots' conditioning with it).

The averaged top's Jacobian is built from these slopes; its sensitivities are checked against
central differences of plain runs in tests/test_sensitivities.py.
"""

from __future__ import annotations

import mpmath as mp
import numpy as np
import pytest
from scipy.optimize import brentq

from gyrostat import _core

A, C, MU = 2.0, 1.0, 0.5
NAMES = ("G_z", "H", "r", "mu")


def first_integrals(p, q, r, theta, phi=0.3, A=A, C=C, mu=MU):
    """(A, C, mu, G_z, H, r) of the top at (p, q, r) with gamma = (sin th sin phi, sin th cos phi, cos th)."""
    gamma = np.array([np.sin(theta) * np.sin(phi), np.sin(theta) * np.cos(phi), np.cos(theta)])
    G_z = A * (p * gamma[0] + q * gamma[1]) + C * r * gamma[2]
    H = 0.5 * (A * (p * p + q * q) + C * r * r) + mu * gamma[2]
    return (A, C, mu, G_z, H, r)


def v_reference(A, C, mu, G_z, H, r):
    """v = u3 - (u3 - u1) E(m)/K(m) at 50 digits. Near a double root a perturbed state's u1, u2 may
    be a complex pair: v is symmetric in u1 and u2 (the imaginary-modulus transformation), so the
    same formula continues it analytically and stays real."""
    A, C, mu, G_z, H, r = map(mp.mpf, (A, C, mu, G_z, H, r))
    a = 2 * H - C * r * r
    # f(u) = A (a - 2 mu u)(1 - u^2) - (G_z - C r u)^2
    coefficients = [A * a - G_z * G_z, -2 * mu * A + 2 * G_z * C * r, -A * a - C * C * r * r, 2 * mu * A]  # u^0 ... u^3
    roots = mp.polyroots(coefficients, maxsteps=400, extraprec=400, asc=True)
    u3 = max(roots, key=lambda x: (abs(mp.im(x)) < mp.mpf(10) ** -30, mp.re(x)))
    u1, u2 = sorted((x for x in roots if x is not u3), key=lambda x: (mp.re(x), mp.im(x)))
    m = (u2 - u1) / (u3 - u1)
    if m == 0:
        return mp.re(u1)
    return mp.re(u3 - (u3 - u1) * mp.ellipe(m) / mp.ellipk(m))


def slopes_reference(case):
    """(dv/dG_z, dv/dH, dv/dr, dv/dmu) by mpmath's numerical derivative of v_reference."""
    with mp.workdps(50):
        out = []
        for index in (3, 4, 5, 2):  # G_z, H, r, mu in (A, C, mu, G_z, H, r)

            def v_along(x, index=index):
                moved = list(case)
                moved[index] = x
                return v_reference(*moved)

            out.append(float(mp.diff(v_along, mp.mpf(case[index]), h=mp.mpf("1e-20"))))
        return np.array(out)


def relative_errors(case):
    got = np.array(_core.lagrange_nutation_slopes(*case))
    want = slopes_reference(case)
    return np.abs(got - want) / np.abs(want), want


@pytest.mark.parametrize(
    "state",
    [(0.3, 0.1, 5.0, 0.6), (0.8, -0.4, 1.0, 1.2), (0.5, 0.5, 0.3, 2.0, 0.3, 1.0, 0.7, 2.0)],
    ids=["fast top", "mid nutation", "other moments"],
)
def test_slopes_of_generic_states_match_mpmath(state):
    p, q, r, theta, *rest = state
    case = first_integrals(p, q, r, theta) if not rest else first_integrals(p, q, r, theta, *rest)
    errors, want = relative_errors(case)
    # measured 2e-16 ... 1.4e-14 (the roots' rounding through the divided differences); bound 1e-12
    assert np.all(errors < 1e-12), f"slopes {dict(zip(NAMES, want))}: relative errors {errors}"


def regular_precession():
    """The spin-up w of a top at theta = 0.8, r = 3 released at a turning point (p, q) = w (sin phi,
    cos phi), where its nutation vanishes: u1 = u2 = cos theta."""
    theta, phi = 0.8, 0.3

    def case(w):
        return first_integrals(w * np.sin(phi), w * np.cos(phi), 3.0, theta, phi)

    def apart(w):
        n = _core.lagrange_nutation(*case(w))
        return n.u1 + n.u2 - 2.0 * np.cos(theta)

    return case, brentq(apart, 0.1, 0.2, xtol=1e-16)


@pytest.mark.parametrize("dw", [0.0, 1e-9, 1e-6, 1e-4, 1e-2])
def test_slopes_through_the_double_root_match_mpmath(dw):
    """k^2 -> 0: at the double root (m ~ 5e-9 from the roots' rounding) and beside it. Each root's
    slope alone is ~1/(u2 - u1) (1e8 here): a formula that summed them would lose ~8 digits."""
    case_of, w0 = regular_precession()
    case = case_of(w0 + dw)
    m = _core.lagrange_nutation(*case).m
    assert m < 5e-3
    errors, want = relative_errors(case)
    # measured 1e-16 ... 2.4e-14 at m = 7e-17 ... 3.6e-3; bound 1e-12
    assert np.all(errors < 1e-12), f"m = {m:.3g}: slopes {dict(zip(NAMES, want))}, relative errors {errors}"


@pytest.mark.parametrize("theta", [0.3, 1e-2, 1e-3])
def test_slopes_towards_the_separatrix_match_mpmath(theta):
    """k^2 -> 1: a slow top released near the upright position (1 - m = theta^2/4 at r -> 0), where
    v's slope grows as 1/(1 - m) and the roots u2, u3 merge: the double-precision roots carry
    ~eps/(1 - m) relative error, and the slopes with them."""
    case = first_integrals(0.0, 0.0, 0.01, theta)
    one_minus_m = 1.0 - _core.lagrange_nutation(*case).m
    errors, want = relative_errors(case)
    # measured 1e-14, 1e-11, 1.1e-9 at 1 - m = 2.2e-2, 2.5e-5, 2.5e-7 (~2.5e-16/(1 - m)); bound 1e-13/(1 - m)
    bound = 1e-13 / one_minus_m
    assert np.all(errors < bound), f"1 - m = {one_minus_m:.3g}: slopes {want}, relative errors {errors} (bound {bound:.2g})"
    assert abs(want[1]) > 1.0 / (10.0 * np.sqrt(one_minus_m))  # dv/dH does grow towards it (4.9, 896, 4.9e4)


def roots_reference(A, C, mu, G_z, H, r):
    """The nutation cubic's three roots at 50 digits, ascending (real parts: a double root's pair)."""
    A, C, mu, G_z, H, r = map(mp.mpf, (A, C, mu, G_z, H, r))
    a = 2 * H - C * r * r
    coefficients = [A * a - G_z * G_z, -2 * mu * A + 2 * G_z * C * r, -A * a - C * C * r * r, 2 * mu * A]
    with mp.workdps(50):
        return sorted(mp.re(x) for x in mp.polyroots(coefficients, maxsteps=400, extraprec=400, asc=True))


@pytest.mark.parametrize("state, u3_bound, apart_bound", [
    ((0.3, -0.2, 1.2, 0.7), 4e-16, 1e-14),     # generic
    ((1.1, 0.4, -0.7, 1.75), 4e-16, 1e-14),    # hanging below the horizontal
    ((0.0, 0.0, 9.0, 0.3), 4e-16, 2e-12),      # fast spin, small nutation: u2 - u1 = 2.3e-3 (measured 4.3e-13)
    ((0.02, 0.0, 0.1, 2.5), 4e-16, 1e-14),     # slow: u3 far above 1
    ((0.0, 0.0, 3.0, 0.0), 4e-16, 3e-8),       # the fast sleeping top: u1 = u2 = 1, a double root (m = 0)
    ((1e-7, 0.0, 1.0, 0.0), 3e-8, 3e-8),       # next to the slow sleeping top: u2, u3 -> 1 (m = 1 - 1.8e-14)
])
def test_roots_against_mpmath(state, u3_bound, apart_bound):
    """u3 by Newton's iteration from above and regula falsi (model::nutation, 2026-11-29; bisection
    before) against the cubic's roots at 50 digits: a simple u3 to 4e-16 relative (2 ulps: the cubic
    is evaluated in doubles; measured 2.5e-17 … 2.5e-16), u1 and u2 to 1e-14 (deflated from u3: their
    error grows as ε |s1| / (u2 − u1), 2e-12 where they are 2.3e-3 apart); at a double root, where a
    root moves as the square root of the rounding (√ε ~ 1.5e-8), to 3e-8. Then v (symmetric in u1, u2:
    their errors cancel to first order) to 1e-14 absolute and the period to 1e-12 relative, against
    the reference roots with mpmath's K and E, the period next to the separatrix too (m = 1 − 1.8e-14:
    m1 taken from the roots)."""
    p, q, r, theta = state
    integrals = first_integrals(p, q, r, theta)
    n = _core.lagrange_nutation(*integrals)
    u1, u2, u3 = roots_reference(*integrals)
    assert abs(n.u3 - u3) <= u3_bound * u3, f"u3 {n.u3!r} against {mp.nstr(u3, 20)} (bound {u3_bound:g} relative)"
    for name, mine, ref in (("u1", n.u1, u1), ("u2", n.u2, u2)):
        assert abs(mine - ref) <= apart_bound, f"{name} {mine!r} against {mp.nstr(ref, 20)} (bound {apart_bound:g})"
    m = (u2 - u1) / (u3 - u1)
    with mp.workdps(50):
        K, E = mp.ellipk(m), mp.ellipe(m)
        v = u3 - (u3 - u1) * E / K
        period = 2 * K / mp.sqrt(integrals[2] * (u3 - u1) / (2 * integrals[0]))
    assert abs(n.v - v) <= 1e-14, f"v {n.v!r} against {mp.nstr(v, 20)} (bound 1e-14)"
    if m < 1:
        assert abs(n.period - period) <= 1e-12 * period, f"period {n.period!r} against {mp.nstr(period, 20)}"
