"""gyrostat: perturbed rotational motion of rigid bodies and gyrostats about the centre of mass.

A thin Python layer over the C++ engine (``gyrostat._core``): build a :class:`Body`, add torques,
make a model of any family (:class:`Model`, :class:`AveragedModel`, :class:`TriaxialAveragedModel`,
:class:`MovingMassModel`,
:class:`TorqueFreeModel`, :class:`gyrostat.lagrange.LagrangeTop`,
:class:`gyrostat.lagrange.LagrangeAveraged`, :class:`gyrostat.orthogonal.OrthogonalModel`),
:func:`solve` it (or :func:`solve_ensemble` many at once) and get a :class:`Solution` with the
state and the named outputs the engine recorded. Scenes (TOML files) bundle all of that with
outputs and plots; ``gyrostat run`` runs one from the command line. :func:`sweep` solves a scene
over a grid or a seeded dispersion of its entries (locally or on Dask) into an xarray Dataset.
"""

import os as _os

from gyrostat import _core
from gyrostat._core import Body, Orbit, TorqueFreeSolution
from gyrostat.assumptions import ValidityWarning
from gyrostat.families.moving_mass import MovingMassModel
from gyrostat.families.rigid_body import AveragedModel, Model, TorqueFreeModel, TriaxialAveragedModel, torque_free
from gyrostat.modelbase import ModelBase
from gyrostat.solution import AccuracyWarning, Solution
from gyrostat.solve import METHODS, Options, solve, solve_ensemble
from gyrostat.sweeps import LogUniform, Normal, Parameter, Uniform, sweep
from gyrostat import attitude, averaged, lagrange, orthogonal, scene, sweeps, validity  # noqa: E402

# every torque class of the core, under its own name (gyrostat.ConstantTorque, …): generated from
# the C++ declarations, so a new torque needs nothing here
globals().update({cls.__name__: cls for cls in _core.torque_types})

__all__ = [
    "Body",
    "Orbit",
    *(cls.__name__ for cls in _core.torque_types),
    "TorqueFreeSolution",
    "ModelBase",
    "Model",
    "AveragedModel",
    "TriaxialAveragedModel",
    "MovingMassModel",
    "TorqueFreeModel",
    "Solution",
    "METHODS",
    "Options",
    "solve",
    "solve_ensemble",
    "torque_free",
    "ValidityWarning",
    "AccuracyWarning",
    "sweep",
    "Parameter",
    "Uniform",
    "Normal",
    "LogUniform",
    "attitude",
    "averaged",
    "lagrange",
    "orthogonal",
    "scene",
    "sweeps",
    "validity",
    "simd_lanes",
    "simd_instruction_set",
    "taylor_kernel",
]
__version__ = _core.__version__
# The ensembles' SIMD batches in the widest form this CPU runs: the default build carries them
# compiled for AVX-512 and for AVX2 + FMA as plugins beside _core (without them, or on another
# CPU, the library's own form runs); GYROSTAT_SIMD=sse2|avx2|avx512 asks for one (tests, timing).
_core.load_batches(_os.path.dirname(_core.__file__), _os.environ.get("GYROSTAT_SIMD", ""))
#: Members one SIMD batch of :func:`solve_ensemble` integrates at once: 8 with AVX-512, 4 with
#: AVX2 or SSE2 (two SSE2 registers per operation), as :data:`simd_instruction_set` says.
simd_lanes: int = _core.simd_lanes
#: The instruction set of the SIMD batches in use, chosen when gyrostat is imported: "avx512f"
#: or "avx2" (the widest the CPU runs, from the default build's plugins, or the native build's
#: own), "sse2" (the portable form; or with GYROSTAT_SIMD=sse2 set before the import).
simd_instruction_set: str = _core.simd_instruction_set
#: The form of the gyrostat's Taylor recursion this process uses: "avx2+fma" (chosen at run time
#: on CPUs with AVX2 and FMA, whatever the build) or "portable" (elsewhere, or with the
#: environment variable GYROSTAT_PORTABLE_KERNELS=1 set before gyrostat is imported). The two agree
#: to rounding, not bit for bit.
taylor_kernel: str = _core.taylor_kernel
