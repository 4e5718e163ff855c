"""Outputs derived from the averaged system: the papers' x, y variables, paper 002's
Lotka–Volterra coefficients and first integral, and the slow variables of a full solution.
Re-exported from the rigid body family, :mod:`gyrostat.families.rigid_body`."""

from gyrostat.families.rigid_body import (LotkaVolterra, averaging_fails, lotka_volterra, r_zero, slow_variables,
                                          xy)

__all__ = ["slow_variables", "r_zero", "averaging_fails", "xy", "LotkaVolterra", "lotka_volterra"]
