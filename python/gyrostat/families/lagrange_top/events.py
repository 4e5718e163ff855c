"""The Lagrange top's events: the turning points of the nutation, and where the averaged model's
assumptions stop holding (near the separatrix, the averaging failing)."""

from __future__ import annotations

from gyrostat.assumptions import SMALL
from gyrostat.events import Event
from gyrostat.families.lagrange_top.models import SEPARATRIX_LIMIT


def turning_points(direction: int = 0, terminal: bool | int = False) -> Event:
    """The turning points of the nutation of the full top: d(cos θ)/dt = γ1 q − γ2 p = 0 (the
    output ``cos_theta_rate``); direction −1: θ at a minimum (cos θ at a maximum), +1: θ at a maximum.

    Parameters
    ----------
    direction : {-1, 0, 1}, optional
        Which turning points (default both).
    terminal : bool or int, optional
        Stop the run at the first (True) or n-th one.

    Examples
    --------
    >>> import numpy as np
    >>> import gyrostat
    >>> from gyrostat import lagrange
    >>> top = lagrange.LagrangeTop(A=1.5, C=1.0, mu=0.5)
    >>> y0 = lagrange.initial_state([0.0, 0.0, np.sqrt(3.0)], theta=np.radians(60.0))
    >>> sol = gyrostat.solve(top, y0, (0.0, 20.0), events=[lagrange.turning_points(direction=1)])
    >>> np.diff(sol.t_events[0]).round(4)  # one nutation period apart
    array([5.8396, 5.8396])
    """
    return Event("cos_theta_rate", 0.0, direction, terminal, "nutation turning point")


def near_separatrix(limit: float = SEPARATRIX_LIMIT, terminal: bool | int = False) -> Event:
    """k² rising through 1 − limit: the motion approaches the separatrix, where the nutation
    period diverges and the averaging degrades (full or averaged top: the output ``m``).

    Parameters
    ----------
    limit : float, optional
        1 − k² at the event (dimensionless; default 1e-3).
    terminal : bool or int, optional
        Stop the run there.

    Examples
    --------
    >>> from gyrostat import lagrange
    >>> lagrange.near_separatrix().value
    0.999
    """
    return Event("m", 1.0 - float(limit), 1, terminal, f"1 - k^2 falls to {limit:g}")


def averaging_fails(limit: float = SMALL, terminal: bool | int = False) -> Event:
    """The averaged top's adiabaticity N = rate·T_nut rising through ``limit``.

    Parameters
    ----------
    limit : float, optional
        N at the event (dimensionless; default "≪ 1" = 0.1).
    terminal : bool or int, optional
        Stop the run there.

    Returns
    -------
    gyrostat.events.Event
        On the averaged top's output ``adiabaticity``, upward.

    Examples
    --------
    >>> from gyrostat import lagrange
    >>> lagrange.averaging_fails(terminal=True).quantity
    'adiabaticity'
    """
    return Event("adiabaticity", float(limit), 1, terminal, f"N = rate T_nut reaches {limit:g}")
