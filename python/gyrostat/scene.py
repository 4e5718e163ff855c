"""Scenes: a body, its torques, an initial state, a horizon, an integrator and outputs, as TOML.

A scene file looks like::

    title = "Damped body under a constant torque"
    [body]
    moments = [1.0, 2.0, 3.0]        # principal moments A1, A2, A3 [kg m^2]
    rotor = [0.0, 0.0, 0.0]          # gyrostatic momentum k [kg m^2/s], optional
    [[torques]]
    type = "constant"                # M = (M1, M2, M3) [N m]
    moment = [0.0, 0.0, 0.05]
    [[torques]]
    type = "linear_damping"          # M = -D omega
    matrix = [[0.02, 0, 0], [0, 0.02, 0], [0, 0, 0.01]]
    [initial]
    omega = [1.0, 0.5, -0.3]         # [rad/s]
    attitude = [1.0, 0.0, 0.0, 0.0]  # optional quaternion (w, x, y, z): integrates the attitude
    [integration]
    model = "auto"                   # "auto" | "full" | "closed_form"
    method = "dop853"
    rtol = 1e-10
    atol = 1e-12
    t_span = [0.0, 100.0]            # [s]
    n_out = 2001
    [outputs]
    plots = ["omega", "invariants", "euler_angles"]
    reference = "closed_form"        # optional: draw and measure against the closed form

Other torques: ``viscous_cavity`` (density, viscosity, radius | p0), ``resistive_medium``
(coefficients = [D_0, D_1, ...], D(t) = Σ D_k t^k), ``moving_mass_damper`` (mass, arm,
frequency, damping). ``model = "averaged"`` solves the system averaged over the symmetric
Euler–Poinsot motion in (a, r); ``model = "compare"`` solves the full and the averaged model
side by side and reports their difference. Plots ``xy`` (x = a², y = r² over time), ``slow``
(a and signed r), ``phase`` (a² against r²) serve the averaged scenes. Every scene's
assumptions are checked (gyrostat.validity) and broken ones reported.
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from gyrostat import _core
from gyrostat.model import Model

KNOWN_PLOTS = ("omega", "invariants", "euler_angles", "error", "xy", "slow", "phase")
KNOWN_MODELS = ("auto", "full", "closed_form", "averaged", "compare")


def _vector(table: dict, key: str, size: int, where: str) -> np.ndarray:
    if key not in table:
        raise ValueError(f"{where}: missing '{key}'")
    value = np.asarray(table[key], dtype=float)
    if value.shape != (size,):
        raise ValueError(f"{where}.{key} must have {size} numbers, got {table[key]!r}")
    return value


def _torque(spec: dict, index: int):
    where = f"torques[{index}]"
    kind = spec.get("type")
    if kind == "constant":
        return _core.ConstantTorque(_vector(spec, "moment", 3, where))
    if kind == "linear_damping":
        if "matrix" in spec:
            matrix = np.asarray(spec["matrix"], dtype=float)
            if matrix.shape != (3, 3):
                raise ValueError(f"{where}.matrix must be 3x3, got {spec['matrix']!r}")
        elif "diagonal" in spec:
            matrix = np.diag(_vector(spec, "diagonal", 3, where))
        else:
            raise ValueError(f"{where}: linear_damping needs 'matrix' (3x3) or 'diagonal' (3)")
        return _core.LinearDamping(matrix)
    if kind == "resistive_medium":
        if "coefficients" not in spec:
            raise ValueError(f"{where}: resistive_medium needs 'coefficients' (a list of 3x3 matrices, D(t) = sum D_k t^k)")
        matrices = [np.asarray(c, dtype=float) for c in spec["coefficients"]]
        for k, matrix in enumerate(matrices):
            if matrix.shape != (3, 3):
                raise ValueError(f"{where}.coefficients[{k}] must be 3x3")
        return _core.ResistiveMedium(matrices)
    if kind == "viscous_cavity":
        for key in ("density", "viscosity"):
            if key not in spec:
                raise ValueError(f"{where}: viscous_cavity needs '{key}'")
        if "radius" in spec:
            return _core.ViscousCavity.sphere(float(spec["density"]), float(spec["viscosity"]), float(spec["radius"]))
        if "p0" in spec:
            return _core.ViscousCavity(float(spec["density"]), float(spec["viscosity"]), float(spec["p0"]))
        raise ValueError(f"{where}: viscous_cavity needs 'radius' (sphere) or 'p0' (P = P0 I)")
    if kind == "moving_mass_damper":
        for key in ("mass", "arm", "frequency", "damping"):
            if key not in spec:
                raise ValueError(f"{where}: moving_mass_damper needs '{key}'")
        return _core.MovingMassDamper(float(spec["mass"]), float(spec["arm"]), float(spec["frequency"]),
                                      float(spec["damping"]))
    raise ValueError(f"{where}.type = {kind!r} is not a known torque (constant, linear_damping, resistive_medium, "
                     "viscous_cavity, moving_mass_damper)")


@dataclass
class Scene:
    """A runnable scene; build it with :meth:`Scene.from_toml` or :meth:`Scene.from_dict`."""

    name: str
    title: str
    body: _core.Body
    torques: list
    omega0: np.ndarray
    attitude0: np.ndarray | None
    model_choice: str
    method: str
    rtol: float
    atol: float
    t_span: tuple[float, float]
    n_out: int
    plots: list[str] = field(default_factory=list)
    reference: str | None = None
    description: str = ""

    @classmethod
    def from_toml(cls, path: str | Path) -> "Scene":
        path = Path(path)
        with path.open("rb") as handle:
            try:
                data = tomllib.load(handle)
            except tomllib.TOMLDecodeError as error:
                raise ValueError(f"{path}: not valid TOML: {error}") from None
        return cls.from_dict(data, name=path.stem)

    @classmethod
    def from_dict(cls, data: dict, name: str = "scene") -> "Scene":
        body_spec = data.get("body")
        if not isinstance(body_spec, dict):
            raise ValueError("scene: missing [body] table")
        moments = _vector(body_spec, "moments", 3, "body")
        rotor = _vector(body_spec, "rotor", 3, "body") if "rotor" in body_spec else np.zeros(3)
        body = _core.Body(moments, rotor)
        torques = [_torque(spec, i) for i, spec in enumerate(data.get("torques", []))]
        initial = data.get("initial", {})
        omega0 = _vector(initial, "omega", 3, "initial")
        attitude0 = _vector(initial, "attitude", 4, "initial") if "attitude" in initial else None
        if attitude0 is not None:
            norm = float(np.linalg.norm(attitude0))
            if not math.isfinite(norm) or norm == 0.0:
                raise ValueError(f"initial.attitude = {initial['attitude']!r} is not a usable quaternion")
            attitude0 = attitude0 / norm
        integ = data.get("integration", {})
        model_choice = integ.get("model", "auto")
        if model_choice not in KNOWN_MODELS:
            raise ValueError(f"integration.model = {model_choice!r}; choose one of {', '.join(KNOWN_MODELS)}")
        t_span = _vector(integ, "t_span", 2, "integration")
        outputs = data.get("outputs", {})
        plots = list(outputs.get("plots", ["omega", "invariants"]))
        for plot in plots:
            if plot not in KNOWN_PLOTS:
                raise ValueError(f"outputs.plots: {plot!r} is not one of {', '.join(KNOWN_PLOTS)}")
        reference = outputs.get("reference")
        if reference not in (None, "closed_form"):
            raise ValueError(f"outputs.reference = {reference!r}; only 'closed_form' is known")
        return cls(
            name=name,
            title=str(data.get("title", name)),
            description=str(data.get("description", "")),
            body=body,
            torques=torques,
            omega0=omega0,
            attitude0=attitude0,
            model_choice=model_choice,
            method=str(integ.get("method", "dop853")),
            rtol=float(integ.get("rtol", 1e-8)),
            atol=float(integ.get("atol", 1e-10)),
            t_span=(float(t_span[0]), float(t_span[1])),
            n_out=int(integ.get("n_out", 1001)),
            plots=plots,
            reference=reference,
        )

    @property
    def needs_attitude(self) -> bool:
        """The attitude is integrated only when the scene asks for it (an initial quaternion or
        an Euler-angle plot)."""
        return self.attitude0 is not None or "euler_angles" in self.plots

    def model(self) -> Model:
        return Model(self.body, self.torques, attitude=self.needs_attitude)

    def averaged_model(self):
        from gyrostat.model import AveragedModel

        return AveragedModel(self.body, self.torques)

    @property
    def slow0(self) -> np.ndarray:
        """(a, r) of the initial state: a = √(p² + q²), r signed."""
        return np.array([math.hypot(self.omega0[0], self.omega0[1]), self.omega0[2]])

    def choose_model(self) -> tuple[str, str]:
        """The cheapest model that answers the scene, and the reason for the choice."""
        free = not self.torques and not np.any(np.asarray(self.body.rotor))
        if self.model_choice == "closed_form":
            if not free:
                raise ValueError("integration.model = 'closed_form' needs a rigid body (k = 0) with no torque")
            if self.needs_attitude:
                raise ValueError("integration.model = 'closed_form' gives omega only; the scene asks for attitude")
            return "closed_form", "asked for by the scene"
        if self.model_choice in ("full", "averaged", "compare"):
            return self.model_choice, "asked for by the scene"
        if free and not self.needs_attitude:
            return "closed_form", "no torque, no rotor, no attitude asked for: the closed form needs no integration"
        reasons = []
        if self.torques:
            reasons.append(f"{len(self.torques)} torque(s)")
        if np.any(np.asarray(self.body.rotor)):
            reasons.append("a rotor (k != 0)")
        if self.needs_attitude:
            reasons.append("attitude asked for")
        return "full", "full model: " + ", ".join(reasons)
