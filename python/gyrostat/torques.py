"""The torques a model or a scene may name: ``TORQUE_TYPES`` (the C++ torque types a model
accepts) and ``TORQUES`` (the one registration table of the scene torques: the schema of each,
and how to build it from the validated table), with ``TORQUE``, the ``[[torques]]`` variant
schema. Generic: every family takes its torques from here."""

from __future__ import annotations

import numpy as np

from gyrostat import _core
from gyrostat.schema import Field, ListOf, Matrix, Table, Variants, Vector, positive
from gyrostat.schema import all_finite as _all_finite

__all__ = ["TORQUE_TYPES", "TORQUES", "TORQUE"]

TORQUE_TYPES = (_core.ConstantTorque, _core.LinearDamping, _core.ResistiveMedium, _core.ViscousCavity,
                _core.MovingMassDamper)

# The one registration table of the torques a scene may name: the schema of each, and how to
# build it from the validated table.
TORQUES: dict[str, tuple[Table, callable]] = {
    "constant": (
        Table({"moment": Field(Vector(3), required=True, doc="M in body axes", unit="N m", check=_all_finite)},
              doc="a constant torque in body axes"),
        lambda s: _core.ConstantTorque(s["moment"])),
    "linear_damping": (
        Table({"matrix": Field(Matrix(3, 3), doc="D (M = -D omega)", unit="N m s"),
               "diagonal": Field(Vector(3), doc="the diagonal of D", unit="N m s")},
              one_of=[("matrix", "diagonal")], doc="M = -D omega"),
        lambda s: _core.LinearDamping(np.asarray(s["matrix"]) if "matrix" in s else np.diag(s["diagonal"]))),
    "resistive_medium": (
        Table({"coefficients": Field(ListOf(Matrix(3, 3), min_len=1), required=True,
                                     doc="D_0, D_1, ...: D(t) = sum D_k t^k (M = -D(t) omega)")},
              doc="a resistive medium whose resistance varies with time"),
        lambda s: _core.ResistiveMedium([np.asarray(c) for c in s["coefficients"]])),
    "viscous_cavity": (
        Table({"density": Field(float, required=True, doc="rho", unit="kg/m^3", check=positive),
               "viscosity": Field(float, required=True, doc="kinematic viscosity nu", unit="m^2/s", check=positive),
               "radius": Field(float, doc="radius of a spherical cavity", unit="m", check=positive),
               "p0": Field(float, doc="P0 of the cavity tensor P = P0 I", unit="m^5", check=positive)},
              one_of=[("radius", "p0")], doc="a cavity filled with a highly viscous fluid"),
        lambda s: (_core.ViscousCavity.sphere(s["density"], s["viscosity"], s["radius"]) if "radius" in s
                   else _core.ViscousCavity(s["density"], s["viscosity"], s["p0"]))),
    "moving_mass_damper": (
        Table({"mass": Field(float, required=True, doc="mass m", unit="kg", check=positive),
               "arm": Field(float, required=True, doc="distance rho of the mass on the z axis", unit="m",
                            check=positive),
               "frequency": Field(float, required=True, doc="Omega = sqrt(c/m)", unit="rad/s", check=positive),
               "damping": Field(float, required=True, doc="lambda = delta/m", unit="1/s", check=positive)},
              doc="Chernousko's quasi-static moving-mass damper"),
        lambda s: _core.MovingMassDamper(s["mass"], s["arm"], s["frequency"], s["damping"])),
}
TORQUE = Variants("type", {name: table for name, (table, _) in TORQUES.items()}, doc="a perturbation torque")
