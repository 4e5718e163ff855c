"""The probe: a rung and the top run over a window at the start, their difference giving the
rung's measured error constant and its growth, extrapolated to the horizon (:func:`probe`)."""

from __future__ import annotations

import math
import time
import warnings

import numpy as np

from gyrostat import _core
from gyrostat.ladder.rungs import PROBE_FRACTION, PROBE_PERIODS, SAFETY, Estimate, Rung, rates
from gyrostat.solution import AccuracyWarning, Solution
from gyrostat.solve import make_options, solve


# ------------------------------------------------------------------------------------ the probe
PROBE_SAMPLES = 201
"""The probe compares the rungs at this many evenly spaced times of its window."""
_PROBED = ("method", "rtol", "atol", "max_steps")
_DEFAULT = _core.Options()


def _solve(rung: Rung, y0, span, options: dict, t_eval=None, events=None) -> Solution:
    kept = {k: v for k, v in options.items() if k in _PROBED}
    return solve(rung.model, y0, span, **kept, t_eval=t_eval, events=events, check_validity=False, progress=False)


def _run_on_engine(rung: Rung, y0, span, opts) -> Solution:
    """A probe's run: the engine called once with Options made beforehand (the checks of
    :func:`gyrostat.solve` were made on the scene's own runs)."""
    return Solution(_core.solve(rung.model._core, np.asarray(y0, float), float(span[0]), float(span[1]), opts, None),
                    rung.model)


def _segment(rung: Rung, y0, span, opts) -> Solution:
    """A piece of a switching run: the engine called with the rung's Options made once; the run's
    doubts warned about as :func:`gyrostat.solve` warns them."""
    solution = _run_on_engine(rung, y0, span, opts)
    for doubt in solution.accuracy_warnings:
        warnings.warn(doubt, AccuracyWarning, stacklevel=3)
    return solution


def probe(rung: Rung, top: Rung, span: tuple[float, float], options: dict) -> Estimate:
    """The rung's error against the top, measured at the start and extrapolated to the horizon.

    Both run over [t0, t0 + T], T = min(20 fast periods, span/20), compared at 201 times:
    d(t) = |Δ(compared quantities)| / max |compared quantities of the top|. The estimate at the
    horizon t1 is SAFETY · (max(max d, floor) + g (t1 − t0 − T)), g = max(0, max d(second half) −
    max d(first half)) / (T/2): the oscillating O(ε) part, plus the drift measured over the window,
    grown linearly (quadratically, g (t² / 1.5T), where ω(t) itself is compared). The floor
    rtol·√(fast periods in the span) is the integrators' own error (per-period local errors adding
    up like a random walk), which the comparison with the top cannot resolve below."""
    t0, t1 = span
    window = min(PROBE_PERIODS * rung.fast_period, PROBE_FRACTION * (t1 - t0))
    times = np.linspace(t0, t0 + window, PROBE_SAMPLES)
    opts = make_options(**{k: v for k, v in options.items() if k in _PROBED}, t_eval=times)
    started = time.perf_counter()
    upper = _run_on_engine(top, top.y0, (t0, t0 + window), opts)
    middle = time.perf_counter()
    lower = _run_on_engine(rung, rung.y0, (t0, t0 + window), opts)
    ended = time.perf_counter()
    return _estimate(rung, top, span, options, window, upper, lower, {top.name: middle - started,
                                                                       rung.name: ended - middle})


def _estimate(rung: Rung, top: Rung, span, options: dict, window: float, upper: Solution, lower: Solution,
              seconds: dict) -> Estimate:
    """The estimate from the two runs of a probe over [t0, t0 + window] at PROBE_SAMPLES times."""
    t0, t1 = span
    samples = PROBE_SAMPLES
    if not (upper.success and lower.success) or len(upper) != samples or len(lower) != samples:
        failed = upper if not upper.success else lower
        return Estimate(math.inf, math.inf, math.inf, (t0, t0 + window), seconds,
                        f"the probe failed ({failed.status}: {failed.message})")

    def extrapolated(reference, values, quadratic: bool, law: str, basis: str, small: float | None = None) -> Estimate:
        reference = np.asarray(reference, float)
        apart = reference - values
        scale = float(np.sqrt((reference * reference).sum(axis=1)).max()) or 1.0  # the rows' norms, as np.linalg.norm
        difference = np.sqrt((apart * apart).sum(axis=1)) / scale
        measured = float(difference.max())
        half = samples // 2
        growth = max(0.0, float(difference[half:].max() - difference[:half].max())) / (0.5 * window)
        rest = max(0.0, t1 - t0 - window)
        # d = c t²: the halves' maxima differ by (3/4) c T², so growth = 1.5 c T and c = growth / (1.5 T)
        # the integrators' own error as a floor: per-period local errors ~ rtol adding up like a random walk
        periods = (t1 - t0) / rung.fast_period
        floor = float(options.get("rtol", _DEFAULT.rtol)) * math.sqrt(max(periods, 1.0))
        value = SAFETY * (max(measured, floor) + (growth * (rest + rest**2 / (1.5 * window)) if quadratic
                                                 else growth * rest))
        text = (f"probe over [{t0:g}, {t0 + window:g}] ({window / rung.fast_period:.3g} fast periods): largest relative "
                f"difference {measured:.3g} (at least rtol x sqrt(fast periods) = {floor:.3g}, the integrators' own), "
                f"growth {growth:.3g} per unit time, extrapolated {law} to t = {t1:g}, times {SAFETY:g}" + basis
                + (f"; constant of the O(small) error: {measured / small:.3g}" if small else ""))
        return Estimate(value, measured, growth, (t0, t0 + window), seconds, text)

    law = ("quadratically (the fast phase is compared)" if rung.phase_compared else
           "linearly (an exact reduction: the difference is the integrators' own, and grows as theirs)" if rung.exact
           else "linearly")
    estimate = extrapolated(top.compare(upper), rung.compare(lower), rung.phase_compared, law,
                            f"; {rung.basis}" if rung.basis else "", rung.small)
    if rung.fast_compare is not None:
        # linearly: the carried phase advances at the averaged frequency, right at the slow variables' current
        # values to O(eps) with zero mean over a fast period, so its error grows like the slow variables' (the
        # quadratic law read 1.34 where omega's measured error was 4.6e-4 on a damped triaxial body at eps = 1e-5)
        estimate.fast = extrapolated(rates(upper), rung.fast_compare(lower), False,
                                     "linearly (the carried phase runs at the averaged frequency)",
                                     "; omega at the carried phase against the top's: reported, not used for the choice")
    return estimate
