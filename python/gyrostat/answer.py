"""What a run says about its answer, for :func:`gyrostat.solve` and :func:`gyrostat.solve_ensemble`
alike: the accuracy contract's measurement (``accuracy`` and ``error_estimate`` read and checked,
the tolerances chosen or the run measured by :mod:`gyrostat.accuracy`, the estimate attached to
the Solution) and the doubts and broken assumptions warned when the run returns."""

from __future__ import annotations

import warnings

import numpy as np

from gyrostat import accuracy as _accuracy
from gyrostat import contract as _contract
from gyrostat.modelbase import ModelBase
from gyrostat.solution import AccuracyWarning, Solution

BASE_CHECK = ModelBase.check


def checked(solution: Solution, model, check_validity: bool) -> Solution:
    if solution.status == "interrupted":
        warnings.warn(f"interrupted: {solution.message}", RuntimeWarning, stacklevel=3)
    for doubt in solution.accuracy_warnings:
        warnings.warn(doubt, AccuracyWarning, stacklevel=3)
    if check_validity and type(model).check is not BASE_CHECK and len(solution):
        from gyrostat.assumptions import ValidityWarning

        for assumption in model.check(solution):
            if not assumption.holds:
                solution.notes.append(f"assumption broken: {assumption}")
                warnings.warn(str(assumption), ValidityWarning, stacklevel=3)
    return solution


def estimate_mode(error_estimate) -> str:
    """``error_estimate`` as "window", "full" or "" (off); ValueError naming another value."""
    if error_estimate is True or error_estimate == "window":
        return "window"
    if error_estimate is False:
        return ""
    if error_estimate == "full":
        return "full"
    raise ValueError(f"error_estimate = {error_estimate!r} must be True, False or 'full'")


def accuracy_asked(accuracy) -> float | None:
    """The accuracy asked as a float, or a ValueError naming a value that is not in (0, 1)."""
    if accuracy is None:
        return None
    if isinstance(accuracy, bool) or not isinstance(accuracy, (int, float, np.integer, np.floating)) \
            or not 0 < accuracy < 1:
        raise ValueError(f"accuracy = {accuracy!r} must be a number in (0, 1): the largest relative error accepted")
    return float(accuracy)


def measured(results: list, cores: list, run, opts, t0: float, t1: float, mode: str, accuracy: float | None,
              explicit: bool, size: float, choose_method: bool = False) -> tuple[list, list]:
    """The answers and their estimates: tolerances chosen for ``accuracy`` (:func:`gyrostat.contract.meet`;
    the method too with ``choose_method``) unless they were given (``explicit``), or the given run
    measured (``mode``)."""
    if accuracy is not None and not explicit:
        return _contract.meet(run, cores, opts, t0, t1, accuracy, size, choose=choose_method)
    if results is None:
        results = run(opts, t1, list(range(len(cores))))
    if not mode and accuracy is None:
        return results, [None] * len(results)
    estimates = _accuracy.estimate_runs(run, cores, opts, t0, t1, results, full=mode == "full" or not mode)
    for estimate in estimates:
        if estimate is not None and accuracy is not None:
            estimate.accuracy = accuracy
            if estimate.value > accuracy:
                estimate.warning = (f"the measured error {estimate.value:.3g} exceeds the accuracy {accuracy:g} at the "
                                    f"tolerances given (rtol {opts.rtol:g}, atol {opts.atol:g}): leave rtol and atol "
                                    f"out to have them chosen, or tighten rtol about "
                                    f"{opts.rtol * _contract.MARGIN * accuracy / estimate.value:.2g}")
    return results, estimates


def attach(solution: Solution, estimate) -> Solution:
    """The estimate on the solution: its value, its basis among the notes, its warning among the doubts."""
    if estimate is None:
        return solution
    solution.estimate = estimate
    solution.note_estimate(estimate)  # (its line written when the notes are read)
    if estimate.warning:
        solution.doubt(estimate.warning)
    return solution
