"""Paper 004: a free gyrostat under a servo torque orthogonal to its momentum G and its angular
velocity ω (Makeev): magnitude laws, :class:`OrthogonalModel`, the report of where τ(t) stops
(:func:`tau_report`), the torque-free gyrostat at τ(t) and the nearly spherical approximations of
§4 (:class:`NearlySpherical`). Re-exported from the orthogonal torque family,
:mod:`gyrostat.families.orthogonal_torque`."""

from gyrostat.families.orthogonal_torque import (ETA, G_FALLS, G_RISES, NearlySpherical, OrthogonalModel,
                                                 attitude_along_momentum, constant, constant_law_regime, g_zero,
                                                 harmonic, law_from_spec, orbit_q_range, polynomial, tabulated,
                                                 tau_report, torque_free_at_tau, wrap)

__all__ = ["ETA", "constant", "polynomial", "harmonic", "tabulated", "law_from_spec", "OrthogonalModel", "G_FALLS",
           "G_RISES", "g_zero", "tau_report", "orbit_q_range", "constant_law_regime", "torque_free_at_tau",
           "attitude_along_momentum", "wrap", "NearlySpherical"]
