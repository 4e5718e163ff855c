"""Ready-made checks for ``Field(check=...)`` (:func:`positive`, :func:`non_negative`,
:func:`at_least`, :func:`increasing`, :func:`finite`, ...); a list of numbers is checked element
by element, and :func:`elementwise` marks a check a number passes alone."""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from gyrostat.schema.fields import _FLOATS


def elementwise(check: Callable[[Any], Any]) -> Callable[[Any], Any]:
    """Marks ``check`` as one that a list of numbers passes when each of its numbers passes it
    alone (and that takes a single number): a number changed inside a valid value is then checked
    by itself (:meth:`Located.accepts_number`, what a sweep member's values go through)."""
    check.elementwise = True
    return check


def _each(value: Any) -> list:
    if isinstance(value, (list, tuple)):
        return [x for item in value for x in _each(item)]
    return [value]


@elementwise
def positive(value: Any) -> None:
    """Every number is > 0."""
    if not all(x > 0 for x in _each(value)):
        raise ValueError("must be positive")


@elementwise
def non_negative(value: Any) -> None:
    """Every number is >= 0."""
    if not all(x >= 0 for x in _each(value)):
        raise ValueError("must not be negative")


def at_least(bound: float) -> Callable[[Any], None]:
    """Every number is >= ``bound``."""

    @elementwise
    def check(value: Any) -> None:
        if not all(x >= bound for x in _each(value)):
            raise ValueError(f"must be at least {bound}")

    return check


def increasing(value: Any) -> None:
    """A list of numbers is strictly increasing."""
    if not all(a < b for a, b in zip(value, value[1:])):
        raise ValueError("must be increasing")


@elementwise
def finite(value: Any, _: Any = None) -> None:
    """A number is finite."""
    if not math.isfinite(value):
        raise ValueError("must be finite")


def _flat_floats(values: Any) -> Any:
    """A float, a list of floats or a list of lists of floats as one iterable of them; None for
    anything else."""
    if type(values) is float:
        return (values,)
    if type(values) is list:
        if set(map(type, values)) <= _FLOATS:
            return values
        if all(type(row) is list and set(map(type, row)) <= _FLOATS for row in values):
            return [x for row in values for x in row]
    return None


@elementwise
def all_finite(values: Any) -> None:
    """Every number is finite."""
    flat = _flat_floats(values)  # validated values are floats: checked without NumPy
    if not (all(map(math.isfinite, flat)) if flat is not None else np.all(np.isfinite(np.asarray(values, float)))):
        raise ValueError("must be finite numbers")


def span_order(values: Any) -> None:
    """A time span (t0, t1) of two finite times."""
    if not (math.isfinite(values[0]) and math.isfinite(values[1])):
        raise ValueError("must be two finite times")


def nonzero_quaternion(values: Any) -> None:
    """A finite, non-zero quaternion (w, x, y, z)."""
    q = np.asarray(values, float)
    if not np.all(np.isfinite(q)) or not np.any(q):
        raise ValueError("must be a finite, non-zero quaternion (w, x, y, z)")
