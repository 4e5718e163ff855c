"""Draws docs/figures/orbit_frame.png: the orbit frame (LVLH) and Hill's frame on the default orbit,
seen from above the orbit plane (from +N), with the positions computed by gyrostat.Orbit itself.

    .venv/bin/python docs/figures/orbit_frame.py
"""

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import gyrostat  # noqa: E402

HERE = Path(__file__).resolve().parent


def draw(ax, orbit, frame: str) -> None:
    """One panel: the orbit seen from +N (inertial x right, y up), the body at three times and
    the in-plane axes of the frame there; the normal axis marked ⊙ (out of the page) or ⊗ (into it)."""
    u = np.linspace(0, 2 * np.pi, 200)
    ax.plot(np.cos(u), np.sin(u), color="0.6", lw=1)
    ax.plot(0, 0, "o", ms=28, color="tab:blue", alpha=0.5)
    ax.text(0, 0, "planet", ha="center", va="center", fontsize=8)
    period = 2 * np.pi / orbit.rate
    for k, t in enumerate((0.0, 0.17 * period, 0.4 * period)):
        c, R = orbit.position(t), orbit.frame(t)
        ax.plot(c[0], c[1], "ks", ms=7)
        ax.text(1.12 * c[0] - 0.05, 1.12 * c[1] + 0.05 * (k == 0) - 0.12 * (k == 0), "t = 0" if k == 0 else "", fontsize=9)
        if frame == "lvlh":
            axes = {"x_o (along track, roll)": R[:, 0], "z_o (nadir, yaw)": R[:, 2]}
            normal = "⊗ y_o = −N (pitch)"
        else:
            axes = {"x_H (radial)": -R[:, 2], "y_H (along track)": R[:, 0]}
            normal = "⊙ z_H = N"
        for (label, v), color in zip(axes.items(), ("tab:red", "tab:green")):
            ax.annotate("", xy=c[:2] + 0.35 * v[:2], xytext=c[:2], arrowprops=dict(arrowstyle="->", color=color, lw=1.8))
            if k == 0:
                tip = c[:2] + 0.35 * v[:2]
                ax.text(tip[0] + 0.05 * (v[0] > 0.5), tip[1] + 0.08 * (abs(v[1]) > 0.5) - 0.1 * (abs(v[1]) < 0.5), label,
                        color=color, fontsize=8, ha="left" if v[0] > 0.5 else "center", va="center")
        if k == 0:
            ax.text(c[0] + 0.05, c[1] - 0.22, normal, fontsize=8)
    ax.annotate("", xy=(np.cos(5.0), np.sin(5.0)), xytext=(np.cos(4.6), np.sin(4.6)),
                arrowprops=dict(arrowstyle="->", color="k", lw=1.5))
    ax.text(0.1, -1.25, "motion: about N (counter-clockwise seen from +N)", fontsize=8, ha="center")
    ax.set_xlabel("inertial x = e1 (the node)")
    ax.set_ylabel("inertial y = e2 = N × e1")
    ax.set_aspect("equal")
    ax.set_xlim(-1.5, 1.9)
    ax.set_ylim(-1.4, 1.35)
    ax.set_title("orbit frame (LVLH): x along track, y = −N, z nadir" if frame == "lvlh"
                 else "Hill's frame: x radial, y along track, z = N", fontsize=10)


def main() -> None:
    orbit = gyrostat.Orbit(rate=1.0)  # the default orbit: N = z, phase 0
    fig, axes = plt.subplots(1, 2, figsize=(12, 5.4))
    draw(axes[0], orbit, "lvlh")
    draw(axes[1], orbit, "hill")
    fig.suptitle("gyrostat.Orbit(rate=n): c(t) = cos(n t + phase) e1 + sin(n t + phase) e2, seen from +N", fontsize=11)
    fig.tight_layout()
    fig.savefig(HERE / "orbit_frame.png", dpi=110)


if __name__ == "__main__":
    main()
