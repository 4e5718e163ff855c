"""gyrostat: perturbed rotational motion of rigid bodies and gyrostats about the centre of mass.

A thin Python layer over the C++ core (``gyrostat._core``): build a :class:`Body`, add torques,
make a :class:`Model`, :func:`solve` it (or :func:`solve_ensemble` many at once) and get NumPy
arrays back. Scenes (TOML files) bundle all of that with outputs and plots; ``gyrostat run``
runs one from the command line.
"""

from gyrostat._core import Body, ConstantTorque, LinearDamping, TorqueFreeSolution
from gyrostat.model import Model
from gyrostat.solution import Solution
from gyrostat.solve import METHODS, solve, solve_ensemble, torque_free

__all__ = [
    "Body",
    "ConstantTorque",
    "LinearDamping",
    "TorqueFreeSolution",
    "Model",
    "Solution",
    "METHODS",
    "solve",
    "solve_ensemble",
    "torque_free",
]
__version__ = "0.1.0"
