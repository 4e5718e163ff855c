"""The rigid body family: a rigid body or gyrostat under perturbation torques (papers 000-002).

A family module provides, in this order (copy it for a new family):

1. its models: ``ModelBase`` subclasses over the C++ constructors, each with its own
   ``assumptions`` (beside its torques') and ``check``;
2. its paper helpers and analysis functions (from recorded outputs only);
3. its plots, drawn with :mod:`gyrostat.figures`;
4. its scene kind(s): ``Kind`` subclasses (:mod:`gyrostat.kind`) with the schema and defaults,
   the runs, the ladder rungs, the checks, the analysis, the extra columns and the plots;
5. one ``register(...)`` line at the end.

A family over a few hundred lines is a package, one concern a module, whose ``__init__`` gathers
its public names (as here).

Here: :class:`Model` (Euler's equations of a gyrostat), :class:`TorqueFreeModel` (the closed
form, :func:`torque_free`) and :class:`AveragedModel` (the system averaged over the symmetric
Euler-Poinsot motion in (a, r)); the averaged system's outputs (the papers' x, y, paper 002's
Lotka-Volterra coefficients and first integral, the slow variables of a full solution); the
kinds ``rigid_body`` (the full model, its closed form or the averaged system; its ladder:
closed form (nothing perturbs a rigid body) -> averaged (a, r) -> full (Euler's equations)) and
``averaged`` (the averaged system alone).

The family, one concern a module: ``models`` (:class:`Model`, :class:`TorqueFreeModel`,
:func:`torque_free`, :class:`AveragedModel`), ``triaxial`` (:class:`TriaxialAveragedModel`),
``averaged_outputs`` (the slow variables, the events, x and y, the Lotka-Volterra system),
``analyses`` (:func:`analyse`), ``plots`` (:func:`draw`), ``rungs`` (the averaged and the
triaxial averaged rungs, what the ladder compares, the checks at a run's start) and
``scene_kind`` (:class:`RigidBody`, :class:`Averaged`, registered when the family is imported).
"""

from gyrostat.families.rigid_body.analyses import analyse, carried_omega, first_reaching, omega_error, separatrix_crossings
from gyrostat.families.rigid_body.averaged_outputs import (LotkaVolterra, averaging_fails, lotka_volterra, r_zero,
                                                           slow_variables, xy)
from gyrostat.families.rigid_body.models import AveragedModel, Model, TorqueFreeModel, torque_free
from gyrostat.families.rigid_body.plots import AVERAGED_STYLE, FULL_STYLE, draw, nutation, phase, slow_curves
from gyrostat.families.rigid_body.rungs import (TRIAXIAL_PLOTS, averaged_rung, initial_assumptions, invariant_columns,
                                                nearly_symmetric, slow_columns, triaxial_rung)
from gyrostat.families.rigid_body.scene_kind import Averaged, RigidBody
from gyrostat.families.rigid_body.triaxial import TriaxialAveragedModel

__all__ = ["Model", "TorqueFreeModel", "AveragedModel", "TriaxialAveragedModel", "torque_free", "slow_variables",
           "r_zero", "averaging_fails", "xy", "LotkaVolterra", "lotka_volterra", "slow_columns", "initial_assumptions",
           "first_reaching", "separatrix_crossings", "analyse", "carried_omega", "omega_error", "FULL_STYLE",
           "AVERAGED_STYLE", "slow_curves", "phase", "nutation", "draw", "averaged_rung", "invariant_columns",
           "nearly_symmetric", "TRIAXIAL_PLOTS", "triaxial_rung", "RigidBody", "Averaged"]
