"""Does a scene satisfy the assumptions of the models it uses? Each check names the assumption,
its number and the limit; broken ones are warned about (:class:`ValidityWarning`) and returned.

:func:`check` checks a model over states (its torques' assumptions, then the model's own, which
its family module declares); :func:`check_scene` checks a scene's runs at their initial states.

Limits: "≪ 1" is taken as ≤ 0.1 (a first-order theory then errs by about that fraction); the
paper's own condition (4) of paper 001, Ω² ≫ λ|ω| ≫ |ω|², is reported as printed with ratios
≥ 10. Where the averaged reduction is exact (symmetric body; cavity, axial constant torque,
axisymmetric diagonal resistance, damper), the fast-frequency condition is not needed and is
reported as such.
"""

from __future__ import annotations

from gyrostat.assumptions import PAPER_RATIO, SMALL, Assumption, ValidityWarning, check
from gyrostat.scene import Scene

__all__ = ["SMALL", "PAPER_RATIO", "ValidityWarning", "Assumption", "check", "check_scene"]


def check_scene(scene, warn: bool = True, *, allow_import=None) -> list[Assumption]:
    """Checks a scene (a :class:`gyrostat.scene.Scene` or the path of its TOML file) at its
    initial state, for every model the scene uses, without solving it. (`gyrostat run` checks
    along the whole solution.)

    Parameters
    ----------
    scene : gyrostat.scene.Scene or str or pathlib.Path
        The scene or its file.
    allow_import : str or list of str, optional
        Modules whose code a scene file may name (:meth:`gyrostat.scene.Scene.from_file`).
    warn : bool, optional
        Warn for each broken assumption (default True).

    Examples
    --------
    >>> from gyrostat import validity
    >>> from gyrostat.scene import SCENES
    >>> broken = [c for c in validity.check_scene(SCENES / "p002_paper_scene.toml", warn=False) if not c.holds]
    >>> broken[0].statement
    'Reynolds number |ω| b²/ν ≪ 1'
    """
    if not isinstance(scene, Scene):
        scene = Scene.from_file(scene, allow_import=allow_import)
    results: list[Assumption] = []
    for run in scene.runs:
        results += scene.kind.initial_assumptions(run, warn)
    return results
