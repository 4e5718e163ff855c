"""The base of the validity checks: :class:`Assumption` (a check with its number and limit),
:class:`ValidityWarning`, the limit :data:`SMALL`, the torques' own checks and :func:`check`,
which adds each model's own (``ModelBase.assumptions``, in its family module). The torques'
numbers are computed by their C++ headers (``torque.assumptions(motion)``). Each check names
the assumption, its number and the limit; broken ones are warned about and returned.
:mod:`gyrostat.validity` is what users call (it adds ``check_scene``).

Limits: "≪ 1" is taken as ≤ 0.1 (a first-order theory then errs by about that fraction); the
paper's own condition (4) of paper 001, Ω² ≫ λ|ω| ≫ |ω|², is reported as printed with ratios
≥ 10. Where the averaged reduction is exact (symmetric body; cavity, axial constant torque,
axisymmetric diagonal resistance, damper), the fast-frequency condition is not needed and is
reported as such.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np

from gyrostat import _core

SMALL = _core.small
""""≪ 1": the limit of every ratio that must be small (C++ torque::kSmall)."""
PAPER_RATIO = _core.large
""""≫ 1" for the conditions a paper prints as such (C++ torque::kLarge)."""


class ValidityWarning(UserWarning):
    """A scene or a run breaks an assumption of a model it uses: the sentence names the
    assumption, its measured value and the limit. :func:`gyrostat.solve` warns so for an averaged
    model whose assumptions fail along the run (the sentence is also kept in ``Solution.notes``).

    Examples
    --------
    >>> import warnings
    >>> import gyrostat
    >>> body = gyrostat.Body([4.0, 4.4, 1.0])  # 10 % asymmetry: too far from symmetric for the averaging
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     sol = gyrostat.solve(gyrostat.AveragedModel(body), [0.1, 1.0], (0.0, 1.0))
    >>> any(issubclass(w.category, gyrostat.ValidityWarning) for w in caught)
    True
    """


@dataclass(frozen=True)
class Assumption:
    """One assumption of a model or torque, measured: ``value`` against ``limit`` (``holds`` says
    whether it does), in the words of the model's or torque's declaration.

    Parameters
    ----------
    part : str
        What assumes it ("viscous cavity", "averaged model").
    statement : str
        The condition ("Reynolds number |ω| b²/ν ≪ 1").
    value, limit : float
        The measured number and its limit (dimensionless ratios).
    holds : bool
        Whether the value is within the limit.
    note : str, optional
        What the number rests on.

    Examples
    --------
    >>> from gyrostat.validity import Assumption
    >>> print(Assumption("viscous cavity", "Reynolds number ≪ 1", 0.0625, 0.1, True))
    viscous cavity: Reynolds number ≪ 1: 0.0625 (limit 0.1) holds
    """
    part: str
    statement: str
    value: float
    limit: float
    holds: bool
    note: str = ""

    def __str__(self) -> str:
        verdict = "holds" if self.holds else "BROKEN"
        text = f"{self.part}: {self.statement}: {self.value:.3g} (limit {self.limit:.3g}) {verdict}"
        return text + (f"; {self.note}" if self.note else "")


def _omegas(model, states: np.ndarray, outputs: dict | None = None) -> np.ndarray:
    """(n, 3) angular velocities: for an averaged model ω = (a, 0, r) stands for the motion, or the
    model's own ``omegas_of`` (the free motion at the carried phase, from the outputs recorded at
    those states where the model has them)."""
    if hasattr(model, "omegas_of"):
        return model.omegas_of(states, outputs)
    if states.shape[1] == 2:
        return np.column_stack([states[:, 0], np.zeros(len(states)), states[:, 1]])
    return states[:, :3]


def check(model, states, times=None, warn: bool = True, outputs: dict | None = None) -> list[Assumption]:
    """Checks a model's assumptions over the given states: its torques' first, then the
    model's own (``model.assumptions``). Returns every check; warns
    (:class:`ValidityWarning`) for the broken ones when ``warn``.

    Parameters
    ----------
    model : gyrostat.ModelBase
        The model.
    states : array_like, shape (dim,) or (n, dim)
        One state or many (e.g. a solution's ``y``), in the model's units.
    times : array_like, shape (n,), optional
        Their times, in s (for time-dependent coefficients; default 0).
    warn : bool, optional
        Warn for each broken assumption (default True).
    outputs : dict, optional
        What a solve recorded at those states (the averaged model's ``slow_to_fast``), used as it is.

    Examples
    --------
    >>> import gyrostat
    >>> model = gyrostat.Model(gyrostat.Body([12.0, 12.0, 4.0]),
    ...                        [gyrostat.ViscousCavity(density=970.0, viscosity=2.0, radius=0.25)])
    >>> [round(c.value, 4) for c in gyrostat.validity.check(model, [0.05, 0.0, 2.0])]
    [0.0625, 0.0007]
    """
    states = np.atleast_2d(np.asarray(states, float))
    times = np.zeros(len(states)) if times is None else np.asarray(times, float)
    if states.shape[1] == model.dim:  # the checks look at the motion in principal axes (a body given by a tensor)
        states = np.asarray(model._core.principal_states(states))
    omegas = _omegas(model, states, outputs)
    # each torque's own numbers, as its C++ header declares them (torque.assumptions)
    motion = _core.Motion(model.body.moments, omegas)
    results: list[Assumption] = [Assumption(a.part, a.statement, a.value, a.limit, a.holds, a.note)
                                 for torque in model.torques for a in torque.assumptions(motion)]

    results += model.assumptions(states, times, outputs)

    if warn:
        for assumption in results:
            if not assumption.holds:
                warnings.warn(str(assumption), ValidityWarning, stacklevel=2)
    return results
