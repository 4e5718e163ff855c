"""The gyrostat's Taylor recursion in its two forms: AVX2 + FMA (chosen at run time on CPUs that
have both) and portable (elsewhere, or with GYROSTAT_PORTABLE_KERNELS=1). Each form runs in its own
process (the choice is made once per process); both are checked against SciPy with the right-hand
side written here and against each other, with rotors, damping and constant torques, with the
attitude, and at rtol 1e-13, where the compensated state and the first coefficient's error
(taylor_rate_error) are used."""

import functools
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import gyrostat

# the directory of the gyrostat this test imported (installed, or the source tree with the built
# module in it), for the child processes
PYTHON_DIR = str(Path(gyrostat.__file__).resolve().parent.parent)

# The members (J, k, D, M0, ω0) and the run, as a script for a fresh process.
SCRIPT = r"""
import json, sys
import numpy as np
import gyrostat as g

rtol, attitude = float(sys.argv[1]), sys.argv[2] == "1"
members = json.loads(sys.argv[3])
out = {"kernel": g.taylor_kernel, "y": []}
for J, k, D, M0, w0 in members:
    torques = [g.LinearDamping(np.array(D)), g.ConstantTorque(np.array(M0))]
    model = g.Model(g.Body(J, k), torques, attitude=attitude)
    sol = g.solve(model, w0, (0.0, 20.0), method="taylor", rtol=rtol, atol=rtol * 1e-3,
                  t_eval=np.linspace(0.0, 20.0, 11))
    assert sol.success, sol.message
    out["y"].append(np.asarray(sol.y).tolist())
print(json.dumps(out))
"""

MEMBERS = [
    ((2.0, 3.0, 4.0), (0.3, -0.2, 0.5), (np.eye(3) * 0.02 + 0.003).tolist(), (0.01, -0.02, 0.03), (0.4, 0.9, -0.3)),
    ((1.0, 1.5, 2.2), (0.0, 0.0, 0.0), np.zeros((3, 3)).tolist(), (0.0, 0.0, 0.0), (1.5, -0.2, 0.7)),
    ((3.0, 3.0, 5.0), (0.0, 0.0, 1.2), np.diag([0.01, 0.0, 0.05]).tolist(), (0.0, 0.05, 0.0), (0.1, 2.0, -1.0)),
]


@functools.lru_cache(maxsize=None)  # each run once per session: the two tests below share them
def run(rtol: float, attitude: bool, portable: bool):
    env = dict(os.environ, PYTHONPATH=PYTHON_DIR + os.pathsep + os.environ.get("PYTHONPATH", ""))
    env.pop("GYROSTAT_PORTABLE_KERNELS", None)
    if portable:
        env["GYROSTAT_PORTABLE_KERNELS"] = "1"
    done = subprocess.run([sys.executable, "-c", SCRIPT, repr(rtol), "1" if attitude else "0", json.dumps(MEMBERS)],
                          env=env, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    out = json.loads(done.stdout)
    return out["kernel"], [np.array(y) for y in out["y"]]


def euler_rhs(J, k, D, M0):
    """ω̇ = J⁻¹ (M0 − D ω − ω × (J ω + k)), written here independently of the library."""
    J, k, D, M0 = (np.array(v, dtype=float) for v in (J, k, D, M0))
    return lambda t, w: (M0 - D @ w - np.cross(w, J * w + k)) / J


@pytest.mark.parametrize("rtol, attitude", [(1e-10, False), (1e-13, False), (1e-10, True)])
def test_both_recursions_follow_scipy_and_each_other(rtol, attitude):
    kernel, fast = run(rtol, attitude, portable=False)
    portable_kernel, portable = run(rtol, attitude, portable=True)
    assert portable_kernel == "portable", "GYROSTAT_PORTABLE_KERNELS=1 selects the portable recursion"
    assert kernel in ("avx2+fma", "portable")
    t_eval = np.linspace(0.0, 20.0, 11)
    for (J, k, D, M0, w0), a, b in zip(MEMBERS, fast, portable):
        ref = solve_ivp(euler_rhs(J, k, D, M0), (0.0, 20.0), w0, method="DOP853", rtol=1e-13, atol=1e-15,
                        t_eval=t_eval).y.T
        scale = np.abs(ref).max()
        # ω over t = 20 (a few periods): measured errors ≤ 1.2·rtol of |ω|; bound 30·rtol, and no
        # less than 1e-12 (SciPy's own error at rtol 1e-13 over this span, ~1e-13)
        bound = max(30 * rtol, 1e-12) * scale
        assert np.abs(a[:, :3] - ref).max() <= bound, f"{kernel} recursion vs SciPy"
        assert np.abs(b[:, :3] - ref).max() <= bound, "portable recursion vs SciPy"
        if attitude:  # |q| = 1 in both
            assert np.abs(np.linalg.norm(a[:, 3:], axis=1) - 1.0).max() < 1e-14


@pytest.mark.parametrize("rtol, attitude", [(1e-10, False), (1e-13, False), (1e-10, True)])
def test_avx2_and_portable_recursions_differ_by_rounding(rtol, attitude):
    kernel, fast = run(rtol, attitude, portable=False)
    if kernel != "avx2+fma":  # both runs would be the portable recursion: comparing it with itself proves nothing
        pytest.skip(f"the AVX2 + FMA recursion is not in use on this CPU (kernel {kernel!r})")
    _, portable = run(rtol, attitude, portable=True)
    for a, b in zip(fast, portable):
        scale = np.abs(b[:, :3]).max()
        # the two forms differ by rounding only (sums in another order, fused multiply-adds), so
        # their step sizes agree to ~1e-15 and the runs far inside their error: measured
        # ≤ 0.008·rtol; bound rtol
        assert np.abs(a - b).max() <= rtol * scale, "AVX2 vs portable recursion"
