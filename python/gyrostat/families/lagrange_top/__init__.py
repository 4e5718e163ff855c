"""The Lagrange top family (paper 003): a heavy symmetric top under a small, slowly varying torque.

A family module provides its models (``ModelBase`` subclasses with their own assumptions), its
paper helpers and analysis, its plots (drawn with :mod:`gyrostat.figures`), its scene kind(s)
(:class:`gyrostat.kind.Kind`: schema and defaults, runs, ladder rungs, checks, analysis, plots)
and one ``register(...)`` line; see :mod:`gyrostat.families.rigid_body` for the full recipe.
Here the kind ``lagrange_top``, whose ladder is: averaged over the nutation (G_z, H, r) -> full
top (ω, quaternion). :mod:`gyrostat.lagrange` re-exports the models and helpers.

Two models, both integrated by the C++ core:

* :class:`LagrangeTop` — the full model. State ``(p, q, r, Q_w, Q_x, Q_y, Q_z)``: angular
  velocity in body axes and the body→space quaternion (z up); the vertical in body axes
  γ = third row of R(Q). No Euler angles are integrated: θ, ψ, φ are outputs only.
* :class:`LagrangeAveraged` — the system averaged over the nutation in the slow variables
  ``(G_z, H, r)`` (the unperturbed first integrals; smooth, no sign bookkeeping), with
  v = ⟨cos θ⟩ = u1 + (u2 − u1)(K − E)/(m K). The roots u1 ≤ u2 ≤ u3 of the nutation cubic are
  reported for every output (the paper's variables).

Both take torques from the library's set; paper 003's (3.1), M = ε(−a(τ)p, −a(τ)q, −b(τ)r),
τ = εt, is :func:`paper_torque` (a ResistiveMedium). Both use the same clock t; the slow time is
τ = εt. The equations, the checks and the discrepancies with the paper are in
docs/papers/003_lagrange_top.md.

Validity of the averaged model (:func:`check`): the nutation period must be short against the
slow time scale, N = rate · T_nut ≪ 1 (rate = max(d/A, d3/C) of the damping), and the motion
must stay away from the separatrix (1 − k² ≳ 1e-3, where K diverges). Broken assumptions are
warned about (:class:`gyrostat.ValidityWarning`) with the number and what to use instead.

The family, one concern a module: ``models`` (the models and their assumptions, :func:`check`;
the paper's torque, initial states, the nutation table), ``analyses`` (the unperturbed motion,
the exact r, :func:`analyse`), ``events``, ``plots`` (:func:`draw`) and ``scene_kind``
(:class:`LagrangeTopKind`, registered when the family is imported).
"""

from gyrostat.families.lagrange_top.analyses import analyse, r_exact, top_slow_variables, unperturbed
from gyrostat.families.lagrange_top.events import averaging_fails, near_separatrix, turning_points
from gyrostat.families.lagrange_top.models import (SEPARATRIX_LIMIT, LagrangeAveraged, LagrangeTop, check, initial_state,
                                                   nutation_table, paper_torque, vertical)
from gyrostat.families.lagrange_top.plots import draw
from gyrostat.families.lagrange_top.scene_kind import WHY_TOLERANCES, LagrangeTopKind

__all__ = ["SEPARATRIX_LIMIT", "paper_torque", "LagrangeTop", "LagrangeAveraged", "initial_state", "vertical",
           "nutation_table", "unperturbed", "check", "turning_points", "near_separatrix", "averaging_fails", "r_exact",
           "top_slow_variables", "analyse", "draw", "WHY_TOLERANCES", "LagrangeTopKind"]
