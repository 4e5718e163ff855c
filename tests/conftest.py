import contextlib
import io
import os
import signal
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).parent))


@pytest.fixture
def ctrl_c():
    """A function that sends Ctrl-C (SIGINT) to this process, as a terminal would, with Python's
    own handler (KeyboardInterrupt) installed for the test and the one before restored after it:
    a suite started in the background or under nohup inherits SIGINT ignored, so that Python
    installs no handler and the signal would be lost (the test then waiting for it). A test that
    uses it also bounds its run (max_steps, a span), so that a lost signal fails it in seconds."""
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        yield lambda: os.kill(os.getpid(), signal.SIGINT)
    finally:
        if previous is not None:  # None: a handler not installed from Python, which cannot be put back
            signal.signal(signal.SIGINT, previous)


def _drawn(ax) -> bool:
    """Whether a panel shows any data: a line with two finite points, a map, a scatter, a band."""
    lines = any(np.isfinite(np.asarray(line.get_xdata(), float)).sum() >= 2 and
                np.isfinite(np.asarray(line.get_ydata(), float)).sum() >= 2 for line in ax.get_lines())
    return lines or bool(ax.collections) or bool(ax.images)


def _hidden_by_legend(ax) -> dict:
    """label → the fraction of the curve's points (in display space) that the legend's box covers."""
    legend = ax.get_legend()
    if legend is None:
        return {}
    box = legend.get_window_extent()
    hidden = {}
    for line in ax.get_lines():
        x, y = np.asarray(line.get_xdata(), float), np.asarray(line.get_ydata(), float)
        ok = np.isfinite(x) & np.isfinite(y)
        if ok.sum() < 2:
            continue
        points = ax.transData.transform(np.column_stack([x[ok], y[ok]]))
        inside = (points[:, 0] >= box.x0) & (points[:, 0] <= box.x1) & (points[:, 1] >= box.y0) & (points[:, 1] <= box.y1)
        hidden[line.get_label()] = float(inside.mean())
    return hidden


@dataclass
class Examples:
    """One run of `gyrostat examples` (every shipped scene with its plots): its exit code, output
    folder and console output, and the facts of every figure it drew, read before it was saved
    ({(scene, plot file name): [axes facts]})."""

    code: int
    folder: Path
    out: str
    figures: dict


@pytest.fixture(scope="session")
def examples(tmp_path_factory) -> Examples:
    """`gyrostat examples` run once for the session (test_scenes_cli checks what it writes,
    test_plots what it draws): the main job, ~20 s, not twice."""
    from gyrostat import figures as drawing
    from gyrostat.cli import main

    recorded = {}
    finish = drawing.finish

    def record(fig, path):
        fig.tight_layout()  # as finish() lays it out: the legends' places are the saved ones
        fig.canvas.draw()
        recorded[(path.parent.name, path.stem)] = [dict(
            drawn=_drawn(ax), hidden=_hidden_by_legend(ax), title=ax.get_title(),
            xlabel=ax.get_xlabel(), ylabel=ax.get_ylabel(), yscale=ax.get_yscale(),
            x_offset=ax.xaxis.get_major_formatter().get_offset(),
            legend_sizes=[text.get_fontsize() for text in ax.get_legend().get_texts()] if ax.get_legend() else [],
            lines={line.get_label(): (line.get_linestyle(), line.get_ydata()) for line in ax.get_lines()},
            shaded=len(ax.collections), ylim=ax.get_ylim()) for ax in fig.axes
            if ax.get_label() != "<colorbar>"]  # a colorbar's label is checked with its map
        return finish(fig, path)

    folder = tmp_path_factory.mktemp("examples")
    patch = pytest.MonkeyPatch()
    patch.setattr(drawing, "finish", record)
    console = io.StringIO()
    try:
        with contextlib.redirect_stdout(console):
            code = main(["examples", "--out", str(folder), "--quiet"])
    finally:
        patch.undo()
    return Examples(code, folder, console.getvalue(), recorded)
