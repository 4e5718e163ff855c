"""The orthogonal torque family (paper 004): a free gyrostat under a servo torque orthogonal to its
momentum G and its angular velocity ω (Makeev). Derivation, checks and measured errors:
docs/papers/004_orthogonal_torque.md.

A family module provides its models (``ModelBase`` subclasses with their own assumptions), its
paper helpers and analysis, its plots (drawn with :mod:`gyrostat.figures`), its scene kind(s)
(:class:`gyrostat.kind.Kind`: schema and defaults, runs, ladder rungs, checks, analysis, plots)
and one ``register(...)`` line; see :mod:`gyrostat.families.rigid_body` for the full recipe.
Here the kind ``orthogonal_torque``; it has one rung, the full model: its exact solution, the
torque-free gyrostat at τ(t), needs τ(t) from the full run, and the nearly spherical
approximations of §4 are compared in the plots, not a rung. :mod:`gyrostat.orthogonal`
re-exports the models and helpers.

The torque is M = L(t) e_L, e_L = Q/|Q|, Q = ω × G, G = Jω + k. It keeps |G| and h = ω·Jω
exactly, and the motion is the torque-free Zhukovsky–Volterra (ZV) gyrostat run on the clock

    τ(t) = ∫ g dt,   g = dτ/dt = 1 − L(t)/|Q(ω)|,      ω(t) = ω_ZV(τ(t)).

At Q = 0 the direction is undefined: below the threshold |Q| < δ = η|ω||G| (η = 1e-3 by
default) the core tapers the torque to L Q/n, n = (|Q|² + δ²)/(2δ) (C¹ at |Q| = δ, zero torque
at Q = 0); at and above it the paper's L Q/|Q| is applied exactly. Both invariants and the clock
stay exact; where |Q| < δ the prescribed L is not applied, and the solution flags those times.

Contents: magnitude laws (:func:`constant`, :func:`polynomial`, :func:`harmonic`,
:func:`tabulated`), :class:`OrthogonalModel` (solved by :func:`gyrostat.solve`, which records
τ(t) as a state and g, L, |Q|, δ, the angles of G in body axes as outputs), :func:`tau_report`
(where g ≤ 0), :func:`torque_free_at_tau` (ω_ZV(τ)) and the nearly spherical approximations of
§4 (:class:`NearlySpherical`).

The family, one concern a module: ``laws`` (the magnitude laws, :data:`ETA`), ``models``
(:class:`OrthogonalModel`), ``tau`` (where τ(t) stops: :func:`g_zero`, :func:`tau_report`, the
regimes of a constant law), ``free_motion`` (:func:`torque_free_at_tau`, the frame of the Euler
angles), ``nearly_spherical`` (:class:`NearlySpherical`), ``analyses`` (:func:`analyse`),
``plots`` (:func:`draw`) and ``scene_kind`` (:class:`OrthogonalTorqueKind`, registered when the
family is imported). The torque-free gyrostat is the rigid body family's :class:`Model`, through
its public name.
"""

from gyrostat.families.orthogonal_torque.analyses import analyse
from gyrostat.families.orthogonal_torque.free_motion import attitude_along_momentum, torque_free_at_tau, wrap
from gyrostat.families.orthogonal_torque.laws import ETA, constant, harmonic, law_from_spec, polynomial, tabulated
from gyrostat.families.orthogonal_torque.models import OrthogonalModel
from gyrostat.families.orthogonal_torque.nearly_spherical import NearlySpherical
from gyrostat.families.orthogonal_torque.plots import draw
from gyrostat.families.orthogonal_torque.scene_kind import LAW, WHY_TOLERANCES, OrthogonalTorqueKind
from gyrostat.families.orthogonal_torque.tau import (G_FALLS, G_RISES, constant_law_regime, g_zero, orbit_q_range,
                                                     tau_report)

__all__ = ["ETA", "constant", "polynomial", "harmonic", "tabulated", "law_from_spec", "OrthogonalModel", "G_FALLS",
           "G_RISES", "g_zero", "tau_report", "orbit_q_range", "constant_law_regime", "torque_free_at_tau",
           "attitude_along_momentum", "wrap", "NearlySpherical", "analyse", "draw", "LAW", "WHY_TOLERANCES",
           "OrthogonalTorqueKind"]
