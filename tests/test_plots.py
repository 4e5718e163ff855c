"""Every plot kind of every shipped scene, read back from the figure before it is saved: axis
labels with units, log scales, wrapped angles, both curves where full and averaged coincide,
legends readable at the default size, no hidden offsets on time axes."""

import re

import numpy as np
import pytest

from gyrostat import figures as drawing
from gyrostat import plots
from gyrostat.cli import main


@pytest.fixture(scope="module")
def figures(tmp_path_factory):
    """{(scene, plot file name): [axes facts]} of every figure `gyrostat examples` draws."""
    recorded = {}
    finish = drawing.finish

    def record(fig, path):
        fig.canvas.draw()
        recorded[(path.parent.name, path.stem)] = [dict(
            xlabel=ax.get_xlabel(), ylabel=ax.get_ylabel(), yscale=ax.get_yscale(),
            x_offset=ax.xaxis.get_major_formatter().get_offset(),
            legend_sizes=[text.get_fontsize() for text in ax.get_legend().get_texts()] if ax.get_legend() else [],
            lines={line.get_label(): (line.get_linestyle(), line.get_ydata()) for line in ax.get_lines()},
            shaded=len(ax.collections), ylim=ax.get_ylim()) for ax in fig.axes
            if ax.get_label() != "<colorbar>"]  # a colorbar's label is checked with its map
        return finish(fig, path)

    patch = pytest.MonkeyPatch()
    patch.setattr(drawing, "finish", record)
    try:
        assert main(["examples", "--out", str(tmp_path_factory.mktemp("plots")), "--quiet"]) == 0
    finally:
        patch.undo()
    return recorded


UNIT = re.compile(r"\[[^\]]+\]$")


def test_every_axis_has_labels_with_units_and_readable_legends(figures):
    kinds = {name for _, name in figures}
    assert {"omega", "invariants", "euler_angles", "error", "xy", "slow", "phase", "mass", "sweep"} <= kinds
    assert len(figures) > 40
    for key, axes in figures.items():
        for ax in axes:
            if not ax["lines"]:
                continue
            assert UNIT.search(ax["ylabel"]), (key, ax["ylabel"])
            if ax["xlabel"].startswith("t"):
                assert ax["xlabel"] == "t [s]" and not ax["x_offset"].startswith(("+", "−")), (key, ax["x_offset"])  # a scale, never an offset
            assert all(size >= plots.LEGEND_SIZE >= 9 for size in ax["legend_sizes"]), (key, ax["legend_sizes"])
        assert UNIT.search(axes[-1]["xlabel"]), (key, axes[-1]["xlabel"])


def test_invariants_are_relative_changes_on_a_log_scale(figures):
    axes = figures[("torque_free_triaxial", "invariants")]
    assert [ax["ylabel"] for ax in axes] == ["||G|(t)/|G|(0) − 1| [1]", "|T(t)/T(0) − 1| [1]"]
    for ax in axes:
        assert ax["yscale"] == "log"
        (values,) = [y for _, y in ax["lines"].values()]
        assert 0 < values.max() < 1e-13  # the closed form keeps them to rounding, now visible as such
    integrated = figures[("torque_free_integrated", "invariants")]  # DOP853 drift: decades below 1e-8
    assert all(ax["yscale"] == "log" and ax["ylim"][1] < 1e-6 for ax in integrated)
    damped = figures[("forced_damped", "invariants")]  # changed by the torques: signed, linear
    assert [ax["ylabel"] for ax in damped] == ["|G|(t)/|G|(0) − 1 [1]", "T(t)/T(0) − 1 [1]"]
    assert all(ax["yscale"] == "linear" for ax in damped)


@pytest.mark.parametrize("scene", ["forced_damped", "p004_triaxial"])
def test_euler_angles_are_wrapped_and_singular_times_marked(figures, scene):
    for ax in figures[(scene, "euler_angles")]:
        for _, values in ax["lines"].values():
            finite = np.asarray(values, dtype=float)[np.isfinite(values)]
            if ax["ylabel"].startswith("θ"):
                assert finite.min() >= 0 and finite.max() <= np.pi + 1e-12
            else:
                assert finite.min() >= -np.pi and finite.max() < np.pi, ax["ylabel"]
    psi, theta, phi = figures[("forced_damped", "euler_angles")]
    assert (psi["ylabel"], theta["ylabel"], phi["ylabel"]) == (
        "ψ (precession) [rad]", "θ (nutation) [rad]", "φ (proper rotation) [rad]")
    # θ(0) = 0 there: the singular start is shaded on every panel and named in the legend
    assert all(ax["shaded"] >= 1 for ax in (psi, theta, phi))


@pytest.mark.parametrize("scene", ["p002_valid_regime", "p002_paper_scene"])
def test_full_and_averaged_both_visible_and_one_meaning_per_symbol(figures, scene):
    top, difference = figures[(scene, "xy")]
    styles = {label: style for label, (style, _) in top["lines"].items()}
    assert styles["full model"] == "--" and styles["a² (averaged)"] == "-" and styles["r² (averaged)"] == "-"
    assert difference["ylabel"] == "full − averaged [rad²/s²]" and set(difference["lines"]) == {"a²", "r²"}
    (phase,) = figures[(scene, "phase")]
    assert {label: style for label, (style, _) in phase["lines"].items() if not label.startswith("_")} == {
        "averaged": "-", "full": "--"}
    labels = [text for axes in (figures[(scene, "xy")], [phase]) for ax in axes
              for text in [ax["xlabel"], ax["ylabel"], *ax["lines"]]]
    assert not any(re.search(r"\b[xy]\b", text) for text in labels), labels  # a² and r², never x or y
