"""The orthogonal torque's magnitude laws L(t) (:func:`constant`, :func:`polynomial`,
:func:`harmonic`, :func:`tabulated`, from a scene table :func:`law_from_spec`) and the default
regularisation :data:`ETA`."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from gyrostat import _core


ETA = 1e-3
"""Default regularisation: δ = η |ω| |G|."""


# ------------------------------------------------------------------------------ magnitude laws
def _finite(value, what: str) -> float:
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{what} = {value!r} is not a number") from None
    if not math.isfinite(x):
        raise ValueError(f"{what} = {x} is not finite")
    return x


def constant(value: float) -> _core.MagnitudeLaw:
    """L(t) = value: a constant magnitude law of the servo torque.

    Parameters
    ----------
    value : float
        L, in N m.

    Examples
    --------
    >>> from gyrostat import orthogonal
    >>> law = orthogonal.constant(0.1)
    >>> law.kind, law(3.0)
    ('constant', 0.1)
    """
    return _core.MagnitudeLaw.constant(_finite(value, "constant L"))


def polynomial(coefficients: Sequence[float]) -> _core.MagnitudeLaw:
    """L(t) = Σ c_i tⁱ, coefficients (c0, c1, …).

    Parameters
    ----------
    coefficients : sequence of float
        c_i, in N m / s^i.

    Examples
    --------
    >>> from gyrostat import orthogonal
    >>> round(orthogonal.polynomial([0.1, 0.02])(2.0), 12)
    0.14
    """
    return _core.MagnitudeLaw.polynomial([_finite(c, f"polynomial coefficient {i}") for i, c in enumerate(coefficients)])


def harmonic(mean: float, amplitudes: Sequence[float] = (), frequencies: Sequence[float] = (),
             phases: Sequence[float] | None = None) -> _core.MagnitudeLaw:
    """L(t) = L0 + Σ A_i sin(w_i t + φ_i) (phases default to 0).

    Parameters
    ----------
    mean : float
        L0, in N m.
    amplitudes : sequence of float, optional
        A_i, in N m.
    frequencies : sequence of float, optional
        w_i, in rad/s.
    phases : sequence of float, optional
        φ_i, in rad (default 0).

    Examples
    --------
    >>> import numpy as np
    >>> from gyrostat import orthogonal
    >>> round(orthogonal.harmonic(0.1, [0.05], [2.0])(np.pi / 4), 12)
    0.15
    """
    amplitudes = [float(a) for a in np.atleast_1d(amplitudes)]
    frequencies = [float(w) for w in np.atleast_1d(frequencies)]
    phases = [0.0] * len(amplitudes) if phases is None else [float(p) for p in np.atleast_1d(phases)]
    return _core.MagnitudeLaw.harmonic(_finite(mean, "harmonic mean L0"), amplitudes, frequencies, phases)


def tabulated(times: Sequence[float], values: Sequence[float], interpolation: str = "linear") -> _core.MagnitudeLaw:
    """L(t) interpolated in a table (``"linear"`` or ``"cubic"`` Hermite); held constant outside it.
    Times must increase strictly: a zero or negative spacing raises ValueError naming it.

    Parameters
    ----------
    times : sequence of float
        The table's times, in s.
    values : sequence of float
        L at those times, in N m.
    interpolation : {"linear", "cubic"}, optional
        Between the times.

    Examples
    --------
    >>> from gyrostat import orthogonal
    >>> law = orthogonal.tabulated([0.0, 1.0, 2.0], [0.0, 1.0, 0.5])
    >>> law(0.5), law(5.0)
    (0.5, 0.5)
    """
    if interpolation not in ("linear", "cubic"):
        raise ValueError(f"interpolation = {interpolation!r}: choose 'linear' or 'cubic'")
    return _core.MagnitudeLaw.tabulated([float(t) for t in np.ravel(times)], [float(v) for v in np.ravel(values)],
                                        interpolation == "cubic")


def law_from_spec(spec: dict | float) -> _core.MagnitudeLaw:
    """A law from a scene table: a number, or {kind = "constant"|"polynomial"|"harmonic"|"tabulated", …}.

    Parameters
    ----------
    spec : dict or float
        The scene's ``law`` (values in N m, times in s).

    Examples
    --------
    >>> from gyrostat import orthogonal
    >>> round(orthogonal.law_from_spec({"kind": "polynomial", "coefficients": [0.1, 0.02]})(2.0), 12)
    0.14
    """
    if isinstance(spec, (int, float)):
        return constant(spec)
    kind = spec.get("kind", "constant")
    if kind == "constant":
        return constant(spec["value"])
    if kind == "polynomial":
        return polynomial(spec["coefficients"])
    if kind == "harmonic":
        return harmonic(spec["mean"], spec.get("amplitudes", ()), spec.get("frequencies", ()), spec.get("phases"))
    if kind == "tabulated":
        return tabulated(spec["times"], spec["values"], spec.get("interpolation", "linear"))
    raise ValueError(f"law kind = {kind!r}: choose constant, polynomial, harmonic or tabulated")

