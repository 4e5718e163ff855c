"""What every model is: :class:`ModelBase` (a C++ model with named state components and named
outputs, solved by :func:`gyrostat.solve` and :func:`gyrostat.solve_ensemble`), and the argument
helpers every constructor uses (numbers, flags, bodies and torques checked with one-line
errors). Each family's models derive from it in their family module (``gyrostat/families/``);
:func:`model_names` reads them from its subclasses, so that a message naming the models is
written once (:func:`core_of`).
"""

from __future__ import annotations


import numpy as np

from gyrostat import _core
from gyrostat.arguments import flag, floats, shown  # noqa: F401 (flag: the constructors' helper, from here)
from gyrostat.torques import TORQUE_TYPES


def number(value, name: str) -> float:
    """``value`` as one float, or a one-line ValueError naming ``name`` and the value (as :func:`floats`)."""
    array = floats(value, name, "a number")
    if array.ndim:
        raise ValueError(f"{name} must be a number, got {shown(value)}")
    return float(array)


def check_torques(torques) -> tuple:
    """The torques as a tuple (a single torque is a list of one); anything that is not a torque
    raises TypeError naming its type."""
    if isinstance(torques, TORQUE_TYPES):
        return (torques,)
    if isinstance(torques, (str, bytes)) or not hasattr(torques, "__iter__"):
        raise TypeError(f"torques must be a list of torques, got {type(torques).__name__}")
    torques = tuple(torques)
    for torque in torques:
        if not isinstance(torque, TORQUE_TYPES):
            raise TypeError(f"not a torque: {type(torque).__name__} (torques are "
                            + ", ".join(t.__name__ for t in TORQUE_TYPES) + ")")
    return torques


def check_body(body) -> _core.Body:
    if not isinstance(body, _core.Body):
        raise TypeError(f"body must be a gyrostat.Body, not {type(body).__name__}")
    return body


class ModelBase:
    """What every model gives: its C++ model (``_core``), its family, the names of its state
    components and of the outputs recorded at every output time.

    Subclasses set ``_core`` in their constructor; ``kind`` names the model in reports. Users
    build one of the family models (:class:`gyrostat.Model`, :class:`gyrostat.AveragedModel`,
    …); this class is what they have in common. What a model was built from (its body, torques
    and numbers) is fixed once it is built: setting one again raises AttributeError (build a new
    model), since the engine's model was made from it.

    Examples
    --------
    The examples of the attributes below use this model:

    >>> import numpy as np
    >>> import gyrostat
    >>> model = gyrostat.Model(gyrostat.Body([2.0, 1.5, 1.0]), [gyrostat.LinearDamping(diagonal=[0.1, 0.1, 0.1])])
    >>> isinstance(model, gyrostat.ModelBase)
    True
    """

    __slots__ = ("_core", "__dict__")
    kind = "model"

    def __setattr__(self, name: str, value) -> None:
        # The engine's model is made once from the constructor's arguments: one set again afterwards
        # would leave every run on the old model, and the sensitivities' moved models on the new one.
        if name in self.__dict__ and name in getattr(self, "_arguments", dict)():
            raise AttributeError(f"{type(self).__name__}.{name} is fixed once the model is built (its engine model was "
                                 f"made from it): build a new {type(self).__name__} with the {name} you want")
        object.__setattr__(self, name, value)

    @property
    def family(self) -> str:
        """The model's family, as the C++ engine names it.

        Examples
        --------
        >>> model.family
        'gyrostat'
        """
        return self._core.family

    @property
    def dim(self) -> int:
        """Size of the state vector.

        Examples
        --------
        >>> model.dim
        3
        """
        return self._core.dim

    @property
    def state_names(self) -> tuple[str, ...]:
        """The names of the state components, in order (units in :attr:`units`).

        Examples
        --------
        >>> model.state_names
        ('p', 'q', 'r')
        """
        return tuple(self._core.state_names)

    @property
    def output_names(self) -> tuple[str, ...]:
        """Quantities recorded by the engine at every output time (``solution[name]``).

        Examples
        --------
        >>> model.output_names
        ('angular_momentum_norm', 'kinetic_energy', 'nutation_angle')
        """
        return tuple(self._core.output_names)

    @property
    def quantities(self) -> list[dict]:
        """What the C++ model declares about each state component and output: ``name``,
        ``unit``, ``description``, ``role`` ("state" or "output") and ``conserved``.

        Examples
        --------
        >>> [(q["name"], q["unit"], q["role"]) for q in model.quantities][-1]
        ('nutation_angle', 'rad', 'output')
        """
        return list(self._core.quantities)

    @property
    def units(self) -> dict[str, str]:
        """The SI unit of t, of each state component and of each output ("1": dimensionless), as
        the C++ model declares them.

        Examples
        --------
        >>> model.units["p"], model.units["angular_momentum_norm"]
        ('rad/s', 'kg m^2/s')
        """
        return {"t": "s", **{q["name"]: q["unit"] for q in self._core.quantities}}

    @property
    def attitude(self) -> bool:
        """Whether the state holds the attitude quaternion (q_w, q_x, q_y, q_z).

        Examples
        --------
        >>> model.attitude
        False
        """
        return "q_w" in self._core.state_names

    def rhs(self, t: float, y) -> np.ndarray:
        """The right-hand side f(t, y), evaluated by the core (for checks, not for speed).

        Parameters
        ----------
        t : float
            Time, in s.
        y : array_like, shape (dim,)
            A state (units in :attr:`units`).

        Examples
        --------
        >>> model.rhs(0.0, [0.0, 0.0, 1.0])
        array([ 0. ,  0. , -0.1])
        """
        return np.asarray(self._core.rhs(number(t, "t"), floats(y, "y")))

    def initial_state(self, y0) -> np.ndarray:
        """The full initial state from a shorter one where the model allows it (ω alone for a
        model with attitude: identity quaternion; τ(0) = 0 for the orthogonal torque).

        Parameters
        ----------
        y0 : array_like
            The state given.

        Examples
        --------
        >>> model.initial_state([0.1, 0.0, 1.0])
        array([0.1, 0. , 1. ])
        """
        return np.asarray(self._core.initial_state(floats(y0, "y0").ravel()))

    def check(self, solution) -> list:
        """The model's assumptions along a solution: its torques' and its own (:meth:`assumptions`),
        each at its worst value along the run. Models with assumptions of their own (the averaged
        ones, the moving mass) override it; :func:`gyrostat.solve` warns for broken ones.

        Parameters
        ----------
        solution : gyrostat.Solution
            A run of this model.

        Returns
        -------
        list of Assumption
            Empty for a model without assumptions of its own (the full and closed-form models).

        Examples
        --------
        >>> model.check(gyrostat.solve(model, [0.1, 0.0, 1.0], (0.0, 1.0)))
        []
        """
        return []

    def assumptions(self, states: np.ndarray, times: np.ndarray, outputs: dict | None = None) -> list:
        """The model's own assumptions over (n, dim) states at ``times``, beside its torques'
        (:func:`gyrostat.validity.check` adds those first).

        Parameters
        ----------
        states : numpy.ndarray, shape (n, dim)
            States of this model.
        times : numpy.ndarray, shape (n,)
            Their times, in s.
        outputs : dict, optional
            What a solve recorded at those states, used as it is.

        Examples
        --------
        >>> model.assumptions(np.array([[0.1, 0.0, 1.0]]), np.array([0.0]))
        []
        """
        return []


def model_names() -> tuple[str, ...]:
    """The names of the model classes, read from the subclasses of :class:`ModelBase` (every
    family's models, and any a user derives): the one list the error messages name, so that a new
    model needs no message changed. A private class (``_TopModel``) is left out, its subclasses not."""
    names, waiting = [], list(ModelBase.__subclasses__())
    while waiting:
        cls = waiting.pop(0)
        if not cls.__name__.startswith("_") and cls.__name__ not in names:
            names.append(cls.__name__)
        waiting += cls.__subclasses__()
    return tuple(names)


def core_of(model):
    """The C++ model of ``model``, or a TypeError naming every model class (:func:`model_names`)."""
    try:
        return model._core
    except AttributeError:
        raise TypeError(f"model must be a gyrostat model ({', '.join(model_names())}), not "
                        f"{type(model).__name__}") from None
