"""What a run's measured error is (:mod:`gyrostat.accuracy` measures it): an :class:`Estimate` (its
value, per quantity, the words it rests on), and the quantities a run of a model is measured on
(:func:`quantities`: what the model's C++ declarations say; :class:`Compared`: what a caller's
``compare`` gives instead)."""

from __future__ import annotations

import weakref
from collections.abc import Callable
from dataclasses import dataclass
from functools import partial

import numpy as np

__all__ = ["Compared", "Estimate", "Quantity", "quantities", "quantity_names"]


@dataclass(frozen=True)
class Quantity:
    """A compared quantity: its name, and the columns of the state (``role == "state"``) or of
    the outputs that make it."""

    name: str
    role: str
    columns: np.ndarray


class Estimate:
    """A run's measured global error: the largest relative error over the compared quantities
    (``value``), each quantity's (``per_quantity``), what it rests on (``basis``) and, for a run
    given an accuracy, whether the estimate meets it.

    ``basis`` may be given as a callable of no arguments that returns the text: it is then written
    on first reading (a run's default estimate formats seven numbers into it, ~3 µs that a solve
    whose notes are never read need not pay)."""

    __slots__ = ("value", "per_quantity", "_basis", "accuracy", "warning", "safety")

    def __init__(self, value: float, per_quantity: dict[str, float] | None = None, basis="",
                 accuracy: float | None = None, warning: str = "", safety: float = 1.0):
        self.value = value
        self.per_quantity = {} if per_quantity is None else per_quantity
        self._basis = basis
        self.accuracy = accuracy
        self.warning = warning
        """Why the accuracy asked is not met, with the measured error and what would meet it ("" when it is)."""
        self.safety = safety
        """The factor the measurement was multiplied by to make ``value`` (a scaled estimate's
        :data:`gyrostat.contract.SCALE_SAFETY`; 1 for a measurement): ``value / safety`` is what was measured."""

    @property
    def basis(self) -> str:
        """What the estimate rests on, in words (the method, the companion, the window, the growth)."""
        text = self._basis
        if type(text) is not str:
            text = self._basis = text()
        return text

    @basis.setter
    def basis(self, text: str) -> None:
        self._basis = text

    def prefix(self, words) -> None:
        """Puts ``words`` (text, or a callable of no arguments that writes it) before the basis."""
        self._basis = partial(_joined, words, self._basis)

    def __getstate__(self):
        return {name: getattr(self, name) for name in ("value", "per_quantity", "basis", "accuracy", "warning", "safety")}

    def __setstate__(self, state: dict) -> None:
        self.__init__(**state)

    def __repr__(self) -> str:
        return (f"Estimate(value={self.value!r}, per_quantity={self.per_quantity!r}, basis={self.basis!r}, "
                f"accuracy={self.accuracy!r}, warning={self.warning!r}, safety={self.safety!r})")

    def __eq__(self, other) -> bool:
        return type(other) is Estimate and self.__getstate__() == other.__getstate__()

    __hash__ = None

    @property
    def met(self) -> bool | None:
        """Whether the estimate is within the accuracy asked (None: none was asked)."""
        if self.accuracy is None:
            return None
        return bool(self.value <= self.accuracy)

    def as_dict(self) -> dict:
        return {"value": self.value, "per_quantity": dict(self.per_quantity), "basis": self.basis,
                "accuracy": self.accuracy, "met": self.met, "warning": self.warning}


def _joined(first, then) -> str:
    """Two parts of a basis, each text or a callable that writes it (:meth:`Estimate.prefix`)."""
    return (first if type(first) is str else first()) + (then if type(then) is str else then())


class Compared:
    """A model's run measured on the quantities ``compare`` gives (solution → (n, m): one quantity,
    ``"compared"``, relative to its largest row norm) instead of :func:`quantities`: what the model
    ladder compares (|G| and T, (a, r), ...) when a scene needs no more."""

    __slots__ = ("core", "compare", "model")

    def __init__(self, core, compare: Callable, model=None):
        self.core, self.compare, self.model = core, compare, model


_QUANTITIES: dict[tuple, list] = {}
_OF_CORE: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()
"""Each engine model's quantities, by the model object (its names never change; ~1 µs a run saved)."""


def quantities(core) -> list[Quantity]:
    """The quantities the error of a run of the model ``core`` is measured on: what its C++
    declarations say (``core.measured_quantities``: a vector's components as one quantity, labels
    left out, the measured outputs), or ``compared`` for a :class:`Compared` model."""
    if isinstance(core, Compared):
        return [Quantity("compared", "compare", np.zeros(0, int))]
    known = _OF_CORE.get(core)
    if known is not None:
        return known
    key = (tuple(core.state_names), tuple(core.output_names))
    known = _QUANTITIES.get(key)
    if known is None:
        known = _QUANTITIES[key] = [Quantity(name, role, np.asarray(columns, int))
                                    for name, role, columns in core.measured_quantities]
    _OF_CORE[core] = known
    return known


_NAMES: dict[int, tuple] = {}
"""id(engine model) → (a weak reference to it, its quantities' names)."""


def quantity_names(core) -> list[str]:
    """The names of the quantities a run of ``core`` is measured on (:func:`quantities`; kept by
    engine model, a plain dict by id checked by a weak reference: a WeakKeyDictionary's look-up
    cost ~0.5 µs a run).

    Parameters
    ----------
    core : gyrostat._core.Model or Compared
        The engine model (``model._core``), or a :class:`Compared` one.

    Examples
    --------
    >>> import gyrostat
    >>> from gyrostat.estimate import quantity_names
    >>> quantity_names(gyrostat.Model(gyrostat.Body([1.0, 2.0, 3.0]))._core)
    ['omega', 'angular_momentum_norm', 'kinetic_energy']
    """
    known = _NAMES.get(id(core))
    if known is not None and known[0]() is core:
        return known[1]
    if isinstance(core, Compared):  # (no weak reference to it: made each time)
        return [q.name for q in quantities(core)]
    names = [q.name for q in quantities(core)]
    key = id(core)
    _NAMES[key] = (weakref.ref(core, lambda _, key=key: _NAMES.pop(key, None)), names)
    return names
