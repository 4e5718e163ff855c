"""The model ladder: a scene gets no more model than it needs.

Each family has rungs, cheapest first (its scene kind's ``ladder``, listed in its family module
under ``gyrostat/families/``); the last is the scene's most complete model (the *top*).

``model = "auto"`` with a requested accuracy (``integration.accuracy``: the largest relative error
accepted on the quantities the scene's outputs need) takes the cheapest rung that

1. can give those quantities at all (an averaged model gives no ω(t), only its slow variables);
2. has its assumptions holding at the start (:mod:`gyrostat.validity`);
3. has a *measured* error estimate below the accuracy (:func:`probe`): the rung and the top are both run
   over a probe window at the start (20 periods of the fast motion the rung averages or reduces, at most
   a twentieth of the span), their difference in the compared quantities gives the O(ε) constant (the
   largest difference over the window, relative to the quantities' size) and its growth (the largest
   difference over the window's second half minus the first's, per unit time), extrapolated to the
   horizon linearly (the growth law of first-order averaging over times ~1/ε) for slow variables, and
   quadratically where ω(t) itself is compared (its phase error integrates the slow error), times 2.

The chosen lower rung then runs with terminal events on its assumptions (:class:`Watch`): where one
stops holding (r near zero, the nutation period long against the slow time, k² near 1), the run
continues on the top from the state lifted back (C++ ``full_state``: the slow variables at the fast
phase ``integration.phase``, default 0) and comes back down when the assumption holds again with a
margin (hysteresis). The run is one :class:`gyrostat.Solution` joined from its pieces in the lower
rung's variables (:meth:`gyrostat.Solution.join`); the report lists every switch with its time
and reason. The closed form needs no estimate (it is exact to
rounding). The integrator is part of the choice too: ``method = "auto"`` (the scenes' default) picks
DOP853 or CVODE BDF by the stiffness measured along the run.

The package, one concern a module: ``rungs`` (:class:`Rung`, :class:`Watch`, :class:`Estimate`,
:class:`Choice`, the constants), ``probe`` (:func:`probe`), ``choosing`` (:func:`choose`,
:func:`scene_key`) and ``switching`` (:func:`run`, :func:`measure`).
"""

from gyrostat.ladder.choosing import CACHE_SIZE, choose, scene_key
from gyrostat.ladder.probe import PROBE_SAMPLES, probe
from gyrostat.ladder.rungs import (ACCURACY, MAX_SWITCHES, PROBE_FRACTION, PROBE_PERIODS, SAFETY, Choice, Estimate,
                                   Rung, Watch, rates)
from gyrostat.ladder.switching import measure, run, run_estimate

__all__ = ["ACCURACY", "PROBE_PERIODS", "PROBE_FRACTION", "SAFETY", "MAX_SWITCHES", "PROBE_SAMPLES", "CACHE_SIZE",
           "Watch", "Rung", "Estimate", "Choice", "rates", "probe", "scene_key", "choose", "run", "run_estimate", "measure"]
