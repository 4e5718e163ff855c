"""K(m) and ⟨sn²⟩ = (K − E)/(m K) by polynomial pieces (cpp/include/gyrostat/numeric/complete_elliptic.hpp,
the triaxial averaged model's right-hand side) against mpmath, at the limits k² → 0, the separatrix
k'² → 0 (down to the smallest subnormal), the pieces' ends and the switch at m = ½."""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest

from gyrostat import _core

# a few units of rounding: the pieces' interpolation is within 1e-18 of the functions and their
# coefficients are rounded once (tools/make_complete_elliptic_table.py prints both); the evaluation
# rounds ~10 more times. Beyond m = ½, K − E = E(m1) ln(16/m1)/π + F(m1) is a difference whose terms
# are up to 3× larger than it (at m = ½: 1.49 − 0.99): ⟨sn²⟩ there within 2e-15 (measured 1.4e-15 on
# 10⁴ points, at m = 0.55; the AGM it replaced summed positive terms, ~2e-16)
TOLERANCE, MEAN_SN_SQUARED_NEAR_ONE = 5e-16, 2e-15


def _reference(m: float, m1: float) -> tuple[float, float]:
    """K and (K − E)/(m K) at the parameter the function reads (m up to ½, 1 − m1 beyond), in mpmath
    with enough digits to hold 1 − m1 exactly."""
    with mpmath.workdps(40 if min(m, m1) > 1e-30 else 360):
        exact = mpmath.mpf(m) if m <= 0.5 else 1 - mpmath.mpf(m1)
        if exact == 0:
            return float(mpmath.pi / 2), 0.5
        K, E = mpmath.ellipk(exact), mpmath.ellipe(exact)
        return float(K), float((K - E) / (exact * K))


def _pairs() -> list[tuple[float, float]]:
    small = [0.0, 5e-324, 1e-300, 1e-30, 1e-16, 1e-8, 1e-4, 0.01]
    pairs = [(m, 1.0 - m) for m in small]  # k² → 0: m carries the digits
    pairs += [(1.0 - m1, m1) for m1 in small[1:]]  # the separatrix: m1 carries them
    for i in range(1, 16):  # every end of a piece (i/16), a unit of rounding to either side
        edge = i / 16.0
        for m in (np.nextafter(edge, 0.0), edge, np.nextafter(edge, 1.0)):
            pairs.append((float(m), 1.0 - float(m)) if m <= 0.5 else (1.0 - (1.0 - float(m)), 1.0 - float(m)))
    rng = np.random.default_rng(7)
    pairs += [(float(m), 1.0 - float(m)) for m in rng.uniform(0.0, 1.0, 60)]
    return pairs


@pytest.mark.parametrize("m, m1", _pairs())
def test_K_and_mean_sn_squared_equal_mpmath(m, m1):
    K, S = _core.complete_elliptic(m, m1)
    want_K, want_S = _reference(m, m1)
    assert K == pytest.approx(want_K, rel=TOLERANCE, abs=0.0), (m, m1)
    assert S == pytest.approx(want_S, rel=TOLERANCE if m <= 0.5 else MEAN_SN_SQUARED_NEAR_ONE, abs=0.0), (m, m1)


def test_limits_are_exact_where_the_functions_are_known():
    # K(0) = π/2 and ⟨sn²⟩ = ½ at k² = 0 (the circle); next to the separatrix K → ln(4/k') + O(k'² ln k'),
    # ⟨sn²⟩ → 1 − 1/K (E → 1): at k'² = 1e-300 those leading terms are exact to rounding
    K, S = _core.complete_elliptic(0.0, 1.0)
    assert K == pytest.approx(math.pi / 2, rel=2e-16) and S == pytest.approx(0.5, rel=2e-16)
    K, S = _core.complete_elliptic(1.0, 1e-300)
    assert K == pytest.approx(math.log(4.0) + 150.0 * math.log(10.0), rel=2e-16)
    assert S == pytest.approx(1.0 - 1.0 / K, rel=2e-16)


@pytest.mark.parametrize("m, m1", [(-0.1, 1.1), (float("nan"), 0.5), (0.3, 0.8), (1.5, -0.5), (0.5, float("inf"))])
def test_bad_parameters_are_refused_by_value(m, m1):
    with pytest.raises(ValueError, match="complete_integrals: needs m = k\\^2 and m1 = 1 - m"):
        _core.complete_elliptic(m, m1)


def test_the_table_is_what_its_generator_writes():
    # the header is generated (tools/make_complete_elliptic_table.py, ~1 s): a hand edit, or a change
    # of the generator's pieces or degree without running it, differs here
    import importlib.util
    from pathlib import Path

    path = Path(__file__).resolve().parents[1] / "tools" / "make_complete_elliptic_table.py"
    spec = importlib.util.spec_from_file_location("make_complete_elliptic_table", path)
    generator = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(generator)
    assert generator.OUT.read_text() == generator.table_text()
