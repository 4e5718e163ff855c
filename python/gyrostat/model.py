"""Models: what the engine integrates. Every family's models (the gyrostat, the averaged
symmetric system, the explicit moving mass, the closed-form torque-free body; the Lagrange top
and the orthogonal torque in :mod:`gyrostat.lagrange` and :mod:`gyrostat.orthogonal`) are a
:class:`ModelBase`, solved by :func:`gyrostat.solve` and :func:`gyrostat.solve_ensemble`. This
module re-exports them from :mod:`gyrostat.modelbase` and the family modules."""

from gyrostat.families.moving_mass import MovingMassModel
from gyrostat.families.rigid_body import AveragedModel, Model, TorqueFreeModel, TriaxialAveragedModel
from gyrostat.modelbase import ModelBase, check_body, check_torques, flag, floats, number, shown
from gyrostat.torques import TORQUE_TYPES

__all__ = ["ModelBase", "Model", "TorqueFreeModel", "AveragedModel", "TriaxialAveragedModel", "MovingMassModel", "TORQUE_TYPES", "shown",
           "floats", "number", "flag", "check_torques", "check_body"]
