"""The model families, one module or package each (a vertical slice: its models, paper helpers and
analysis, validity checks, ladder rungs, plots and scene kinds):

* :mod:`gyrostat.families.rigid_body`: the gyrostat, its closed form and its averaged system
  (kinds ``rigid_body``, ``averaged``);
* :mod:`gyrostat.families.moving_mass`: the explicit moving-mass damper (kind ``moving_mass``);
* :mod:`gyrostat.families.lagrange_top`: the heavy top and its nutation-averaged system (kind
  ``lagrange_top``);
* :mod:`gyrostat.families.orthogonal_torque`: the orthogonal servo torque (kind
  ``orthogonal_torque``).

Importing this package imports every module in it (a new family is one more module here: nothing
else to edit), each of which registers its kinds into :data:`KINDS` (:mod:`gyrostat.kind`); the
generic layers (scene, runner, sweeps, plots) look kinds up there and name none. The kinds are
listed with the default kind's family first, then by module name.
"""

import importlib
import pkgutil

from gyrostat.kind import KINDS, default_kind

for _module in sorted(pkgutil.iter_modules(__path__), key=lambda m: m.name):
    importlib.import_module(f"{__name__}.{_module.name}")  # each module registers its family's kinds

# the default kind's family first, then the others by module name
_first = type(KINDS[default_kind()]).__module__
_order = sorted(KINDS.values(), key=lambda kind: type(kind).__module__ != _first)
KINDS.clear()
KINDS.update({kind.name: kind for kind in _order})

__all__ = ["KINDS", "default_kind"]
