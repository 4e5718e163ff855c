"""The orthogonal torque family's analysis of a scene's runs (:func:`analyse`): the g = 0
report, the torque-free gyrostat at τ(t) and the errors of the nearly spherical approximations."""

from __future__ import annotations

import numpy as np

from gyrostat import attitude
from gyrostat.families.orthogonal_torque.free_motion import torque_free_at_tau, wrap
from gyrostat.families.orthogonal_torque.tau import constant_law_regime, tau_report


def analyse(scene, solutions: dict, report: dict, derived: dict) -> None:
    """Per run: the g = 0 report, the torque-free gyrostat at τ(t) and, for a nearly spherical body,
    the errors of the approximations of section 4."""
    kind = scene.kind
    spherical = kind.spherical(scene.doc)
    for run in scene.runs:
        sol, model = solutions[run.name], run.model
        entry = report["runs"][run.name]
        if not len(sol):
            continue
        omega0, q0 = run.y0[:3], run.y0[3:7]
        g_report = tau_report(model, sol)  # from the g = 0 events the run watched
        sol.notes.extend(g_report["messages"])
        regime = constant_law_regime(model, omega0)
        if regime:
            sol.notes.append(regime)
        entry["notes"] = list(sol.notes)
        entry["g_report"] = {k: v for k, v in g_report.items() if k != "messages"}
        if g_report["crossings"] or g_report["min_g"] <= 0:
            report["broken_assumptions"].append(
                f"{run.name}: g = 1 - L/|Q| reaches {g_report['min_g']:.3g} <= 0: tau(t) is not a homeomorphism "
                "(the paper's (10) assumes g > 0)")
        if g_report["regularised_times"]:
            report["broken_assumptions"].append(f"{run.name}: |Q| < delta at some times: the prescribed L was not "
                                                "applied there")
        tau = sol["tau"]
        zv = torque_free_at_tau(model, omega0, tau)
        zv_angles = attitude.euler_angles(torque_free_at_tau(model, omega0, tau, q0)[:, 3:7])
        entry["max_error_vs_torque_free_at_tau"] = float(np.max(np.abs(sol.omega - zv)))
        entry["tau_end"] = float(tau[-1])
        entry["min_g"] = g_report["min_g"]
        entry["max_psi_full_minus_zv"] = float(np.max(np.abs(wrap(sol["psi"] - zv_angles[:, 0]))))
        approx = {"exact": zv_angles}
        if spherical is not None:
            approx["zeroth"], approx["first"] = spherical.zeroth(tau), spherical.first(tau)
            for label in ("zeroth", "first"):
                a = approx[label]
                entry[f"max_error_{label}_theta"] = float(np.max(np.abs(sol["theta_G"] - a[:, 1])))
                entry[f"max_error_{label}_phi"] = float(np.max(np.abs(wrap(sol["phi_G"] - a[:, 2]))))
                entry[f"max_error_{label}_psi_vs_zv"] = float(np.max(np.abs(wrap(zv_angles[:, 0] - a[:, 0]))))
            if not np.any(spherical.k):
                entry["mean_precession_rate_corrected_34"] = spherical.mean_precession_rate()
                entry["mean_spin_rate_quadrature"] = spherical.mean_spin_rate()
        derived[run.name] = {"torque_free": zv, "approximations": approx, "g_report": g_report}

