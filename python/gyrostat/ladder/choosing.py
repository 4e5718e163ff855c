"""The choice: the cheapest rung that can answer, whose assumptions hold at the start and
whose measured estimate meets the accuracy (:func:`choose`), kept per scene (:func:`scene_key`)
so that solving a scene again skips its probes."""

from __future__ import annotations

import copy
import dataclasses
import io
import math
import pickle

import numpy as np

from gyrostat.ladder.probe import probe
from gyrostat.ladder.rungs import ACCURACY, PROBE_FRACTION, PROBE_PERIODS, SAFETY, Choice, Estimate, Rung


CACHE_SIZE = 64
"""The choices of this many scenes are kept (:func:`scene_key`): solving a scene again skips its probes."""
_CHOICES: dict[bytes, Choice] = {}


class _PlainPickler(pickle.Pickler):
    """Pickles numbers, strings, booleans, lists, tuples, tables and NumPy arrays and scalars (their
    bytes: every digit), and refuses anything else (a Python callable, say) with TypeError."""

    def reducer_override(self, value):
        if isinstance(value, (np.ndarray, np.generic)) and value.dtype != object:
            return _plain_array, (value.dtype.str, np.shape(value), value.tobytes())
        if isinstance(value, float):  # a float's subclass (gyrostat.kind.Unstated): its type and value
            return type(value), (float(value),)
        if value is _plain_array:
            return NotImplemented  # (by its name)
        raise TypeError(type(value).__name__)


def _plain_array(dtype: str, shape: tuple, data: bytes) -> np.ndarray:
    """The array a scene key holds (_PlainPickler)."""
    return np.frombuffer(data, dtype=dtype).reshape(shape)


def scene_key(doc: dict) -> bytes | None:
    """The scene document (defaults filled in) as bytes: equal documents give equal rungs, models
    and probes, hence the same choice (a table written in another key order is another key: it is
    probed once more). None for a document holding anything but numbers, strings, booleans, lists,
    tables and NumPy arrays (a Python callable, say): such a scene is probed every time. (A
    pickle: ~4 µs for a paper's scene, where sorted JSON took ~30.)"""
    buffer = io.BytesIO()
    try:
        _PlainPickler(buffer, protocol=pickle.HIGHEST_PROTOCOL).dump(doc)
    except (TypeError, pickle.PicklingError):
        return None
    return buffer.getvalue()


def choose(rungs: list[Rung], span: tuple[float, float], options: dict, accuracy: float = ACCURACY,
           key: bytes | None = None) -> Choice:
    """The cheapest rung that can answer, whose assumptions hold at the start and whose measured
    estimate is at most ``accuracy``; the top when none is.

    With ``key`` (:func:`scene_key` of the scene that made the rungs) the choice of the last
    :data:`CACHE_SIZE` scenes is kept: the same scene solved again reuses it, probes and all
    (``Choice.reused``; its report says so), instead of probing again. The choice is a function
    of the scene alone (its rungs, span, options and accuracy all come from it), so it is the
    same choice."""
    if key is not None:
        cached = _CHOICES.get(key)
        if cached is not None:
            return dataclasses.replace(cached, entries=_copied(cached.entries), reused=True)
        made = choose(rungs, span, options, accuracy)
        if len(_CHOICES) >= CACHE_SIZE:
            _CHOICES.pop(next(iter(_CHOICES)))
        _CHOICES[key] = made
        return made
    rungs = list(rungs)
    top = rungs[-1]
    entries: list[dict] = []
    for index, rung in enumerate(rungs[:-1]):
        entry = {"rung": rung.name, "model": rung.description}
        entries.append(entry)
        if rung.blocked:
            entry.update(taken=False, reason=rung.blocked + _carried_phase_miss(rung, top, span, options, accuracy,
                                                                                entry))
            continue
        broken = [a for a in rung.start_checks() if not a.holds]
        if broken:
            entry.update(taken=False, reason="assumption broken at the start: " + "; ".join(map(str, broken)))
            continue
        if rung.name == "closed_form":
            entry.update(taken=True, reason="nothing perturbs the body: the exact flow needs no integration",
                         estimate=None)
            return Choice(rungs, rung, accuracy, entries + _rest(rungs, rung))
        t0, t1 = span
        if not math.isfinite(rung.fast_period) or PROBE_PERIODS * rung.fast_period > PROBE_FRACTION * (t1 - t0):
            entry.update(taken=False, reason=(
                f"the span holds {(t1 - t0) / rung.fast_period:.3g} fast periods: too few for the averaging to pay "
                f"(a probe of {PROBE_PERIODS} periods would cost more than {PROBE_FRACTION:.0%} of the full run)"))
            continue
        estimate = probe(rung, top, span, options)
        refusal = "" if estimate.value <= accuracy else f"estimated error {estimate.value:.3g} > accuracy {accuracy:g}"
        if not refusal:
            rung, refusal = _fit_watches(rung, estimate, accuracy)
            rungs[index] = rung
        entry["estimate"] = estimate.as_dict()
        if refusal:
            entry.update(taken=False, reason=refusal)
            continue
        if estimate.value <= accuracy:
            entry.update(taken=True, reason=f"estimated error {estimate.value:.3g} <= accuracy {accuracy:g}")
            return Choice(rungs, rung, accuracy, entries + _rest(rungs, rung), estimate)
        entry.update(taken=False, reason=f"estimated error {estimate.value:.3g} > accuracy {accuracy:g}")
    entries.append({"rung": top.name, "model": top.description, "taken": True,
                    "reason": "the scene's most complete model (the reference of the rungs below)"})
    return Choice(rungs, top, accuracy, entries)


def _carried_phase_miss(rung: Rung, top: Rung, span, options: dict, accuracy: float, entry: dict) -> str:
    """For a rung blocked because the outputs need ω(t) (:attr:`Rung.probe_when_blocked`): its
    probe's estimate of ω at the carried phase against the accuracy, in words ("" otherwise)."""
    t0, t1 = span
    if not rung.probe_when_blocked or rung.model is None or rung.fast_compare is None or \
            PROBE_PERIODS * rung.fast_period > PROBE_FRACTION * (t1 - t0):
        return ""
    estimate = probe(rung, top, span, options)
    if estimate.fast is None or not math.isfinite(estimate.fast.value):
        return ""
    entry["estimate"] = estimate.as_dict()
    verdict = "above" if estimate.fast.value > accuracy else "within"
    return (f"; omega at the carried phase would err by {estimate.fast.value:.3g} (the probe's estimate), {verdict} "
            f"the accuracy {accuracy:g}; |G| and T alone by {estimate.value:.3g}")


def _copied(value):
    """A deep copy of a choice's entries (dicts, lists and numbers, as :func:`choose` makes them),
    without copy.deepcopy's bookkeeping."""
    if isinstance(value, dict):
        return {k: _copied(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_copied(v) for v in value]
    return copy.deepcopy(value) if not isinstance(value, (str, int, float, bool, type(None), tuple)) else value


def _fit_watches(rung: Rung, estimate: Estimate, accuracy: float) -> tuple[Rung, str]:
    """The rung with its error-scaling watch fitted to the accuracy. Its error is c·x, x the
    watched small parameter (slow/fast, N) and c measured by the probe (its largest difference
    over x at the start). At a switch up the error is at most 3c·x: c·x carried by the lower
    rung, and up to 2c·x from lifting at a fixed phase instead of the true one (the slow
    variables' oscillation c·x·f(φ) differs by at most twice its amplitude). The run therefore
    leaves the rung where SAFETY·3c·x reaches the accuracy: limit = min(the assumption's own
    limit, accuracy / (3 SAFETY c)), and comes back below limit/2. The estimate keeps what the probe
    measured; the run's (:func:`gyrostat.ladder.switching.run_estimate`) adds SAFETY·c·x at the
    largest x the run met (3× where it switched). ("" or why the rung cannot hold the accuracy even
    at the start.)"""
    watches = list(rung.watches)
    scaling = [i for i, w in enumerate(watches) if w.scales_error]
    if not scaling or not math.isfinite(estimate.measured):
        return rung, ""
    i = scaling[0]
    watch = watches[i]
    names = list(rung.model.output_names)
    start = float(rung.model._core.outputs_at(estimate.probe[0], np.asarray(rung.y0, float))[names.index(watch.output)])
    if not start > 0:
        return rung, ""
    c = estimate.measured / start
    limit = min(watch.limit, accuracy / (3.0 * SAFETY * c)) if c > 0 else watch.limit
    if start >= limit:
        return rung, (f"the measured error constant c = {c:.3g} of the O({watch.output}) error needs {watch.output} <= "
                      f"{limit:.3g} for the accuracy {accuracy:g}; it is {start:.3g} at the start")
    watches[i] = dataclasses.replace(watch, limit=limit, back=0.5 * limit)
    estimate.watched, estimate.constant = watch.output, c
    estimate.basis += (f"; error = c {watch.output} with c = {c:.3g} (measured): the run switches up where "
                       f"{watch.output} reaches {limit:.3g} and back below {0.5 * limit:.3g} (an error of at most "
                       f"{SAFETY:g} x 3c x {limit:.3g} = {3.0 * SAFETY * c * limit:.3g} there); the run's own "
                       f"estimate takes the largest {watch.output} it met")
    return dataclasses.replace(rung, watches=tuple(watches)), ""


def _rest(rungs: list[Rung], chosen: Rung) -> list[dict]:
    above = rungs[rungs.index(chosen) + 1:]
    return [{"rung": r.name, "model": r.description, "taken": False, "reason": "not needed"} for r in above]
