"""The model ladder against always-full, over the papers' scenes at long horizons (issue 15).

Run:  PYTHONPATH=python .venv/bin/python bench/ladder.py        (about a minute)

Each case is one of the papers' scenes with its perturbation scaled by a small ε and its horizon
set to t = 100/ε (paper 003: its own slow-time span τ ∈ [0, 4], t = 4/ε, at ε = 1e-4). For each:
`model = "auto"` solved as `gyrostat run` solves it (the probes included in its time) against the
scene's most complete model over the same span, the same integrator and tolerances; the error is
the largest relative difference of the compared quantities (a, r; G_z, H, r; ω) at the outputs,
next to the ladder's own estimate. Columns: `1st auto`, the first auto solve of the scene (its
probes included); `auto`, the best of 3 further solves, which reuse the choice made for the same
scene (`ladder.choose` keeps it per scene: no probe runs); `full`, the top rung alone; `rung`, the
rung auto chose run alone (the scene with that model: no ladder, no switching); the ratios
auto/full (target ≤ 1.1) and auto/rung (target ≤ 2), for the repeated solves and for the first
(`1st/full`, `1st/rung`: the probes paid). Times are the best of 3 in one run (the first: the
best of 3 first solves, the choice forgotten before each; the machine is shared).
The chart (ladder cost against error, per case) goes to bench/results/ladder.png.
"""

from __future__ import annotations

import copy
import sys
import time
import tomllib
import warnings
from pathlib import Path

import numpy as np

from gyrostat import ladder, runner
from gyrostat.scene import SCENES, Scene

RESULTS = Path(__file__).resolve().parent / "results"


def scene(name: str) -> dict:
    with open(SCENES / f"{name}.toml", "rb") as handle:
        return tomllib.load(handle)


def cases() -> list[tuple[str, dict, str]]:
    """(label, scene document with model = "auto", the top rung's model value)."""
    out = []
    for eps in (1e-2, 1e-3, 1e-4, 1e-5):
        # Paper 000: cavity κ and axial torque M3 both O(ε) (the scene has ε = 0.1)
        doc = scene("p000_A8_C4_M3-0p1")
        doc["torques"][0]["viscosity"] = 1000.0 * 0.1 / eps
        doc["torques"][1]["moment"] = [0.0, 0.0, -0.1 * eps]
        doc["integration"].update(model="auto", accuracy=1e-5, t_span=[0.0, 100.0 / eps], n_out=1001)
        doc["outputs"] = {"plots": ["xy", "slow"]}
        out.append((f"paper 000 (cavity + axial torque), eps = {eps:g}", doc, "full"))
    for eps in (1e-3, 1e-4):
        # Paper 001: linear damping and the quasi-static damper, both O(ε)
        doc = scene("p001_A4_C2_I1-2p5")
        doc["torques"][0]["diagonal"] = [eps, eps, 0.4 * eps]
        doc["torques"][1]["mass"] = 4.0 * eps
        doc["integration"].update(model="auto", accuracy=1e-3, t_span=[0.0, 100.0 / eps], n_out=1001)
        doc["outputs"] = {"plots": ["xy"]}
        out.append((f"paper 001 (damper, damping), eps = {eps:g}", doc, "full"))
    for t1 in (4e3, 4e4):
        # Paper 000's body with a transverse torque the averaging drops: r crosses zero, the run switches
        doc = scene("p000_A8_C4_M3-0p1")
        doc["torques"][0]["viscosity"] = 1e4
        doc["torques"][1]["moment"] = [0.002, 0.0, -0.005 * 4e3 / t1]
        doc["initial"]["omega"] = [1.0, 0.0, 2.0]
        doc["integration"].update(model="auto", accuracy=0.05, t_span=[0.0, t1], n_out=1001)
        doc["outputs"] = {"plots": ["xy", "slow"]}
        out.append((f"paper 000 + transverse torque (switching), t = {t1:g}", doc, "full"))
    # Paper 002's valid regime: near-symmetric body, cavity and a full resistance matrix
    for k in (0.1, 0.01):
        doc = scene("p002_valid_regime")
        doc["torques"][0]["viscosity"] = 6.68e10 / k
        doc["torques"][1]["matrix"] = [[k * v for v in row] for row in doc["torques"][1]["matrix"]]
        eps = k * 0.2322e6 / 2.6e7
        doc["integration"].update(model="auto", accuracy=2e-2, t_span=[0.0, 100.0 / eps], n_out=1001)
        out.append((f"paper 002 (valid regime, near-symmetric), eps = {eps:.2g}", doc, "full"))
    # Paper 003 case 3 over its own slow-time span
    doc = scene("p003_case3_theta0_150deg")
    doc["torque"]["epsilon"] = 1e-4
    doc["integration"].update(model="auto", accuracy=1e-3, n_out=1001)
    doc["outputs"] = {"plots": ["slow", "roots", "validity"]}
    out.append(("paper 003 case 3 (Lagrange top), eps = 1e-4, tau in [0, 4]", doc, "full"))
    # The Explorer-1-like damper of issue 15, explicit model
    doc = {"kind": "moving_mass", "body": {"moments": [10.0, 10.0, 2.0]},
           "damper": {"mass": 0.1, "arm": 1.0, "frequency": 5.0, "damping": 1.0},
           "initial": {"omega": [0.05, 0.0, 2.0]},
           "integration": {"model": "auto", "accuracy": 1e-2, "method": "dop853", "rtol": 1e-8, "atol": 1e-10,
                           "t_span": [0.0, 2e4], "n_out": 1001},
           "outputs": {"plots": ["omega", "invariants"]}}
    out.append(("Explorer-1-like body, explicit moving-mass damper, t = 2e4", doc, "explicit"))
    return out


def solve(doc: dict):
    """The scene solved as `gyrostat run` solves it, without writing files (timed: the choice,
    probes and switches included; reading the scene, the same for both, is not)."""
    scene_ = Scene.from_dict(copy.deepcopy(doc), "bench")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        started = time.perf_counter()
        solutions, report, _ = runner.solve_scene(scene_, progress=False)
        report["solve_seconds"] = time.perf_counter() - started
    return scene_, next(iter(solutions.values())), report


def timed(doc: dict, repeat: int = 3):
    """(best solve time of `repeat`, its scene, solution, report)."""
    runs = [solve(doc) for _ in range(repeat)]
    best = min(runs, key=lambda run: run[2]["solve_seconds"])
    return best[2]["solve_seconds"], best


def main() -> int:
    rows = []
    print(f"{'case':62s} {'auto picks':>10s} {'1st auto':>9s} {'auto [s]':>9s} {'full [s]':>9s} {'rung [s]':>9s} "
          f"{'1st/full':>8s} {'1st/rung':>8s} {'auto/full':>9s} {'auto/rung':>9s} {'error':>8s} {'estimate':>8s} "
          f"{'accuracy':>8s}")
    worst = dict(full=0.0, rung=0.0, first_full=0.0, first_rung=0.0)
    for label, doc, top in cases():
        firsts = []
        for _ in range(3):  # the first auto run probes; the repeats reuse its choice (cached per scene)
            ladder.choosing._CHOICES.clear()
            firsts.append(solve(doc)[2]["solve_seconds"])
        first = min(firsts)
        t_auto, (scene_, sol, report) = timed(doc)
        full_doc = copy.deepcopy(doc)
        full_doc["integration"]["model"] = top
        t_full, (_, reference, _) = timed(full_doc)
        if report["ladder"]["chosen"] == scene_.ladder[-1].name:
            t_rung = t_full
        else:  # the chosen rung run alone: the scene with that model, no ladder, no switching
            rung_doc = copy.deepcopy(doc)
            rung_doc["integration"]["model"] = report["ladder"]["chosen"]
            t_rung = timed(rung_doc)[0]
        rung = scene_.ladder[-1]
        chosen = next(r for r in scene_.ladder if r.name == report["ladder"]["chosen"])
        expected = rung.compare(reference)
        n = min(len(sol), len(reference))
        got = (chosen.compare or rung.compare)(sol)[:n]
        error = float(np.max(np.linalg.norm(got - expected[:n], axis=1)) / np.max(np.linalg.norm(expected, axis=1)))
        estimate = (report["ladder"]["estimate"] or {}).get("value")
        accuracy = report["ladder"]["accuracy"]
        switches = len(report["ladder"]["switches"])
        rows.append(dict(label=label, chosen=chosen.name, t_auto=t_auto, t_full=t_full, error=error,
                         estimate=estimate, accuracy=accuracy, switches=switches))
        ratios = dict(full=t_auto / t_full, rung=t_auto / t_rung, first_full=first / t_full, first_rung=first / t_rung)
        worst = {k: max(v, ratios[k]) for k, v in worst.items()}
        print(f"{label:62s} {chosen.name + ('*' if switches else ''):>10s} {first:9.3g} {t_auto:9.3g} {t_full:9.3g} "
              f"{t_rung:9.3g} {ratios['first_full']:8.3g} {ratios['first_rung']:8.3g} {ratios['full']:9.3g} "
              f"{ratios['rung']:9.3g} {error:8.2g} {estimate if estimate is not None else float('nan'):8.2g} "
              f"{accuracy:8.2g}")
        sys.stdout.flush()
        assert error <= accuracy, f"{label}: error {error:.3g} above the accuracy {accuracy:g}"
    print(f"largest auto/full {worst['full']:.3g} (target: at most 1.1); largest auto/rung {worst['rung']:.3g} "
          f"(target: at most 2); first solves: largest 1st/full {worst['first_full']:.3g}, largest 1st/rung "
          f"{worst['first_rung']:.3g}")
    chart(rows)
    return 0


def chart(rows: list[dict]) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(8, 5))
    floor = 1e-13
    for i, row in enumerate(rows):
        color = plt.cm.tab20(i / max(len(rows) - 1, 1))
        error = max(row["error"], floor)
        ax.annotate("", xy=(row["t_auto"], error), xytext=(row["t_full"], error),
                    arrowprops=dict(arrowstyle="->", color=color, lw=1.5))
        full = row["chosen"] in ("full", "explicit")
        ax.loglog(row["t_auto"], error, "x" if full else "o", color=color, ms=8, mew=2,
                  label=f"{row['label']}: {row['chosen']}, {row['t_full'] / row['t_auto']:.3g}x")
        ax.loglog(row["t_full"], error, "|", color=color, ms=12, mew=2)
    ax.axhline(floor, color="0.6", lw=0.8, ls=":")
    ax.text(0.99, floor * 1.5, "x: the full model chosen (error 0, drawn here)", transform=ax.get_yaxis_transform(),
            ha="right", fontsize=8, color="0.4")
    ax.set_xlabel("time for the whole span [s] (| always-full, o auto; the arrow is the saving)")
    ax.set_ylabel("error of auto against the full model [1] (relative)")
    ax.set_title("The model ladder: auto against always-full at t = 100/eps")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(0, -0.15), ncol=1)
    RESULTS.mkdir(exist_ok=True)
    fig.savefig(RESULTS / "ladder.png", dpi=120, bbox_inches="tight")
    plt.close(fig)
    print(f"wrote {RESULTS / 'ladder.png'}")


if __name__ == "__main__":
    _ = ladder  # the module measured
    sys.exit(main())
