"""gyrostat: perturbed rotational motion of rigid bodies and gyrostats about the centre of mass.

A thin Python layer over the C++ core (``gyrostat._core``): build a :class:`Body`, add torques,
make a :class:`Model`, :func:`solve` it (or :func:`solve_ensemble` many at once) and get NumPy
arrays back. Scenes (TOML files) bundle all of that with outputs and plots; ``gyrostat run``
runs one from the command line.
"""

from gyrostat._core import (Body, ConstantTorque, LinearDamping, MovingMassDamper, ResistiveMedium,
                            TorqueFreeSolution, ViscousCavity)
from gyrostat.model import AveragedModel, Model, MovingMassModel
from gyrostat.solution import Solution
from gyrostat.solve import METHODS, solve, solve_ensemble, torque_free
from gyrostat.validity import ValidityWarning
from gyrostat import averaged, lagrange, orthogonal, validity  # noqa: E402  (papers 002-004 helpers)

__all__ = [
    "Body",
    "ConstantTorque",
    "LinearDamping",
    "ResistiveMedium",
    "ViscousCavity",
    "MovingMassDamper",
    "TorqueFreeSolution",
    "Model",
    "AveragedModel",
    "MovingMassModel",
    "Solution",
    "METHODS",
    "solve",
    "solve_ensemble",
    "torque_free",
    "ValidityWarning",
    "averaged",
    "lagrange",
    "orthogonal",
    "validity",
]
__version__ = "0.1.0"
