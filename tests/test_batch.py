"""SIMD batch ensembles through the Python API: batched members against their single runs and
against SciPy with the right-hand side written here; lanes that fail beside lanes that finish;
the averaged model; what the batch does not cover runs alone, bit for bit."""

from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import gyrostat as g


def euler_rhs(J, k, D, M0):
    """ω̇ = J⁻¹ (M0 − D ω − ω × (J ω + k)), written here independently of the library."""

    def f(t, w):
        return (M0 - D @ w - np.cross(w, J * w + k)) / J

    return f


def members(n=11):
    """n gyrostats with other moments, rotors, damping and torques per member (not a multiple of
    any lane width), and ω0 from 0.05 to ~50 in size, so that lanes need very different step counts."""
    out = []
    for i in range(n):
        J = np.array([1.0 + 0.1 * i, 2.0 + 0.05 * i, 3.0 - 0.07 * i])
        k = np.array([0.1, -0.2, 0.05 * i]) if i % 3 == 0 else np.zeros(3)
        D = 0.01 * (1 + i) * np.eye(3) + 0.001 if i % 2 == 0 else np.zeros((3, 3))
        M0 = np.array([0.01, -0.02, 0.03 * i]) if i % 4 == 1 else np.zeros(3)
        torques = []
        if i % 2 == 0:
            torques.append(g.LinearDamping(D))
        if i % 4 == 1:
            torques.append(g.ConstantTorque(M0))
        w0 = 0.05 * 2.0 ** i * np.array([np.cos(i), 0.5, -np.sin(0.7 * i)])
        out.append((g.Model(g.Body(J, k), torques), w0, euler_rhs(J, k, D, M0)))
    return out


@pytest.mark.parametrize("method", ["taylor", "dop853"])
def test_batched_members_against_scipy_and_their_single_runs(method):
    cases = members()
    models, y0s = [c[0] for c in cases], [c[1] for c in cases]
    t_eval = np.linspace(0.0, 10.0, 21)
    batched = g.solve_ensemble(models, y0s, (0.0, 10.0), method=method, rtol=1e-10, atol=1e-12, t_eval=t_eval,
                               threads=2)
    single = g.solve_ensemble(models, y0s, (0.0, 10.0), method=method, rtol=1e-10, atol=1e-12, t_eval=t_eval,
                              threads=2, batch=False)
    steps = []
    for (model, w0, rhs), b, s in zip(cases, batched, single):
        assert b.success and s.success
        ref = solve_ivp(rhs, (0.0, 10.0), w0, method="DOP853", rtol=1e-13, atol=1e-15, t_eval=t_eval).y.T
        scale = np.abs(ref).max()
        # rtol 1e-10 over up to ~100 periods: the global error stays below 1e-7 of |ω|
        assert np.abs(b.y - ref).max() <= 1e-7 * scale, "batch vs SciPy"
        # the batch and the scalar run follow the same rules per lane: they differ by rounding
        # (and for taylor by the batch's common order), within 100 rtol
        assert np.abs(b.y - s.y).max() <= 100 * 1e-10 * scale, "batch vs its single run"
        assert abs(b.stats["steps"] - s.stats["steps"]) <= 1 + s.stats["steps"] // 20
        steps.append(s.stats["steps"])
    assert max(steps) > 10 * min(steps), "the lanes need very different numbers of steps"


def test_attitude_lanes_keep_unit_quaternions_and_match_single_runs():
    cases = members(9)
    models = [g.Model(c[0].body, c[0].torques, attitude=True) for c in cases]
    y0s = [c[1] for c in cases]
    batched = g.solve_ensemble(models, y0s, (0.0, 15.0), method="taylor", rtol=1e-11, atol=1e-13, n_out=16)
    single = g.solve_ensemble(models, y0s, (0.0, 15.0), method="taylor", rtol=1e-11, atol=1e-13, n_out=16, batch=False)
    for (model, w0, rhs), b, s in zip(cases, batched, single):
        q = b.y[:, 3:]
        assert np.abs(np.linalg.norm(q, axis=1) - 1.0).max() < 1e-14  # projected after every step
        assert np.abs(b.y - s.y).max() <= 100 * 1e-11 * max(1.0, np.abs(s.y).max())
        # the attitude against q̇ = ½ q ⊗ (0, ω) integrated here with the member's ω̇ = rhs (no
        # projection in the reference): measured at most 2.1e-12 over the 9 lanes; 10× it
        ref = solve_ivp(lambda t, y: np.concatenate([rhs(t, y[:3]), 0.5 * quaternion_times_omega(y[3:], y[:3])]),
                        (0.0, 15.0), b.y[0], method="DOP853", rtol=1e-13, atol=1e-14, t_eval=b.t).y.T
        ref_q = ref[:, 3:] / np.linalg.norm(ref[:, 3:], axis=1)[:, None]
        assert np.abs(q - ref_q).max() < 2.1e-11, np.abs(q - ref_q).max()


def quaternion_times_omega(q, w):
    """q ⊗ (0, ω), written out (w, x, y, z)."""
    qw, qx, qy, qz = q
    p, qq, r = w
    return np.array([-qx * p - qy * qq - qz * r, qw * p + qy * r - qz * qq, qw * qq + qz * p - qx * r,
                     qw * r + qx * qq - qy * p])


def test_taylor_lanes_carry_their_rounding_error_at_tight_tolerances():
    """Below rtol 1e-12 the batch's Taylor lanes carry the state's rounding error from step to step
    (compensated, as the scalar path): 64 torque-free members over t = 200 at rtol 3e-14 against
    the closed form (g.torque_free, exact to ~1e-15 here). Measured (relative errors, median and
    largest): the lanes 9.2e-15 and 1.3e-13; the single runs (the SSE2 form runs its Taylor
    members so) 3.3e-15 and 5.9e-14; single runs with the state rounded once per step (Horner's
    scheme alone, built for the measurement) 2.8e-14 and 3.4e-13 (order + 8), 3.1e-14 and 7.7e-13
    (+ 6, the lanes' order): the random walk of the rounding. Bounds: median 1.5e-14 (1.6x above
    the lanes', 1.9x below the uncompensated runs'), largest 2.5e-13 (2x above the lanes', below
    the uncompensated runs'). (At rtol 1e-13 the truncation error of the larger steps at order + 8
    is of the same size as the rounding's walk, 3.4e-13 compensated against 2.6e-13 not, and no
    bound there tells the two apart.)"""
    body = g.Body([2.0, 3.0, 4.0])
    y0s = np.random.default_rng(1).uniform(-1.0, 1.0, size=(64, 3))
    exact = np.array([g.torque_free(body, w, [0.0, 200.0]).y[-1] for w in y0s])
    runs = g.solve_ensemble(g.Model(body), y0s, (0.0, 200.0), method="taylor", rtol=3e-14, atol=1e-16,
                            t_eval=[0.0, 200.0], error_estimate=False)
    final = np.array([r.y[-1] for r in runs])
    error = np.linalg.norm(final - exact, axis=1) / np.linalg.norm(y0s, axis=1)
    assert all(r.success for r in runs), [r.message for r in runs if not r.success]
    assert np.median(error) < 1.5e-14 and error.max() < 2.5e-13, (np.median(error), error.max())


def test_a_failing_lane_beside_lanes_that_finish():
    model = g.Model(g.Body([1.0, 2.0, 3.0]))
    y0s = np.array([[1.0, 0.5, -0.3], [1e150, 2e150, -1e150], [0.2, -0.4, 0.9], [0.5, 0.5, 0.5], [-1.0, 0.1, 0.2]])
    for method in ("taylor", "dop853"):
        batched = g.solve_ensemble(model, y0s, (0.0, 10.0), method=method, rtol=1e-10, atol=1e-12, n_out=11)
        single = g.solve_ensemble(model, y0s, (0.0, 10.0), method=method, rtol=1e-10, atol=1e-12, n_out=11,
                                  batch=False)
        assert batched[1].status == single[1].status == "non_finite_state", batched[1].message
        for i in (0, 2, 3, 4):
            assert batched[i].success
            # torque-free: the closed form is the reference (rtol 1e-10 over ~10 periods: < 1e-8)
            exact = g.torque_free(model.body, y0s[i], batched[i].t).y
            assert np.abs(batched[i].y - exact).max() < 1e-8 * np.abs(y0s[i]).max()


def test_averaged_members_batch_against_single_runs():
    body_moments = [(8.0, 8.0, 4.0 + 0.3 * i) for i in range(6)]
    models = [g.AveragedModel(g.Body(m), [g.ViscousCavity(1260.0, 1000.0 * (1 + 0.1 * i), 0.48)])
              for i, m in enumerate(body_moments)]
    y0s = [[1.0 + 0.1 * i, 0.5 - 0.1 * i] for i in range(6)]
    # batch against scalar integration of the same equations: whether the averaging holds for
    # these cavities is not under test here (check_validity=False)
    batched = g.solve_ensemble(models, y0s, (0.0, 50.0), rtol=1e-10, atol=1e-12, n_out=11, method="dop853",
                               check_validity=False)
    single = g.solve_ensemble(models, y0s, (0.0, 50.0), rtol=1e-10, atol=1e-12, n_out=11, method="dop853", batch=False,
                              check_validity=False)
    for b, s in zip(batched, single):
        assert b.success
        assert np.abs(b.y - s.y).max() <= 100 * 1e-10 * np.abs(s.y).max()


def test_what_no_batch_covers_runs_alone_bit_for_bit():
    """Events, and torques outside the affine ones, keep the scalar path: equal to single solves."""
    cavity = g.Model(g.Body([1.0, 2.0, 3.0]), [g.ViscousCavity(1.0, 0.5, 0.1)])
    y0s = np.array([[1.0, 0.5, -0.3], [0.2, -0.4, 0.9], [0.5, 0.5, 0.5]])
    ens = g.solve_ensemble(cavity, y0s, (0.0, 5.0), method="dop853", n_out=6)
    for y0, e in zip(y0s, ens):
        one = g.solve(cavity, y0, (0.0, 5.0), method="dop853", n_out=6)
        assert np.array_equal(e.y, one.y)


def test_simd_lanes_are_reported():
    """numeric/lanes.hpp and docs/integrators.md: 8 doubles per batch with AVX-512, 4 otherwise
    (two SSE2 registers per operation on the baseline x86-64 build)."""
    assert g.simd_instruction_set in ("sse2", "avx", "avx2", "avx512f", "scalar")
    assert g.simd_lanes == (8 if g.simd_instruction_set == "avx512f" else 4)


def _cpu_flags() -> set[str]:
    try:
        with open("/proc/cpuinfo") as info:
            return next((set(line.split(":", 1)[1].split()) for line in info if line.startswith("flags")), set())
    except OSError:
        return set()


def _runs(isa: str) -> bool:
    """Whether this CPU runs the batches' plugin for `isa` and the plugin is installed beside _core."""
    from pathlib import Path

    needs = {"avx2": {"avx2", "fma"}, "avx512": {"avx512f", "avx512dq", "avx512vl", "avx512bw"}}[isa]
    return needs <= _cpu_flags() and (Path(g._core.__file__).parent / f"_batch_{isa}.so").exists()


def _session_form(isa: str) -> bool:
    """Whether this test session's batches are the `isa` form (its widest, or GYROSTAT_SIMD's)."""
    return g.simd_instruction_set == {"avx512": "avx512f"}.get(isa, isa)


def _in_process(asked: str, code: str) -> str:
    import os
    import subprocess
    import sys

    env = {**os.environ, "GYROSTAT_SIMD": asked}
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True)
    return out.stdout.strip()


def test_the_widest_instruction_set_the_cpu_runs_is_chosen():
    """Runtime dispatch of the SIMD lanes: the default build loads the widest form of the batches
    the CPU runs (AVX-512, then AVX2 + FMA, else its own SSE2 form); GYROSTAT_SIMD asks for one."""
    expected = "avx512f" if _runs("avx512") else "avx2" if _runs("avx2") else g.simd_instruction_set
    if g.simd_instruction_set not in ("sse2", "avx2", "avx512f"):
        pytest.skip(f"a native build ({g.simd_instruction_set}) carries its own batches")
    # the portable SSE2 lanes on a CPU that runs wider ones: the install lost its plugins (a wheel
    # without them passes everything else, slower)
    if g.simd_instruction_set == "sse2":
        assert not {"avx2", "fma"} <= _cpu_flags(), (
            f"this CPU runs AVX2 but {Path(g._core.__file__).parent} has no _batch_avx2.so: the default install "
            "must carry the batches' plugins")
    assert g.simd_instruction_set == expected and g.simd_lanes == (8 if expected == "avx512f" else 4)
    report = "import gyrostat as g; print(g.simd_instruction_set, g.simd_lanes)"
    assert _in_process("sse2", report) == "sse2 4"
    if _runs("avx2"):
        assert _in_process("avx2", report) == "avx2 4"
    with pytest.raises(ValueError, match="GYROSTAT_SIMD = 'neon': choose sse2, avx2 or avx512"):
        g._core.load_batches("", "neon")


@pytest.mark.parametrize("isa", ["sse2", "avx2", "avx512"])
def test_every_instruction_set_of_the_batches_agrees_with_single_runs(isa):
    """Each form of the batches (SSE2, AVX2 + FMA, AVX-512) passes this file's tests against the
    scalar path and SciPy, in a process that asked for it."""
    import os
    import subprocess
    import sys

    if isa != "sse2" and not _runs(isa):
        pytest.skip(f"this CPU does not run the {isa} batches, or their plugin is not installed")
    if _session_form(isa):
        pytest.skip(f"this session runs the {isa} batches: its own run of these tests is that form's")
    env = {**os.environ, "GYROSTAT_SIMD": isa}
    check = f"import gyrostat as g; assert g.simd_instruction_set == {('avx512f' if isa == 'avx512' else isa)!r}"
    subprocess.run([sys.executable, "-c", check], env=env, check=True)
    result = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", __file__, "-k",
                             "not instruction_set"], env=env, capture_output=True, text=True)
    assert result.returncode == 0, result.stdout[-3000:]
