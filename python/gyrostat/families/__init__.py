"""The model families, one module each (a vertical slice: its models, paper helpers and analysis,
validity checks, ladder rungs, plots and scene kinds):

* :mod:`gyrostat.families.rigid_body`: the gyrostat, its closed form and its averaged system
  (kinds ``rigid_body``, ``averaged``);
* :mod:`gyrostat.families.moving_mass`: the explicit moving-mass damper (kind ``moving_mass``);
* :mod:`gyrostat.families.lagrange_top`: the heavy top and its nutation-averaged system (kind
  ``lagrange_top``);
* :mod:`gyrostat.families.orthogonal_torque`: the orthogonal servo torque (kind
  ``orthogonal_torque``).

Importing this package imports every family, each of which registers its kinds into
:data:`KINDS` (:mod:`gyrostat.kind`); the generic layers (scene, runner, sweeps, plots) look
kinds up there and name none. A new family is one more module here and one more line below.
"""

# in this order: the order of the kinds in ``scene-format`` and in error messages
from gyrostat.families import rigid_body  # noqa: F401, I001  (each import registers the family's kinds)
from gyrostat.families import moving_mass  # noqa: F401
from gyrostat.families import lagrange_top  # noqa: F401
from gyrostat.families import orthogonal_torque  # noqa: F401
from gyrostat.kind import KINDS, default_kind

__all__ = ["KINDS", "default_kind"]
