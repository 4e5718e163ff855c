"""A value a user passed, checked and shown with one-line errors: :func:`floats` (numbers as an
array of floats, never cast from strings or complex numbers), :func:`flag` (True or False, never
a truthy value) and :func:`shown` (a value on one line, cut short, for a message). Below every
floor that checks arguments (the options, the results, the models, the runs);
:mod:`gyrostat.modelbase` builds its constructors' helpers on them."""

from __future__ import annotations

import numpy as np


def shown(value, limit: int = 60) -> str:
    """``repr(value)`` on one line, shortened to ``limit`` characters: for error messages."""
    text = " ".join(repr(value).split())
    return text if len(text) <= limit else text[:limit - 3] + "..."


def floats(value, name: str, what: str = "real numbers") -> np.ndarray:
    """``value`` as an array of floats, or a one-line ValueError naming ``name``, ``what`` it must
    be and the value: strings, None, booleans alone, complex numbers and ragged lists are refused,
    never cast (NumPy would say "could not convert string to float" or drop an imaginary part)."""
    try:
        array = np.asarray(value)
    except (TypeError, ValueError):  # a ragged list
        array = None
    if array is None or array.dtype.kind not in "iuf":
        raise ValueError(f"{name} must be {what}, got {shown(value)}")
    return array.astype(float, copy=False)


def flag(value, name: str) -> bool:
    """``value`` as a bool, or a ValueError naming ``name``: only True and False are booleans
    (``bool("no")`` is True; 0 and 1 are numbers)."""
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    raise ValueError(f"{name} = {shown(value)} must be True or False")
