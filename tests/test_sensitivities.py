"""Forward sensitivities (``gyrostat.solve(..., sensitivities=...)``, ``Solution.sensitivity``)
against references that do not use them:

1. the averaged symmetric body under linear damping: its closed form and exact derivatives;
2. SciPy's DOP853 (rtol 1e-12, atol 1e-14) on variational systems written here: Euler's equations
   of a triaxial body under M = −Dω (Jacobian and ∂f/∂p by hand) and under the viscous cavity
   (∂f/∂ω and ∂f/∂J by complex step of tests/references.cavity_torque, ∂f/∂ν = −M/(νJ) by hand);
3. central differences of plain ``gyrostat.solve`` runs at two steps for the other families;
4. the outputs |G| and T: the chain rule from the state sensitivities and the definitions;
5. the errors a caller can make.

An error is max over times and components of |mine − reference| / max |reference|: one scale per
derivative, so that a component whose derivative is 0 is measured against the others.

The references were checked on their own (scratch runs, not repeated here): the closed form of 1
against central differences (h, h/2, Richardson) of SciPy runs of (ȧ, ṙ) written out, to 1.1e-11;
the variational systems of 2 against central differences (Richardson) of SciPy runs of
tests/references.euler_rhs at rtol 1e-13, to 9e-10 (the differences' own error); the differences
of 3 at h and h/2 agree to 5e-8 or better (h/4 as well).
"""

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import gyrostat as g
from gyrostat import lagrange as lg
from gyrostat import orthogonal as o
from references import cavity_torque


def rel_error(mine, ref):
    mine, ref = np.asarray(mine, float), np.asarray(ref, float)
    assert mine.shape == ref.shape, f"shape {mine.shape}, reference {ref.shape}"
    return float(np.max(np.abs(mine - ref)) / np.max(np.abs(ref)))


def run(model, y0, t, **kw):
    return g.solve(model, y0, (t[0], t[-1]), t_eval=t, progress=False, **kw)


# ------------------------------------------------------------------------------- 1. closed form
# ȧ = −(D11 + D22) a/(2A), ṙ = −D33 r/C (LinearDamping's averaged contribution, moments (A, A, C)):
# a = a0 e^(−(D11+D22)t/(2A)), r = r0 e^(−D33 t/C)
A_AV, C_AV, D11, D33, A0, R0 = 1.0, 1.8, 0.05, 0.08, 0.3, 1.2  # C < 2A: C ± h stays a body
T_AV = np.linspace(0.0, 40.0, 41)


def averaged_exact(t):
    """(a, r) and their exact derivatives {name: (n, 2)}."""
    ea, er = np.exp(-D11 * t / A_AV), np.exp(-D33 * t / C_AV)
    a, r, zero = A0 * ea, R0 * er, np.zeros_like(t)
    return np.column_stack([a, r]), {
        "a": np.column_stack([ea, zero]),
        "r": np.column_stack([zero, er]),
        "moments[2]": np.column_stack([zero, r * D33 * t / C_AV**2]),   # ∂r/∂C
        "LinearDamping.matrix[2,2]": np.column_stack([zero, -r * t / C_AV]),
        "torques[0].matrix[0,0]": np.column_stack([-a * t / (2 * A_AV), zero]),  # D11 alone, not D22
    }


def test_averaged_closed_form():
    model = g.AveragedModel(g.Body([A_AV, A_AV, C_AV]), [g.LinearDamping(diagonal=[D11, D11, D33])])
    y, exact = averaged_exact(T_AV)
    names = list(exact) + ["LinearDamping.matrix[0,1]"]
    sol = run(model, [A0, R0], T_AV, rtol=1e-12, atol=1e-14, sensitivities=names)
    assert sol.success, sol.message
    assert sol.sensitivities == tuple(names), sol.sensitivities
    assert rel_error(sol.y, y) < 1e-10, "the run itself must follow the closed form (rtol 1e-12)"
    for name, ref in exact.items():
        err = rel_error(sol.sensitivity(name), ref)
        # 1e-9: an rtol-1e-12 run of two decaying exponentials over 40 s (≤ 2 e-folds) is good to
        # ~1e-11, the sensitivities' error being controlled with the state's; ∂f/∂C as a central
        # difference adds ~1e-11. A wrong term (missing 1/C², t) is off by O(1).
        assert err < 1e-9, f"d(a, r)/d {name}: relative error {err:.2e} against the closed form (bound 1e-9)"
    off = np.max(np.abs(sol.sensitivity("LinearDamping.matrix[0,1]")))
    # D12 averages out (not in ȧ, ṙ): its derivative is 0 up to rounding
    assert off < 1e-12, f"d(a, r)/d D12 must be 0 (D12 averages out), got max |.| = {off:.2e}"


# ------------------------------------------------------------------------------- 2. SciPy variational
J3 = np.array([1.0, 1.4, 2.1])
D_FULL = np.array([[0.05, 0.01, 0.0], [0.02, 0.08, -0.01], [0.0, 0.01, 0.03]])
W0 = np.array([0.2, 0.3, 1.0])  # near the major axis: a stable rotation, well conditioned
T_VAR = np.linspace(0.0, 20.0, 41)
RHO, NU, P0 = 1.0, 2.0, 0.5  # κ = ρP0/ν = 0.25: the cavity acts over the span


def skew(v):
    return np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])


def damped_variational(J, D, entries):
    """f = J⁻¹(−Dω − ω × Jω) and its sensitivities S (3 × (6 + len(entries))): columns ω0 (3),
    J_k (3), D_ij for (i, j) in entries. Ṡ = ∂f/∂ω S + ∂f/∂p with, by hand,
    ∂f/∂ω = J⁻¹(−D + [Jω×] − [ω×]J), ∂f_i/∂J_k = −(ω × e_k ω_k)_i/J_i − δ_ik f_i/J_i,
    ∂f_i/∂D_ij = −ω_j/J_i."""
    def rhs(t, y):
        w, S = y[:3], y[3:].reshape(3, -1)
        f = (-D @ w - np.cross(w, J * w)) / J
        jac = (-D + skew(J * w) - skew(w) * J) / J[:, None]
        dp = np.zeros_like(S)
        for k in range(3):
            dp[:, 3 + k] = -np.cross(w, np.eye(3)[k] * w[k]) / J
            dp[k, 3 + k] -= f[k] / J[k]
        for n, (i, j) in enumerate(entries):
            dp[i, 6 + n] = -w[j] / J[i]
        return np.concatenate([f, (jac @ S + dp).ravel()])
    return rhs, 6 + len(entries)


def cavity_variational(J, rho, nu, p0, k):
    """f = J⁻¹(M(ω) − ω × Jω), M the cavity's (tests/references.py); columns ω0 (3), J_k, ν.
    ∂f/∂ω and ∂f/∂J_k by complex step, Im f(x + ih)/h with h = 1e-30 (exact to rounding for this
    rational f: no subtraction); ∂f/∂ν = −M/(νJ) by hand (M ∝ κ = ρP0/ν)."""
    kappa, h = rho * p0 / nu, 1e-30

    def f(w, moments):
        return (cavity_torque(w, moments, kappa) - np.cross(w, moments * w)) / moments

    def rhs(t, y):
        w, S = y[:3], y[3:].reshape(3, -1)
        jac = np.column_stack([f(w + 1j * h * e, J).imag / h for e in np.eye(3)])
        dp = np.zeros_like(S)
        dp[:, 3] = f(w, J + 1j * h * np.eye(3)[k]).imag / h
        dp[:, 4] = -cavity_torque(w, J, kappa) / (nu * J)
        return np.concatenate([f(w, J), (jac @ S + dp).ravel()])
    return rhs, 5


def variational_reference(rhs, columns, w0, t):
    """(ω (n, 3), S (n, 3, columns)) by SciPy DOP853 at rtol 1e-12, atol 1e-14; S(0) = [I | 0]."""
    s0 = np.zeros((3, columns))
    s0[:, :3] = np.eye(3)
    sol = solve_ivp(rhs, (t[0], t[-1]), np.concatenate([w0, s0.ravel()]), method="DOP853", t_eval=t,
                    rtol=1e-12, atol=1e-14)
    assert sol.success, sol.message
    return sol.y[:3].T, sol.y[3:].T.reshape(len(t), 3, columns)


SCIPY_CASES = {
    "damping": (lambda: g.Model(g.Body(list(J3)), [g.LinearDamping(matrix=D_FULL)]),
                lambda: damped_variational(J3, D_FULL, [(0, 1), (2, 2)]),
                ["p", "q", "r", "moments[0]", "moments[1]", "moments[2]", "LinearDamping.matrix[0,1]",
                 "torques[0].matrix[2,2]"], None),
    "cavity": (lambda: g.Model(g.Body(list(J3)), [g.ViscousCavity(density=RHO, viscosity=NU, p0=P0)]),
               lambda: cavity_variational(J3, RHO, NU, P0, 1),
               ["p", "q", "r", "moments[1]", "ViscousCavity.viscosity"], "dop853"),
}


@pytest.mark.parametrize("case", SCIPY_CASES)
def test_against_scipy_variational_equations(case):
    build, reference, names, method = SCIPY_CASES[case]
    w_ref, S_ref = variational_reference(*reference(), W0, T_VAR)
    sol = run(build(), W0, T_VAR, rtol=1e-11, atol=1e-13, method=method, sensitivities=names)
    assert sol.success, sol.message
    assert rel_error(sol.y, w_ref) < 1e-9, f"{case}: ω itself against SciPy (rtol 1e-11 vs 1e-12)"
    for j, name in enumerate(names):
        err = rel_error(sol.sensitivity(name), S_ref[:, :, j])
        # 1e-8: gyrostat at rtol 1e-11 and SciPy at 1e-12 over 20 s of a stable, damped rotation
        # are good to ~1e-10 on ω; the sensitivities, in the same error norm, likewise (~100x margin)
        assert err < 1e-8, f"{case}: dω/d {name}: relative error {err:.2e} against SciPy's variational run (bound 1e-8)"


# ------------------------------------------------------------------------------- 3. central differences
Q0 = np.array([0.9, 0.1, -0.3, 0.2]) / np.linalg.norm([0.9, 0.1, -0.3, 0.2])
TOP_Y0 = lg.initial_state([0.2, -0.1, 1.7], 1.0, 0.3)


def moving_mass(damping=10.0):
    return g.MovingMassModel(g.Body([1.5, 1.5, 1.0]), mass=0.01, arm=1.0, frequency=30.0, damping=damping)


def top(mu=0.5):
    return lg.LagrangeTop(1.5, 1.0, mu, [lg.paper_torque(0.1)])


def averaged_top(mu=0.5):
    return lg.LagrangeAveraged(1.5, 1.0, mu, [lg.paper_torque(0.05)])


def triaxial(d11=0.01):
    return g.TriaxialAveragedModel(g.Body(list(J3)), [g.LinearDamping(diagonal=[d11, 0.02, 0.015])])


def orthogonal(A2=3.0):
    return o.OrthogonalModel(g.Body([2.0, A2, 4.0], [0.3, -0.2, 0.5]), 0.1)


def attitude(d33=0.03):
    return g.Model(g.Body(list(J3)), [g.LinearDamping(diagonal=[0.05, 0.08, d33])], attitude=True)


# Torques that read the attitude: ∂M/∂q enters the variational equations (the orbit's rate is fast
# here, 0.5 rad/s, so that the gravity gradient turns the body within the span)
def gravity_gradient(C=2.1):
    return g.Model(g.Body([1.0, 1.4, C]), [g.GravityGradient()], orbit=g.Orbit(rate=0.5))


def inertial(m1=0.2):
    return g.Model(g.Body(list(J3)), [g.InertialTorque([0.1, m1, -0.3]), g.LinearDamping(diagonal=[0.01, 0.02, 0.03])],
                   attitude=True)


def top_inertial(mu=0.5):
    return lg.LagrangeTop(1.5, 1.0, mu, [g.InertialTorque([0.3, -0.2, 0.1])])


def orthogonal_inertial(m1=0.2):
    return o.OrthogonalModel(g.Body([2.0, 3.0, 4.0]), 0.1, torques=[g.InertialTorque([0.1, m1, -0.3])], attitude=True)


# family → (model builder, its nominal parameter, y0, span, solve keywords). The averaged models
# start from their own state (not from ω, whose conversion would depend on the parameter). The
# averaged top's scene breaks rate·T_nut ≪ 1 (N > 0.5 by t = 10): its equations are differentiated, not its
# asymptotics, so no validity check.
FAMILIES = {
    "moving_mass": (moving_mass, 10.0, np.r_[0.3, 0.1, 1.0, np.zeros(6)], 5.0, {}),
    "lagrange_top": (top, 0.5, TOP_Y0, 5.0, {}),
    "lagrange_averaged": (averaged_top, 0.5, averaged_top().initial_state(TOP_Y0), 20.0,
                          dict(check_validity=False)),
    "triaxial_averaged": (triaxial, 0.01, triaxial().initial_state(W0), 20.0, {}),
    "orthogonal": (orthogonal, 3.0, np.array([1.0, 0.5, -0.8, 0.0]), 10.0, {}),
    "attitude": (attitude, 0.03, np.r_[W0, Q0], 5.0, {}),
    "gravity_gradient": (gravity_gradient, 2.1, np.r_[0.05, -0.02, 0.5, Q0], 10.0, {}),
    "inertial": (inertial, 0.2, np.r_[W0, Q0], 10.0, {}),
    "orthogonal_inertial": (orthogonal_inertial, 0.2, np.r_[1.0, 0.5, -0.8, Q0, 0.0], 10.0, {}),
    "top_inertial": (top_inertial, 0.5, TOP_Y0, 5.0, {}),
}
# (family, name asked, whether it is the builder's parameter (else a component of y0), step / |value|):
# 1e-4 balances truncation (~h²) and the runs' noise (~1e-13/h); the orthogonal model's third
# derivative in A2 is large (1e-5: spread 2e-9 vs 2e-7 at 1e-4), the triaxial averaged runs are
# noisier (3e-3: spread 5e-8, truncation-dominated; 3e-7 at 1e-4); the gravity gradient's C likewise
# (3e-5: spread 2.2e-7 at 1e-4)
DIFFERENCE_CASES = [("moving_mass", "damping", True, 1e-4), ("moving_mass", "q", False, 1e-4),
                    ("lagrange_top", "mu", True, 1e-4), ("lagrange_top", "p", False, 1e-4),
                    ("lagrange_averaged", "mu", True, 1e-4), ("lagrange_averaged", "H", False, 1e-4),
                    ("triaxial_averaged", "LinearDamping.matrix[0,0]", True, 3e-3),
                    ("orthogonal", "moments[1]", True, 1e-5), ("orthogonal", "r", False, 1e-4),
                    ("attitude", "torques[0].matrix[2,2]", True, 1e-4), ("attitude", "p", False, 1e-4),
                    ("attitude", "q_x", False, 1e-4),  # solve normalises the quaternion given: d/dq_x includes it
                    # an attitude torque: without ∂M/∂q in the equations these read 0.7-1.0 (before 2026-11-29)
                    ("gravity_gradient", "q_y", False, 1e-4), ("gravity_gradient", "p", False, 1e-4),
                    ("gravity_gradient", "moments[2]", True, 3e-5), ("inertial", "q_z", False, 1e-4),
                    ("inertial", "torques[0].moment[1]", True, 1e-4), ("orthogonal_inertial", "q_w", False, 1e-4),
                    ("top_inertial", "q_y", False, 1e-4), ("top_inertial", "mu", True, 1e-4)]


def central_difference(family, name, is_parameter, t, h):
    """(y(+h) − y(−h))/2h of plain runs at rtol 1e-13: the model rebuilt with its parameter moved,
    or y0's component moved (solve normalises a quaternion y0 as it would any other)."""
    build, value, y0, _, kw = FAMILIES[family]
    ends = []
    for sign in (1, -1):
        if is_parameter:
            model, start = build(value + sign * h), y0
        else:
            model, start = build(), np.array(y0, float)
            start[build().state_names.index(name)] += sign * h
        sol = run(model, start, t, rtol=1e-13, atol=1e-15, error_estimate=False, **kw)
        assert sol.success, sol.message
        ends.append(sol.y)
    return (ends[0] - ends[1]) / (2 * h)


@pytest.mark.parametrize("family,name,is_parameter,step", DIFFERENCE_CASES,
                         ids=[f"{f}-{n}" for f, n, *_ in DIFFERENCE_CASES])
def test_against_central_differences(family, name, is_parameter, step):
    build, value, y0, span, kw = FAMILIES[family]
    t = np.linspace(0.0, span, 21)
    moved = value if is_parameter else y0[build().state_names.index(name)]
    h = step * abs(moved)
    coarse, fine = (central_difference(family, name, is_parameter, t, x) for x in (h, h / 2))
    # the reference checks itself: truncation O(h²) quarters from h to h/2 and the runs' noise
    # (~1e-13/h relative) is ~1e-9: their distance bounds fine's error (1/3 of it for truncation, at
    # most all of it for noise) to 2e-7, a fifth of the bound below (measured ≤ 5e-8)
    spread = rel_error(coarse, fine)
    assert spread < 2e-7, f"{family} d/d {name}: central differences at h, h/2 differ by {spread:.2e}: reference unusable"
    sol = run(build(), y0, t, rtol=1e-10, atol=1e-12, sensitivities=name, **kw)
    assert sol.success, sol.message
    assert sol.sensitivities == (name,), sol.sensitivities
    mine = sol.sensitivity(name)
    assert mine.shape == (len(t), len(build().state_names)), mine.shape
    err = rel_error(mine, fine)
    # 1e-6: the requirement; the run at rtol 1e-10 (~1e-9) and the reference (≤ 5e-8) are far below
    assert err < 1e-6, f"{family}: dy/d {name}: relative error {err:.2e} against central differences (bound 1e-6)"
    if family == "triaxial_averaged":
        branch = mine[:, build().state_names.index("branch")]
        assert np.all(branch == 0.0), f"branch is a label (ds/dt = 0): its derivative must be 0, got {branch}"


def test_cvode_bdf_starts_from_the_normalised_quaternion():
    """A quaternion given with |q| = 0.975: solve normalises it for every method, and the variational
    run by cvode_bdf must start there too (it ran from q as given before 2026-11-29: the state 2.3e-2
    off, dy/d moment 5.2e-3, with a reported error of 2.8e-9)."""
    y0 = np.r_[W0, 0.9, 0.1, 0.3, 0.2]
    t = np.linspace(0.0, 10.0, 11)
    name = "torques[0].moment[1]"
    h = 1e-4 * 0.2
    moved = [run(inertial(0.2 + sign * h), y0, t, rtol=1e-13, atol=1e-15, error_estimate=False) for sign in (1, -1)]
    reference = (moved[0].y - moved[1].y) / (2 * h)
    plain = run(inertial(), y0, t, rtol=1e-13, atol=1e-15, error_estimate=False)
    sol = run(inertial(), y0, t, rtol=1e-11, method="cvode_bdf", sensitivities=name)
    assert sol.success, sol.message
    # 1e-7: BDF at rtol 1e-11 over 10 s (measured 3.4e-9); the unnormalised start read 2.3e-2
    assert rel_error(sol.y, plain.y) < 1e-7, f"the state against the normalised start's: {rel_error(sol.y, plain.y):.2e}"
    err = rel_error(sol.sensitivity(name), reference)
    # 1e-6 as above (measured 1.3e-8; 5.2e-3 from the unnormalised start)
    assert err < 1e-6, f"dy/d {name} by cvode_bdf: relative error {err:.2e} against central differences (bound 1e-6)"


def test_output_sensitivities_where_their_parts_cancel():
    """The averaged top's nutation roots u1, u2 and modulus m near small nutation: their derivative in
    μ is the sum of a change through the state and one through μ itself, each ~9 where the sum is
    ~0.45; taken as one central difference along (S, 1) it holds to ~1e-8 (taken apart, each part's
    truncation left 1e-3; before 2026-11-29)."""
    y0 = lg.initial_state([0.1, 0.2, 2.0], theta=np.radians(50.0), phi=0.3, psi=0.2)
    t = [0.0, 5.0]

    def plain(mu):
        return run(lg.LagrangeAveraged(1.5, 1.0, mu), y0, t, rtol=1e-13, atol=1e-15, error_estimate=False)

    sol = run(lg.LagrangeAveraged(1.5, 1.0, 0.5), y0, t, rtol=1e-11, error_estimate=False, sensitivities="mu")
    for output in ("u1", "u2", "m", "u3", "v"):
        coarse, fine = ((plain(0.5 + h)[output] - plain(0.5 - h)[output]) / (2 * h) for h in (5e-6, 2.5e-6))
        spread = rel_error(coarse, fine)
        assert spread < 1e-7, f"d{output}/dmu: central differences at h, h/2 differ by {spread:.2e}: reference unusable"
        err = rel_error(sol.sensitivity("mu", of=output), fine)
        # 1e-6: the differences agree to ≤ 1e-7 (measured ~1e-9); the output's derivative measured 1e-8 … 4e-8
        assert err < 1e-6, f"d{output}/dmu: relative error {err:.2e} against central differences (bound 1e-6)"


# ------------------------------------------------------------------------------- 4. outputs
@pytest.mark.parametrize("name", ["q", "moments[1]", "LinearDamping.matrix[0,1]"])
def test_output_sensitivities_follow_the_chain_rule(name):
    model = g.Model(g.Body(list(J3)), [g.LinearDamping(matrix=D_FULL)])  # no rotor: G = Jω
    sol = run(model, W0, T_VAR, rtol=1e-11, atol=1e-13, sensitivities=[name, "p"])
    assert sol.success, sol.message
    w, S = sol.y, sol.sensitivity(name)
    explicit = np.zeros(3)  # ∂J/∂name: moments[k] enters T and |G| explicitly
    if name.startswith("moments["):
        explicit[int(name[8])] = 1.0
    G = J3 * w
    T_parts = np.column_stack([J3 * w * S, 0.5 * explicit * w**2])                # T = ½ Σ J_i ω_i²
    G_parts = G * (J3 * S + explicit * w) / np.linalg.norm(G, axis=1)[:, None]  # |G| = |Jω|
    dT, dG = T_parts.sum(axis=1), G_parts.sum(axis=1)
    T_terms, G_terms = np.abs(T_parts).sum(axis=1), np.abs(G_parts).sum(axis=1)
    for output, ref, terms in (("kinetic_energy", dT, T_terms), ("angular_momentum_norm", dG, G_terms)):
        mine = sol.sensitivity(name, of=output)
        err = float(np.max(np.abs(mine - ref)) / np.max(terms))
        # measured against the size of the terms the derivative sums (|dT/dp| is ~0.1 of them here:
        # a sum with cancellation); 1e-9: ~10x the state sensitivities' own error at rtol 1e-11 (an
        # output's derivative must not be much worse than the state's it comes from)
        assert err < 1e-9, f"d {output}/d {name}: error {err:.2e} of its terms' size against the chain rule (bound 1e-9)"
    # a state component's derivative is its column of the state sensitivity
    np.testing.assert_allclose(sol.sensitivity(name, of="r"), S[:, 2], rtol=1e-14, atol=0,
                               err_msg=f"d r/d {name} must be column r of sensitivity({name!r}) (rounding only)")


# ------------------------------------------------------------------------------- 5. errors
def damped():
    return g.Model(g.Body(list(J3)), [g.LinearDamping(matrix=D_FULL)])


@pytest.mark.parametrize("asked", ["moments[7]", ["p", "ViscousCavity.viscosity"], "LinearDamping.gain"])
def test_unknown_name_lists_the_valid_ones(asked):
    with pytest.raises(ValueError) as info:
        run(damped(), W0, T_VAR, sensitivities=asked)
    message = str(info.value)
    wrong = asked if isinstance(asked, str) else asked[1]
    assert wrong in message, f"the message must name the unknown {wrong!r}: {message}"
    for valid in ("moments[0]", "LinearDamping.matrix[2,2]", "torques[0].matrix[1,0]"):
        assert valid in message, f"the message must list the valid names ({valid!r} missing): {message}"


def test_an_orbit_torque_on_the_models_orbit_lists_its_parameters():
    """A GravityGradient that takes the model's orbit has no orbit parameters of its own (None): the
    names listed are the body's (this raised a TypeError from abs(None) before 2026-11-29)."""
    model = gravity_gradient()
    assert g.sensitivity.parameter_names(model) == ("moments[0]", "moments[1]", "moments[2]", "rotor[0]", "rotor[1]",
                                                    "rotor[2]")
    with pytest.raises(ValueError, match=r"no parameter or state component 'GravityGradient.orbit_rate'.*moments\[0\]"):
        run(model, np.r_[W0, Q0], T_VAR, sensitivities="GravityGradient.orbit_rate")


@pytest.mark.parametrize("build, value, name", [
    (lambda r=0.5: g.Model(g.Body(list(J3)), [g.GravityGradient(orbit_rate=r)], attitude=True), 0.5,
     "GravityGradient.orbit_rate"),
    (lambda d=0.1: g.Model(g.Body(list(J3)), [g.DipoleFieldTorque(dipole=[d, 0.0, 0.0], field_strength=3.0)],
                           orbit=g.Orbit(rate=0.3)), 0.1, "DipoleFieldTorque.dipole[0]"),
], ids=["own orbit's rate", "on the model's orbit"])
def test_an_orbit_torques_parameters(build, value, name):
    """An orbit torque's own orbit rate (the model's orbit follows it), and a parameter of one on the
    model's orbit (its orbit parameters are None: left out when it is rebuilt): both were listed by
    parameter_names and refused before 2026-11-29. Against central differences of plain runs."""
    y0, t = np.r_[0.05, -0.02, 0.5, Q0], np.linspace(0.0, 10.0, 3)
    sol = run(build(), y0, t, rtol=1e-11, sensitivities=[name])
    ends = [run(build(value + sign * 1e-5 * value), y0, t, rtol=1e-13, atol=1e-15, error_estimate=False).y
            for sign in (1, -1)]
    reference = (ends[0] - ends[1]) / (2e-5 * value)
    err = rel_error(sol.sensitivity(name), reference)
    # 1e-6 as above (measured 3.9e-9 and 3.0e-10)
    assert err < 1e-6, f"dy/d {name}: relative error {err:.2e} against central differences (bound 1e-6)"


@pytest.mark.parametrize("method", ["splitting", "auto", "cvode_adams"])
def test_other_methods_are_refused(method):
    with pytest.raises(ValueError, match=method):
        run(damped(), W0, T_VAR, method=method, sensitivities=["p"])


def test_derivative_not_asked_is_a_key_error():
    sol = run(damped(), W0, T_VAR, sensitivities="p")
    assert sol.sensitivities == ("p",), f"a str is one name: {sol.sensitivities}"
    assert sol.sensitivity("p").shape == (len(T_VAR), 3), sol.sensitivity("p").shape
    with pytest.raises(KeyError, match=r"moments\[1\]"):
        sol.sensitivity("moments[1]")
