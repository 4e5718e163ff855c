"""The ladder's pieces: a :class:`Rung` (a model of the scene, what it can answer, the
assumptions it :class:`Watch`-es along its run), an :class:`Estimate` of a rung's error, the
:class:`Choice` made, the compared quantities, and the ladder's constants."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from gyrostat.assumptions import Assumption
from gyrostat.solution import Solution


ACCURACY = 1e-3
"""Default of ``integration.accuracy``: the relative error accepted on the compared quantities."""
PROBE_PERIODS = 20
"""The probe covers this many periods of the fast motion."""
PROBE_FRACTION = 0.05
"""... and at most this fraction of the span (so that it costs at most that much of a full run)."""
SAFETY = 2.0
"""The measured estimate is multiplied by this before it is compared with the accuracy."""
MAX_SWITCHES = 100
"""A run that switches more often than this stays on the top rung (the assumption flickers)."""


# ------------------------------------------------------------------------------------ pieces
@dataclass(frozen=True)
class Watch:
    """An assumption of a lower rung watched along its run: the model output ``output`` must stay
    below ``limit``; after a switch up, the run comes back down when it falls below ``back``."""

    output: str
    limit: float
    back: float
    statement: str
    scales_error: bool = False
    """The output is the small parameter of the rung's error (slow rate / fast frequency, the
    adiabaticity N): its limit is lowered so that the error c·value stays within the accuracy."""

    def ratio(self, value: float) -> float:
        """0 at ``back``, 1 at ``limit``."""
        return (value - self.back) / (self.limit - self.back)


@dataclass
class Rung:
    """One model of a family's ladder: the model, its initial state, and how it is compared."""

    name: str
    model: object
    y0: np.ndarray
    description: str
    compare: Callable[[Solution], np.ndarray] | None = None
    """The quantities compared with the top, (n, m), from a solution of this rung."""
    blocked: str = ""
    """Why this rung cannot answer the scene ("" when it can)."""
    probe_when_blocked: bool = False
    """Blocked because the outputs need ω(t), yet probed all the same: the report then says by how
    much ω at the carried phase (:attr:`fast_compare`) would miss the accuracy."""
    fast_period: float = math.inf
    """The period of the motion the rung averages or reduces (sets the probe's length)."""
    watches: tuple[Watch, ...] = ()
    """Assumptions watched along the run (empty: nothing to switch on)."""
    start_checks: Callable[[], list[Assumption]] = lambda: []
    """The rung's assumptions at the initial state."""
    basis: str = ""
    """What the error estimate rests on, besides the probe."""
    small: float | None = None
    """The small parameter of a reduction: the probe reports its constant, measured / small."""
    exact: bool = False
    """The reduction is exact (no model error): the probe's difference is the integrators' own."""
    phase_compared: bool = False
    """The compared quantities include the fast motion itself (ω(t), not only slow variables):
    its phase error is the integral of a frequency error that grows like the slow one, so the
    error grows quadratically, not linearly."""
    run: str = "full"
    """The name of the scene run this rung's solution stands for (the name its kind's analysis
    and plots look for)."""
    complete: Callable[[np.ndarray], np.ndarray] | None = None
    """(The top rung) its full state from the ω a lower rung lifts to where the run switches up,
    when the top carries more (a moving mass's displacement and velocity). None: the model's
    ``initial_state`` (the identity attitude, say)."""
    fast_compare: Callable[[Solution], np.ndarray] | None = None
    """ω(t) as this rung gives it (an averaged rung carrying the fast phase: the free motion at
    that phase), (n, 3): the probe compares it with the top's ω (:func:`rates`) and extrapolates
    its error linearly (the carried phase runs at the averaged frequency); reported beside the
    estimate (``fast_motion``), not used for the choice, which rests on ``compare``."""


@dataclass
class Estimate:
    """A measured error estimate of a rung against the top, extrapolated to the horizon."""

    value: float
    measured: float
    growth: float
    probe: tuple[float, float]
    seconds: dict[str, float]
    basis: str
    fast: Estimate | None = None
    """The error of ω(t) at the phase the rung carries (:attr:`Rung.fast_compare`), when it carries one."""
    watched: str = ""
    """The output whose size scales the rung's error (its :class:`Watch` with ``scales_error``)."""
    constant: float = math.nan
    """The measured constant c of the error c·(watched output)."""

    def as_dict(self) -> dict:
        entry = {"value": self.value, "measured_in_probe": self.measured, "growth_per_unit_time": self.growth,
                 "probe": list(self.probe), "probe_seconds": self.seconds, "basis": self.basis}
        if self.fast is not None:
            entry["fast_motion"] = self.fast.as_dict()
        if self.watched:
            entry["error_constant"] = {"output": self.watched, "c": self.constant}
        return entry


@dataclass
class Choice:
    """The ladder's decision for a scene: each rung considered, why it was taken or not."""

    rungs: list[Rung]
    chosen: Rung
    accuracy: float
    entries: list[dict] = field(default_factory=list)
    estimate: Estimate | None = None
    reused: bool = False
    """The choice was made for an identical scene solved before (no probe ran this time)."""

    @property
    def summary(self) -> str:
        if self.estimate is None:
            error = "exact to rounding" if self.chosen.name == "closed_form" else "reference model"
        else:
            error = f"estimated error {self.estimate.value:.2g} <= {self.accuracy:g}"
        return f"model {self.chosen.name} ({error})"

    def report(self) -> dict:
        return {"accuracy": self.accuracy, "chosen": self.chosen.name, "summary": self.summary,
                "estimate": self.estimate.as_dict() if self.estimate else None, "rungs": self.entries,
                "reused": self.reused}


# ------------------------------------------------------------------------------------ compared quantities
def rates(solution) -> np.ndarray:
    """ω = (p, q, r): (n, 3)."""
    return np.column_stack([solution["p"], solution["q"], solution["r"]])
