"""The tutorial (docs/tutorial.md) runs as written, and the numbers it prints are right: its
flat-spin times for three cavity radii against an independent SciPy integration of paper 000's
averaged equations (5), written here from the paper, not from the library."""

import contextlib
import io
import math
import re
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp

DOCS = Path(__file__).resolve().parent.parent / "docs"

# the tutorial's satellite and damper (section 1)
A, C, A0, R0 = 12.0, 4.0, 0.05, 2.0
RHO, NU = 970.0, 2.0


@pytest.fixture(scope="module")
def printed(tmp_path_factory):
    """What the tutorial's code blocks print, run in order in one namespace in a fresh folder."""
    blocks = re.findall(r"```python\n(.*?)```", (DOCS / "tutorial.md").read_text(), flags=re.S)
    assert len(blocks) >= 8
    folder = tmp_path_factory.mktemp("tutorial")
    namespace = {"__name__": "tutorial"}
    out = io.StringIO()
    with contextlib.chdir(folder), contextlib.redirect_stdout(out):
        for index, block in enumerate(blocks):
            exec(compile(block, f"tutorial.md python block {index}", "exec"), namespace)
    return out.getvalue(), folder, namespace


def scipy_flat_spin_time(radius: float) -> float:
    """Paper 000, eq. (5), the averaged system of a symmetric body with a viscous cavity:
    da/dt = kappa C (A - C) r^2 a / A^3, dr/dt = kappa (C - A) a^2 r / (A C), kappa = rho P0 / nu,
    P0 = 8 pi b^7 / 525; the time r falls through |G| cos 80° / C."""
    kappa = RHO * 8 * math.pi * radius**7 / 525 / NU
    G = math.hypot(A * A0, C * R0)
    r_flat = G * math.cos(math.radians(80.0)) / C

    def rates(t, y):
        a, r = y
        return [kappa * C * (A - C) * r * r * a / A**3, kappa * (C - A) * a * a * r / (A * C)]

    def flat(t, y):
        return y[1] - r_flat
    flat.terminal, flat.direction = True, -1
    run = solve_ivp(rates, (0.0, 1e7), [A0, R0], method="DOP853", rtol=1e-11, atol=1e-13, events=flat)
    assert run.status == 1
    return float(run.t_events[0][0])


def test_the_tutorial_prints_the_flat_spin_times_scipy_finds(printed):
    text, _, _ = printed
    swept = {float(b): float(h) for b, h in re.findall(r"b = (\S+) m: flat spin after (\S+) h", text)}
    assert sorted(swept) == [0.2, 0.25, 0.3]
    for radius, hours in swept.items():
        # printed to 1e-4 h (rounding: 5e-5 h); the sweep's averaged rung and SciPy agree to ~1e-6
        assert hours == pytest.approx(scipy_flat_spin_time(radius) / 3600, abs=1e-4), radius
    closed = {float(b): float(h) for b, h in re.findall(r"b = (\S+) m: closed form (\S+) h", text)}
    assert closed == pytest.approx(swept, abs=1e-4)
    assert float(re.search(r"flat-spin time ~ b\^(\S+)", text).group(1)) == pytest.approx(-7.0, abs=1e-3)


def test_the_full_model_and_the_ladder_agree_with_scipy(printed):
    text, _, namespace = printed
    reference = scipy_flat_spin_time(0.25)
    full = float(re.search(r"stopped by 'flat spin' at t = (\S+) s", text).group(1))
    assert full == pytest.approx(reference, rel=1e-5)  # the full Euler equations, DOP853 at rtol 1e-8
    ladder = re.search(r"ladder rung 'averaged': t_flat = (\S+) s in (\d+) steps", text)
    assert float(ladder.group(1)) == pytest.approx(reference, rel=1e-5)
    assert int(ladder.group(2)) < 100 < namespace["sol"].stats["steps"]
    assert "broken assumptions: []" in text
    assert re.search(r"Reynolds number .*: 0\.0625 \(limit 0\.1, holds: True\)", text)


def test_the_dense_output_gives_states_and_named_outputs_between_outputs(printed):
    text, _, namespace = printed
    sol, G = namespace["sol"], namespace["G"]
    # the kinetic energy at the flat spin: (A a1^2 + C r_flat^2) / 2 with |G| fixed
    r_flat = G * math.cos(math.radians(80.0)) / C
    a1 = math.sqrt(G**2 - (C * r_flat) ** 2) / A
    start, end = map(float, re.search(r"energy (\S+) J -> (\S+) J", text).groups())
    assert start == pytest.approx((A * A0**2 + C * R0**2) / 2, abs=1e-4)
    assert end == pytest.approx((A * a1**2 + C * r_flat**2) / 2, abs=2e-4)
    theta = float(re.search(r"theta\(\d+ s\) = (\S+) deg", text).group(1))
    p, q, r = sol(namespace["t_half"])
    assert theta == pytest.approx(math.degrees(math.acos(C * r / G)), abs=0.01)
    assert 4.3 < theta < 80.0


def test_the_tutorial_writes_its_scene_and_plot(printed):
    _, folder, _ = printed
    assert "viscous_cavity" in (folder / "flat_spin.toml").read_text()
    assert (folder / "flat_spin.png").stat().st_size > 10_000
