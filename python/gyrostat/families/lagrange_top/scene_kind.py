"""The Lagrange top's scene kind ``lagrange_top`` (:class:`LagrangeTopKind`: schema and
defaults, runs, ladder rungs, checks, analysis, plots), registered."""

from __future__ import annotations

import math

import numpy as np

from gyrostat import ladder as _ladder
from gyrostat.assumptions import SMALL
from gyrostat.kind import (Kind, Run, build, engine_option, integration, integration_table, outputs_field, register,
                           title_fields)
from gyrostat.schema import Choice, Field, ListOf, SceneError, Table, Vector, all_finite, finite, positive
from gyrostat.families.lagrange_top.analyses import analyse, top_slow_variables
from gyrostat.families.lagrange_top.models import (SEPARATRIX_LIMIT, LagrangeAveraged, LagrangeTop, check, initial_state, nutation_table,
                        paper_torque)
from gyrostat.families.lagrange_top.plots import draw


WHY_TOLERANCES = ("the scene compares the full top with the nutation-averaged one over a long slow time, whose "
                  "O(eps) difference the integration error must stay far below")


class LagrangeTopKind(Kind):
    name = "lagrange_top"
    doc = ("Paper 003: the heavy symmetric top under M = eps(-a(tau) p, -a(tau) q, -b(tau) r), tau = eps t: the "
           "full top in (omega, quaternion) next to the system averaged over the nutation in (G_z, H, r).")
    plots = ("slow", "roots", "nutation", "validity", "ladder")
    splits = True

    def ladder(self, doc):
        return _lagrange_ladder(self, doc)

    @property
    def schema(self) -> Table:
        return Table({
            **title_fields(),
            "body": Field(Table({"A": Field(float, required=True, doc="equatorial moment", unit="kg m^2",
                                            check=positive),
                                 "C": Field(float, required=True, doc="axial moment", unit="kg m^2", check=positive),
                                 "mu": Field(float, required=True, doc="m g l", unit="N m", check=positive)}),
                          required=True, doc="the top"),
            "torque": Field(Table({"epsilon": Field(float, required=True, doc="eps", check=positive),
                                   "a": Field(ListOf(float, min_len=1), required=True, doc="a_k: a(tau) = sum a_k tau^k"),
                                   "b": Field(ListOf(float, min_len=1), required=True,
                                              doc="b_k: b(tau) = sum b_k tau^k")}),
                            required=True, doc="paper 003's torque (3.1)"),
            "initial": Field(Table({
                "omega": Field(Vector(3), required=True, doc="angular velocity in body axes", unit="rad/s",
                               check=all_finite),
                "theta_deg": Field(float, default=0.0, doc="nutation angle", unit="deg", check=finite),
                "phi_deg": Field(float, default=0.0, doc="proper rotation angle", unit="deg", check=finite),
                "psi_deg": Field(float, default=0.0, doc="precession angle", unit="deg", check=finite),
            }), required=True, doc="the initial state (z-x-z Euler angles)"),
            "integration": integration_table(
                Field(Choice("compare", "auto", "full", "averaged"), default="compare",
                      doc="compare: the full and the averaged top side by side; auto: the cheapest that meets the "
                          "accuracy (the model ladder)"),
                rtol=engine_option("rtol", float, "relative tolerance", 1e-10, WHY_TOLERANCES),
                atol=engine_option("atol", float, "absolute tolerance", 1e-12, WHY_TOLERANCES),
                tau_end=Field(float, required=True, doc="end of the slow time tau = eps t", unit="s", check=positive),
                n_out=engine_option("n_out", int, "number of output times", 4001,
                                    "enough points per nutation period over the paper's slow-time span to draw the "
                                    "nutation"),
                splitting=True),
            "outputs": outputs_field(self.plots, ["slow", "roots", "nutation", "validity"]),
        })

    def runs(self, doc):
        b, tq, ini = doc["body"], doc["torque"], doc["initial"]
        torque = build("torque", paper_torque, tq["epsilon"], tq["a"], tq["b"])
        full = build("body", LagrangeTop, b["A"], b["C"], b["mu"], [torque])
        averaged = build("body", LagrangeAveraged, b["A"], b["C"], b["mu"], [torque])
        y0 = initial_state(ini["omega"], math.radians(ini["theta_deg"]), math.radians(ini["phi_deg"]),
                                    math.radians(ini["psi_deg"]))
        span = (0.0, doc["integration"]["tau_end"] / tq["epsilon"])
        options = integration(doc, self)
        choice = doc["integration"]["model"]
        if options["method"] == "splitting" and choice != "full":
            raise SceneError(f"[integration] method = 'splitting' splits the full top only (the averaged top has no "
                             f"free rotation to split on): set model = 'full' (got model = '{choice}')")
        if choice in ("full", "averaged"):
            return ([Run(choice, full if choice == "full" else averaged, y0, span, options)], choice,
                    "asked for by the scene")
        return ([Run("full", full, y0, span, options), Run("averaged", averaged, y0, span, options)],
                "full_and_averaged",
                f"paper 003: full top (omega, quaternion) next to the nutation-averaged (G_z, H, r) system; "
                f"epsilon = {tq['epsilon']:g}, a = {tq['a']}, b = {tq['b']}")

    def analyse(self, scene, solutions, report, derived):
        analyse(scene, solutions, report, derived)

    def extra_columns(self, scene, solution):
        """The slow time τ = εt of paper 003, beside t."""
        return {"tau": (scene.doc["torque"]["epsilon"] * solution.t, "s")}

    def draw(self, scene, solutions, derived, folder):
        return draw(scene, solutions, derived, folder)


def _lagrange_ladder(kind: "LagrangeTopKind", doc: dict) -> list:
    """The heavy top's rungs: averaged over the nutation in (G_z, H, r), then the full top.
    The averaged one is blocked when a plot needs θ(t) itself; it watches the adiabaticity N and
    the distance from the separatrix 1 − k², switching to the full top where either fails."""
    runs, _, _ = kind.runs({**doc, "integration": {**doc["integration"], "model": "compare"}})
    full, averaged = runs
    slow0 = np.asarray(averaged.model._core.initial_state(full.y0))
    period = float(nutation_table(averaged.model, slow0)["T_nut"][0])
    needs = [p for p in doc["outputs"]["plots"] if p == "nutation"]
    top = _ladder.Rung("full", full.model, full.y0, "the full top (omega, quaternion)",
                       compare=top_slow_variables)
    limit = SEPARATRIX_LIMIT
    lower = _ladder.Rung(
        "averaged", averaged.model, slow0, "the top averaged over the nutation, in (G_z, H, r)",
        compare=top_slow_variables, fast_period=period if period > 0 else math.inf,
        blocked=f"the plots {needs} need theta(t): the averaged top gives its bounds only" if needs else "",
        watches=(_ladder.Watch("adiabaticity", SMALL, 0.5 * SMALL,
                               "nutation period short against the slow time, N << 1", scales_error=True),
                 _ladder.Watch("m", 1.0 - limit, 1.0 - 2.0 * limit, "away from the separatrix, 1 - k^2 >= 1e-3")),
        start_checks=lambda: check(averaged.model, slow0, [0.0], warn=False), run="averaged")
    return [lower, top]


register(LagrangeTopKind())
