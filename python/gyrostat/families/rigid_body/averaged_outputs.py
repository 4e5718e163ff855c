"""The averaged system's outputs (papers 000-002): the slow variables (a, r) of a full or an
averaged solution, the events r = 0 and where the averaging fails, the papers' x, y and paper
002's Lotka-Volterra coefficients and first integral. :mod:`gyrostat.averaged` re-exports them."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from gyrostat.assumptions import SMALL
from gyrostat.events import Event
from gyrostat.solution import Solution


def slow_variables(solution: Solution) -> tuple[np.ndarray, np.ndarray]:
    """(a, r) of a solution, in rad/s: the state of the averaged model; a = √(p² + q²) and r of a
    full one.

    Parameters
    ----------
    solution : gyrostat.Solution
        A run of the full or the averaged rigid-body model.

    Examples
    --------
    >>> import gyrostat
    >>> from gyrostat import averaged
    >>> body = gyrostat.Body([12.0, 12.0, 4.0])
    >>> model = gyrostat.AveragedModel(body, [gyrostat.ViscousCavity(density=970.0, viscosity=2.0, radius=0.25)])
    >>> sol = gyrostat.solve(model, [0.05, 2.0], (0.0, 36000.0), n_out=3)
    >>> a, r = averaged.slow_variables(sol)
    >>> bool(a[-1] > a[0] and r[-1] < r[0])  # towards flat spin
    True
    """
    if solution.state_names[:2] == ("a", "r"):
        return solution["a"], solution["r"]
    return np.hypot(solution["p"], solution["q"]), solution["r"]


def r_zero(direction: int = 0, terminal: bool | int = False) -> Event:
    """The event r = 0 (the axial rate changes sign) of the full or the averaged model: there the
    averaging over the symmetric motion stops being valid (the fast frequency vanishes).

    Parameters
    ----------
    direction : {-1, 0, 1}, optional
        Only downward (-1), only upward (1) or both (0) crossings.
    terminal : bool or int, optional
        Stop the run at the first (True) or n-th crossing.

    Examples
    --------
    >>> from gyrostat import averaged
    >>> averaged.r_zero(direction=-1)
    Event(quantity='r', value=0.0, direction=-1, terminal=False, name='r = 0')
    """
    return Event("r", 0.0, direction, terminal, "r = 0")


def averaging_fails(limit: float = SMALL, terminal: bool | int = False) -> Event:
    """The event where the averaged model's slow rate reaches ``limit`` times its fast frequency
    (the output ``slow_to_fast`` rising through ``limit``): past it the averaging is not valid.

    Parameters
    ----------
    limit : float, optional
        The ratio slow rate / fast frequency (dimensionless; default "≪ 1" = 0.1).
    terminal : bool or int, optional
        Stop the run there.

    Examples
    --------
    >>> from gyrostat import averaged
    >>> averaged.averaging_fails(terminal=True).quantity
    'slow_to_fast'
    """
    return Event("slow_to_fast", float(limit), 1, terminal, f"slow/fast reaches {limit:g}")


def xy(solution: Solution) -> tuple[np.ndarray, np.ndarray]:
    """Papers 000/001: x = a², y = r², in rad²/s² (paper 002 swaps the names: its x is r², its y is a²).

    Parameters
    ----------
    solution : gyrostat.Solution
        A run of the full or the averaged rigid-body model.

    Returns
    -------
    (numpy.ndarray, numpy.ndarray)
        x and y at the output times.

    Examples
    --------
    >>> from gyrostat import averaged
    >>> import gyrostat
    >>> sol = gyrostat.solve(gyrostat.Model(gyrostat.Body([2.0, 2.0, 1.0])), [0.3, 0.4, 1.0], (0.0, 1.0), n_out=2)
    >>> x, y = averaged.xy(sol)
    >>> round(float(x[0]), 6), round(float(y[0]), 6)
    (0.25, 1.0)
    """
    a, r = slow_variables(solution)
    return a**2, r**2


@dataclass(frozen=True)
class LotkaVolterra:
    """Paper 002, eq. (6): with X = r², Y = a² (the paper's x, y) and no constant torque,
    dX/dt = X (λ1 + μ1 Y), dY/dt = Y (λ2 + μ2 X), where

        λ1 = −2 D33 / C,  λ2 = −(D11 + D22) / A,  μ1 = 2κ (C − A)/(A C),  μ2 = 2κ C (A − C)/A³,

    D the summed linear-resistance matrix (ε included), κ = ρ P0 / ν summed over cavities.
    A² μ2 + C² μ1 = 0 (the cavity keeps |G|).

    Parameters
    ----------
    lambda1, lambda2 : float
        λ1, λ2, in 1/s.
    mu1, mu2 : float
        μ1, μ2, in s (per rad²/s² of X or Y).

    Examples
    --------
    >>> from gyrostat import averaged
    >>> system = averaged.LotkaVolterra(lambda1=-0.01, lambda2=-0.002, mu1=-0.0005, mu2=5e-05)
    >>> float(system.first_integral(1.0, 1.0))  # λ2 ln 1 + μ2 − λ1 ln 1 − μ1
    0.00055
    """

    lambda1: float
    lambda2: float
    mu1: float
    mu2: float

    def first_integral(self, X, Y):
        """Paper 002 eq. (7) in logarithmic form (the exponential form overflows on the paper's
        own scene): Φ = λ2 ln X + μ2 X − λ1 ln Y − μ1 Y, constant along the averaged solution.

        Parameters
        ----------
        X, Y : array_like
            r² and a², in rad²/s².

        Examples
        --------
        >>> import gyrostat
        >>> from gyrostat import averaged
        >>> body = gyrostat.Body([12.0, 12.0, 4.0])
        >>> torques = [gyrostat.ViscousCavity(density=970.0, viscosity=2.0, radius=0.25),
        ...            gyrostat.LinearDamping(diagonal=[1e-3, 1e-3, 2e-3])]
        >>> model = gyrostat.AveragedModel(body, torques)
        >>> sol = gyrostat.solve(model, [0.05, 2.0], (0.0, 3600.0), rtol=1e-12, atol=1e-14, n_out=3)
        >>> y, x = averaged.xy(sol)  # the paper's X = r² is xy's y
        >>> phi = averaged.lotka_volterra(model).first_integral(x, y)
        >>> bool(abs(phi[-1] - phi[0]) < 1e-8 * abs(phi[0]))
        True
        """
        X, Y = np.asarray(X, float), np.asarray(Y, float)
        return self.lambda2 * np.log(X) + self.mu2 * X - self.lambda1 * np.log(Y) - self.mu1 * Y


def lotka_volterra(model) -> LotkaVolterra:
    """The coefficients of paper 002's system (6) from each torque's averaged contribution, as its
    C++ header gives it (``torque.averaged``): with Y = a², X = r², the system is Lotka–Volterra
    when each contribution has ṙ/r = (λ1 + μ1 a²)/2 and ȧ/a = (λ2 + μ2 r²)/2, which is read off at
    (a, r) = (0, 1), (1, 0) and (1, 1) and checked at a fourth point. A torque without that form
    (a constant axial torque, the damper's r⁴ terms) raises ValueError naming it.

    Parameters
    ----------
    model : gyrostat.AveragedModel or gyrostat.Model
        A symmetric body with its torques.

    Examples
    --------
    >>> import gyrostat
    >>> from gyrostat import averaged
    >>> body = gyrostat.Body([12.0, 12.0, 4.0])
    >>> model = gyrostat.AveragedModel(body, [gyrostat.LinearDamping(diagonal=[0.01, 0.01, 0.02])])
    >>> system = averaged.lotka_volterra(model)
    >>> round(float(system.lambda1), 6), round(float(system.lambda2), 6)  # -2 D33 / C, -(D11 + D22) / A
    (-0.01, -0.001667)
    """
    A, C = float(model.body.moments[0]), float(model.body.moments[2])
    lambda1 = lambda2 = mu1 = mu2 = 0.0
    for torque in model.torques:
        def rates(a, r):
            return np.asarray(torque.averaged(0.0, a, r, A, C), float)
        l1, l2 = 2.0 * rates(0.0, 1.0)[1], 2.0 * rates(1.0, 0.0)[0]
        m1, m2 = 2.0 * rates(1.0, 1.0)[1] - l1, 2.0 * rates(1.0, 1.0)[0] - l2
        a, r = 1.5, 0.75
        expected = np.array([a * (l2 + m2 * r * r), r * (l1 + m1 * a * a)]) / 2.0
        if not np.allclose(rates(a, r), expected, rtol=1e-12, atol=1e-300):
            raise ValueError(f"paper 002's Lotka-Volterra form has no term for {torque!r}: its averaged "
                             "contribution is not (a (λ2 + μ2 r²), r (λ1 + μ1 a²))/2")
        lambda1, lambda2, mu1, mu2 = lambda1 + l1, lambda2 + l2, mu1 + m1, mu2 + m2
    return LotkaVolterra(lambda1=lambda1, lambda2=lambda2, mu1=mu1, mu2=mu2)

