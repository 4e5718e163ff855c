"""A rigid body on a circular orbit, seen from the orbit frame (LVLH: x along track, y minus the
orbit normal, z nadir; docs/orbit_frame.md): the scene's ``[orbit]`` table, a body given by its
gravity-gradient inertia ratios (k_R, k_P), the classical linear frequencies of its libration,
the plots of roll, pitch and yaw and of the precession of G about the orbit normal, and what a
scene reports of them. The outputs themselves (quaternion body → orbit frame, roll, pitch, yaw,
ω relative to the orbit frame, azimuth of G) are the C++ model's (model/orbiting.hpp)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from gyrostat import _core
from gyrostat import torques as _torques
from gyrostat.figures import LEGEND_SIZE, finish, plt
from gyrostat.schema import Field, SceneError, Vector, all_finite
from gyrostat.solution import Solution

ORBIT = Field(_torques.schema(_core.Orbit),
              doc="the circular orbit the body is on: every orbit torque without its own orbit reads it, and the run "
                  "records the attitude relative to the orbit frame (LVLH: x along track, y minus the orbit normal, "
                  "z nadir; docs/orbit_frame.md)")
"""The scene's ``[orbit]`` table, from :class:`gyrostat.Orbit`'s declared parameters."""

INERTIA_RATIOS = Field(Vector(2), unit="", check=all_finite,
                       doc="instead of moments: the gravity-gradient inertia ratios [k_R, k_P] = [(B - C)/A, "
                           "(A - C)/B] of moments (A, B, C) about (roll x, pitch y, yaw z), B = 1: A = (1 + k_P)/"
                           "(1 + k_R), C = A - k_P (each in (-1, 1))")
"""``[body] inertia_ratios``: a body from its (k_R, k_P)."""

SINGULAR_COS_PITCH = 0.05  # roll and yaw are ill-defined where |cos pitch| is below this


def moments_from_ratios(k_roll: float, k_pitch: float) -> np.ndarray:
    """The principal moments (A, B, C) about roll x, pitch y, yaw z with B = 1 of the inertia
    ratios k_R = (B − C)/A, k_P = (A − C)/B.

    Parameters
    ----------
    k_roll, k_pitch : float
        The ratios, each in (−1, 1).

    Returns
    -------
    numpy.ndarray, shape (3,)
        (A, B, C) = ((1 + k_P)/(1 + k_R), 1, A − k_P); a ValueError names a pair no body has.

    Examples
    --------
    >>> moments_from_ratios(0.5, 0.25)
    array([0.83333333, 1.        , 0.58333333])
    """
    if not (abs(k_roll) < 1 and abs(k_pitch) < 1):
        raise ValueError(f"inertia_ratios = [{k_roll}, {k_pitch}]: each must be in (-1, 1)")
    a = (1.0 + k_pitch) / (1.0 + k_roll)
    moments = np.array([a, 1.0, a - k_pitch])
    return moments


def body_of(doc: dict, make_body) -> _core.Body:
    """The scene's body: from ``[body] inertia_ratios`` when given, else ``make_body(doc)``."""
    body = doc["body"]
    if "inertia_ratios" not in body:
        return make_body(doc)
    try:
        return _core.Body(moments_from_ratios(*body["inertia_ratios"]), body["rotor"])
    except ValueError as error:
        raise SceneError(f"[body] {error}") from None


def make_orbit(doc: dict) -> _core.Orbit | None:
    """The scene's ``[orbit]`` as a :class:`gyrostat.Orbit` (None without one)."""
    if "orbit" not in doc:
        return None
    try:
        return _core.Orbit(**doc["orbit"])
    except ValueError as error:
        raise SceneError(f"[orbit] {error}") from None


def libration_frequencies(moments, rate: float) -> dict[str, float]:
    """The classical linear gravity-gradient libration frequencies about the orbit frame
    (docs/orbit_frame.md derives them), for moments (A, B, C) about roll x, pitch y, yaw z:
    pitch n √(3 k_P), and the two roll–yaw frequencies n √Ω² from Ω⁴ − (1 + 3 k_R + k_R k_Y) Ω²
    + 4 k_R k_Y = 0, k_R = (B − C)/A, k_P = (A − C)/B, k_Y = (B − A)/C (NaN where unstable).

    Parameters
    ----------
    moments : array_like, shape (3,)
        (A, B, C), in kg m^2.
    rate : float
        The orbit rate n, in rad/s.

    Returns
    -------
    dict
        ``pitch``, ``roll_yaw_low``, ``roll_yaw_high`` in rad/s.

    Examples
    --------
    >>> f = libration_frequencies([2.0, 2.5, 1.0], 1.0)
    >>> round(f["pitch"], 6), round(f["roll_yaw_low"], 6), round(f["roll_yaw_high"], 6)
    (1.095445, 0.690219, 1.774429)
    """
    a, b, c = (float(x) for x in moments)
    k_r, k_p, k_y = (b - c) / a, (a - c) / b, (b - a) / c
    s = 1.0 + 3.0 * k_r + k_r * k_y
    p = 4.0 * k_r * k_y
    root = s * s - 4.0 * p
    low = high = math.nan
    if root >= 0 and s > 0 and p > 0:
        low, high = (rate * math.sqrt((s + sign * math.sqrt(root)) / 2.0) for sign in (-1.0, 1.0))
    return {"pitch": rate * math.sqrt(3.0 * k_p) if k_p > 0 else math.nan, "roll_yaw_low": low, "roll_yaw_high": high}


def crossing_period(t: np.ndarray, x: np.ndarray) -> float:
    """The mean period of x(t) from its upward zero crossings (linear interpolation between
    samples; NaN with fewer than two)."""
    x = np.asarray(x, float) - np.mean(x)
    up = np.nonzero((x[:-1] < 0) & (x[1:] >= 0))[0]
    if len(up) < 2:
        return math.nan
    times = t[up] - x[up] * (t[up + 1] - t[up]) / (x[up + 1] - x[up])
    return float((times[-1] - times[0]) / (len(times) - 1))


def orbit_angles(solution: Solution, title: str, path: Path) -> Path:
    """Roll, pitch and yaw (the 3-2-1 angles body → orbit frame) in degrees against the orbits
    flown, the times where the sequence is singular (|cos pitch| small) shaded."""
    orbits = solution.t * solution.model.orbit.rate / (2 * math.pi)
    fig, ax = plt.subplots(figsize=(8, 4.5))
    for name, color in (("roll", "tab:blue"), ("pitch", "tab:red"), ("yaw", "tab:green")):
        ax.plot(orbits, np.degrees(solution[name]), color=color, lw=1.2, label=name)
    near = np.abs(np.cos(solution["pitch"])) < SINGULAR_COS_PITCH
    if near.any():
        ax.fill_between(orbits, 0, 1, where=near, transform=ax.get_xaxis_transform(), color="tab:gray", alpha=0.3,
                        label=f"singular (3-2-1): |cos pitch| < {SINGULAR_COS_PITCH}")
    return _finish(fig, ax, path, "orbits flown, n t / 2π", "angle to the orbit frame [deg]",
                   f"{title}: roll, pitch, yaw (3-2-1) to the orbit frame", "upper right")


def _finish(fig, ax, path: Path, xlabel: str, ylabel: str, title: str, legend: str) -> Path:
    """Labels, title, legend and grid of a one-panel plot, written to ``path``."""
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.legend(fontsize=LEGEND_SIZE, loc=legend)
    ax.grid(alpha=0.3)
    return finish(fig, path)


def precession(solution: Solution, rate: float, title: str, path: Path) -> Path:
    """The azimuth of G about the orbit normal (unwrapped, from its start) against the averaged
    theory's straight line of slope ``rate``."""
    fig, ax = plt.subplots(figsize=(8, 4.5))
    azimuth = np.unwrap(solution["momentum_azimuth"])
    ax.plot(solution.t, np.degrees(azimuth - azimuth[0]), color="k", lw=1.0, label="full model")
    ax.plot(solution.t, np.degrees(rate * (solution.t - solution.t[0])), color="tab:red", lw=2.0, alpha=0.6,
            label=f"averaged theory, {rate:.3g} rad/s (GravityGradient.precession_rate)")
    return _finish(fig, ax, path, "t [s]", "azimuth of G about the orbit normal [deg]", f"{title}: precession of G",
                   "best")


def precession_rate(solution: Solution) -> tuple[float, float]:
    """(measured, theory): the slope of G's azimuth about the orbit normal fitted over the run
    (least squares: the twice-per-orbit wobble averages out), and the averaged rate of each
    gravity-gradient torque at the start (GravityGradient.precession_rate on the model's orbit;
    NaN without one)."""
    model = solution.model
    azimuth = np.unwrap(solution["momentum_azimuth"])
    measured = float(np.polyfit(solution.t, azimuth, 1)[0])
    theory = sum(torque.precession_rate(model.body.moments, solution.omega[0], solution.quaternion[0], orbit=model.orbit)
                 for torque in model.torques if isinstance(torque, _core.GravityGradient))
    return measured, float(theory) if any(isinstance(x, _core.GravityGradient) for x in model.torques) else math.nan


def analyse(solution: Solution, report: dict) -> None:
    """What a run on an orbit reports: the largest roll, pitch and yaw, the pitch period from its
    zero crossings against the linear theory's, and, for a body spinning fast against the orbit
    (|ω| > 10 n, the averaging's condition), G's precession about the orbit normal against
    GravityGradient.precession_rate."""
    orbit = solution.model.orbit
    found = {f"max_abs_{name}": float(np.max(np.abs(solution[name]))) for name in ("roll", "pitch", "yaw")}
    theory = libration_frequencies(solution.model.body.moments, orbit.rate)
    # a libration to time: pitch well above what rounding moves a body at rest (1e-8 rad over a run)
    period = crossing_period(solution.t, solution["pitch"]) if found["max_abs_pitch"] > 1e-6 else math.nan
    if math.isfinite(period) and math.isfinite(theory["pitch"]):
        found["pitch_period"] = period
        found["pitch_period_linear_theory"] = 2 * math.pi / theory["pitch"]
    measured, rate = precession_rate(solution)
    spin = float(np.linalg.norm(solution.omega[0]))
    if math.isfinite(rate) and spin > 10 * orbit.rate:  # the averaged rate assumes a spin fast against the orbit
        found["momentum_precession_rate"] = measured
        found["momentum_precession_rate_theory"] = rate
    report["orbit_frame"] = found
