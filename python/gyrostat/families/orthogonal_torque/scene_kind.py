"""The orthogonal torque's scene kind ``orthogonal_torque`` (:class:`OrthogonalTorqueKind`:
schema with the magnitude laws :data:`LAW` and defaults, runs, analysis, plots), registered."""

from __future__ import annotations

import numpy as np

from gyrostat import _core
from gyrostat.families.orthogonal_torque.analyses import analyse
from gyrostat.families.orthogonal_torque.free_motion import attitude_along_momentum
from gyrostat.families.orthogonal_torque.laws import ETA, law_from_spec
from gyrostat.families.orthogonal_torque.models import OrthogonalModel
from gyrostat.families.orthogonal_torque.nearly_spherical import NearlySpherical
from gyrostat.families.orthogonal_torque.plots import draw
from gyrostat.families.orthogonal_torque.tau import g_zero
from gyrostat.kind import (BODY, Kind, Run, build, engine_option, integration, integration_table, make_body,
                           outputs_field, register, title_fields)
from gyrostat.schema import (ArrayOf, Choice, Field, ListOf, OneOf, SceneError, Table, Variants, Vector, all_finite,
                             increasing, nonzero_quaternion, positive, span_order)
from gyrostat.schema import finite as finite_value


LAW = Variants("kind", {
    "constant": Table({"value": Field(float, required=True, doc="L", unit="N m", check=finite_value)}),
    "polynomial": Table({"coefficients": Field(ListOf(float, min_len=1), required=True, doc="c_i: L = sum c_i t^i")}),
    "harmonic": Table({"mean": Field(float, required=True, doc="L0", unit="N m"),
                       "amplitudes": Field(ListOf(float), default=[], doc="A_i", unit="N m"),
                       "frequencies": Field(ListOf(float), default=[], doc="w_i", unit="rad/s"),
                       "phases": Field(ListOf(float), doc="phi_i (default 0)", unit="rad")}),
    "tabulated": Table({"times": Field(ListOf(float, min_len=2), required=True, doc="t_i", unit="s",
                                       check=increasing),
                        "values": Field(ListOf(float, min_len=2), required=True, doc="L_i", unit="N m"),
                        "interpolation": Field(Choice("linear", "cubic"), default="linear", doc="between points")}),
}, doc="the magnitude law L(t)")


WHY_TOLERANCES = ("the paper's frozen values of tau and g are read at the end of long runs through the "
                  "regularised switch of the servo, where an error of 1e-8 shows")


class OrthogonalTorqueKind(Kind):
    name = "orthogonal_torque"
    doc = ("Paper 004: a gyrostat under the servo torque L(t) Q/|Q|, Q = omega x G, one run per magnitude law, "
           "compared with the torque-free gyrostat at tau(t) and, for a nearly spherical body, with the "
           "approximations of section 4.")
    plots = ("omega", "invariants", "tau", "euler_angles", "approximation_errors")
    splits = True

    @property
    def schema(self) -> Table:
        return Table({
            **title_fields(),
            "body": Field(BODY, doc="a gyrostat (or give [nearly_spherical])"),
            "nearly_spherical": Field(Table({
                "J": Field(float, required=True, doc="mean moment", unit="kg m^2", check=positive),
                "Jj": Field(Vector(3), required=True, doc="A_j = J + mu J_j", unit="kg m^2"),
                "mu": Field(float, required=True, doc="small parameter mu"),
                "rotor": Field(Vector(3), default=[0.0, 0.0, 0.0], doc="rotor momentum k", unit="kg m^2/s"),
                "G": Field(float, default=1.0, doc="|G|", unit="kg m^2/s", check=positive),
                "theta0": Field(float, default=1.0, doc="initial nutation of G in body axes", unit="rad"),
                "phi0": Field(float, default=0.0, doc="initial proper rotation", unit="rad"),
                "psi0": Field(float, default=0.0, doc="initial precession", unit="rad"),
            }), doc="a nearly spherical gyrostat A_j = J + mu J_j, its initial state from G and the Euler angles"),
            "initial": Field(Table({
                "omega": Field(Vector(3), doc="angular velocity (with [body])", unit="rad/s", check=all_finite),
                "attitude": Field(Vector(4), doc="quaternion (w, x, y, z); default: inertial z along G(0)",
                                  check=nonzero_quaternion),
            }), default={}, doc="the initial state (with [body])"),
            "runs": Field(ArrayOf(Table({"name": Field(str, required=True, doc="the run's name"),
                                         "law": Field(OneOf(float, LAW), required=True,
                                                      doc="L(t): a number, or a table with its kind")})),
                          required=True, doc="one run per magnitude law"),
            "integration": integration_table(
                rtol=engine_option("rtol", float, "relative tolerance", 1e-10, WHY_TOLERANCES),
                atol=engine_option("atol", float, "absolute tolerance", 1e-12, WHY_TOLERANCES),
                t_span=Field(Vector(2), default=[0.0, 60.0], doc="(t0, t1)", unit="s", check=span_order),
                eta=Field(float, default=ETA, doc="regularisation: delta = eta |omega| |G|", check=positive),
                n_out=engine_option("n_out", int, "number of output times", 1201,
                                    "20 points per second over the default 60 s span"),
                splitting=True, required=False, doc="the runs' integration"),
            "outputs": outputs_field(self.plots, list(self.plots)),
        })

    def spherical(self, doc: dict):
        s = doc.get("nearly_spherical")
        if s is None:
            return None
        return build("nearly_spherical", NearlySpherical, s["J"], s["Jj"], s["mu"], s["rotor"], s["G"],
                      s["theta0"], s["phi0"], s["psi0"])

    def runs(self, doc):
        if ("body" in doc) == ("nearly_spherical" in doc):
            raise SceneError("needs exactly one of [body] or [nearly_spherical]"
                             + ("; both are given" if "body" in doc else "; none is given"))
        spherical = self.spherical(doc)
        if spherical is not None:
            body = spherical.body()
            omega0, q0 = spherical.initial_state()
            if doc["initial"]:
                raise SceneError("[initial] is not used with [nearly_spherical] (the state follows from G and the angles)")
        else:
            body = make_body(doc)
            if "omega" not in doc["initial"]:
                raise SceneError("[initial] is missing required key 'omega' (angular velocity in body axes [rad/s])")
            omega0 = np.asarray(doc["initial"]["omega"], float)
            if "attitude" in doc["initial"]:
                q0 = _core.unit_vector(doc["initial"]["attitude"], "[initial] attitude")
            else:  # inertial z3 along G(0), ψ0 = 0: the Euler angles of (15)-(16)
                q0 = attitude_along_momentum(np.asarray(body.inertia) @ omega0 + np.asarray(body.rotor))
        integ = doc["integration"]
        runs = []
        for i, spec in enumerate(doc["runs"]):
            law = build(f"runs[{i}].law", law_from_spec, spec["law"])
            model = build(f"runs[{i}]", OrthogonalModel, body, law, (), True, integ["eta"])
            runs.append(Run(spec["name"], model, np.concatenate([omega0, q0, [0.0]]), tuple(integ["t_span"]),
                            integration(doc, self, events=g_zero())))
        names = [r.name for r in runs]
        if len(set(names)) != len(names):
            raise SceneError(f"[runs] names must differ; got {names}")
        return (runs, "orthogonal_torque", "full model in t with tau and the attitude quaternion (paper 004); the "
                "torque-free (Zhukovsky-Volterra) solution at tau(t) and, for a nearly spherical body, the "
                "approximations of section 4 for comparison")

    def analyse(self, scene, solutions, report, derived):
        analyse(scene, solutions, report, derived)

    def draw(self, scene, solutions, derived, folder):
        return draw(scene, solutions, derived, folder)

    def why_not_drawn(self, doc, plot):
        if plot == "approximation_errors" and self.spherical(doc) is None:
            return "the zeroth and first approximations are for a nearly spherical body ([nearly_spherical]), not [body]"
        return ""


register(OrthogonalTorqueKind())

