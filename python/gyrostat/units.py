"""Units of every named quantity the library writes, in one table (CSV/NPZ headers, NetCDF
attributes, report.json)."""

from __future__ import annotations

UNITS: dict[str, str] = {
    # time and clocks
    "t": "s", "tau": "s", "T_nut": "s",
    # angular velocity and slow variables
    "p": "rad/s", "q": "rad/s", "r": "rad/s", "a": "rad/s", "fast_frequency": "rad/s",
    "x": "rad^2/s^2", "y": "rad^2/s^2",
    # attitude
    "q_w": "1", "q_x": "1", "q_y": "1", "q_z": "1",
    "psi": "rad", "theta": "rad", "phi": "rad", "theta_G": "rad", "phi_G": "rad", "cos_theta": "1",
    # moving mass
    "u_1": "m", "u_2": "m", "u_3": "m", "v_1": "m/s", "v_2": "m/s", "v_3": "m/s",
    # invariants
    "angular_momentum_norm": "kg m^2/s", "kinetic_energy": "J", "energy": "J", "h": "kg m^2/s^2",
    "G_z": "kg m^2/s", "H": "J",
    # Lagrange top
    "u1": "1", "u2": "1", "u3": "1", "m": "1", "v": "1", "adiabaticity": "1",
    # orthogonal torque
    "g": "1", "L": "N m", "Q_norm": "kg m^2/s^2", "delta": "kg m^2/s^2", "regularised": "1",
    # averaged
    "slow_to_fast": "1",
}
"""The unit of every named quantity the library writes ("1": dimensionless)."""


def unit(name: str) -> str:
    return UNITS.get(name, "1")

