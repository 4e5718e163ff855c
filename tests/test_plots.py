"""Every plot kind of every shipped scene, read back from the figure before it is saved: axis
labels with units, log scales, wrapped angles, both curves where full and averaged coincide,
legends readable at the default size, no hidden offsets on time axes, no empty panel, no legend
over the curves."""

import re

import numpy as np
import pytest

from gyrostat import figures as drawing
from gyrostat import plots


@pytest.fixture(scope="module")
def figures(examples):
    """{(scene, plot file name): [axes facts]} of every figure `gyrostat examples` draws
    (conftest.py: the session's one run)."""
    assert examples.code == 0
    return examples.figures


UNIT = re.compile(r"\[[^\]]+\]$")


def test_no_panel_is_empty(figures):
    """Every panel of every figure shows data (p001_explicit_moving_mass's invariants had a second
    panel for an energy its model does not conserve, left blank)."""
    empty = [(key, i) for key, axes in figures.items() for i, ax in enumerate(axes) if not ax["drawn"]]
    assert not empty, empty


def test_legends_cover_no_curve(figures):
    """No legend hides more than 1% of any curve's points: measured on main before the legends
    moved beside the panels, 17–100% on 30 panels (p004's Euler angles and τ, p003's validity,
    the omega plots); the 1% leaves room for a legend that touches a curve's last points."""
    covered = {(key, label): round(share, 3) for key, axes in figures.items() for ax in axes
               for label, share in ax["hidden"].items() if share > 0.01}
    assert not covered, covered


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
        (values,) = [y for label, (_, y) in ax["lines"].items() if label.startswith("largest so far")]
        finite = values[np.isfinite(values)]
        # the closed form keeps them to rounding (a few ε), now visible as such; drawn as the
        # largest change so far, a rising staircase, not as noise flickering between 0 and ε
        assert 0 < finite.max() < 1e-13 and np.all(np.diff(finite) >= 0)
        assert ax["ylim"][0] < 2.0 ** -52 < ax["ylim"][1]  # the rounding level is inside the panel
    assert len(figures[("p001_explicit_moving_mass", "invariants")]) == 1  # |K| only: E is dissipated
    integrated = figures[("torque_free_integrated", "invariants")]  # DOP853 drift: decades below 1e-8
    assert all(ax["yscale"] == "log" and ax["ylim"][1] < 1e-6 for ax in integrated)
    damped = figures[("forced_damped", "invariants")]  # changed by the torques: signed, linear
    assert [ax["ylabel"] for ax in damped] == ["|G|(t)/|G|(0) − 1 [1]", "T(t)/T(0) − 1 [1]"]
    assert all(ax["yscale"] == "linear" for ax in damped)
    # each panel says whether the model keeps it (C++: Model::keeps) or its torques change it
    assert [ax["title"] for ax in damped] == ["|G|: a first integral of the free body, changed by the torques",
                                              "T: a first integral of the free body, changed by the torques"]
    assert [ax["title"] for ax in axes] == ["|G|: conserved by the model", "T: conserved by the model"]


@pytest.mark.parametrize("scene", ["forced_damped", "p004_triaxial"])
def test_euler_angles_are_wrapped_and_singular_times_marked(figures, scene):
    for ax in figures[(scene, "euler_angles")]:
        for _, values in ax["lines"].values():
            finite = np.asarray(values, dtype=float)[np.isfinite(values)]
            if "θ [" in ax["ylabel"] or "ϑ" in ax["ylabel"]:  # θ, and p004's nutation ϑ of G: [0, π]
                assert finite.min() >= 0 and finite.max() <= np.pi + 1e-12
            else:
                assert finite.min() >= -np.pi and finite.max() < np.pi, ax["ylabel"]
    psi, theta, phi = figures[("forced_damped", "euler_angles")]
    # the z-x-z angles named as what they are: θ is measured to the start frame's inertial z, not
    # to G (the nutation angle proper is the output nutation_angle)
    assert (psi["ylabel"], theta["ylabel"], phi["ylabel"]) == (
        "precession about inertial z\nψ [rad]", "body z to inertial z\nθ [rad]", "rotation about body z\nφ [rad]")
    # the scene starts body z at 60° from inertial z: θ(0) = π/3, out of the singular band, and
    # θ stays out of it (nothing shaded); on main θ(0) = 0 started inside it
    (values,) = [y for _, y in theta["lines"].values()]
    assert values[0] == pytest.approx(np.pi / 3, abs=1e-12)
    assert np.min(np.abs(np.sin(values))) > drawing.SINGULAR_SIN_THETA and theta["shaded"] == 0


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
