"""Paper 003: a heavy symmetric top (Lagrange case) under a small, slowly varying torque: the full
top :class:`LagrangeTop`, the nutation-averaged :class:`LagrangeAveraged`, the paper's torque,
initial states, the nutation table, the averaged model's checks, events and the exact r of
(3.3). Re-exported from the Lagrange top family, :mod:`gyrostat.families.lagrange_top`."""

from gyrostat.families.lagrange_top import (SEPARATRIX_LIMIT, LagrangeAveraged, LagrangeTop, averaging_fails, check,
                                            initial_state, near_separatrix, nutation_table, paper_torque, r_exact,
                                            turning_points, unperturbed, vertical)

__all__ = ["SEPARATRIX_LIMIT", "paper_torque", "LagrangeTop", "LagrangeAveraged", "initial_state", "vertical",
           "nutation_table", "unperturbed", "check", "turning_points", "near_separatrix", "averaging_fails", "r_exact"]
