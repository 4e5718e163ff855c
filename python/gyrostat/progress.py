"""Progress for solves, ensembles and sweeps: one rule for what ``progress=`` means.

``progress=None`` (the default): a progress bar (tqdm) on stderr when stderr is a terminal,
nothing otherwise; ``True``: a bar in any case; ``False``: nothing; a callable: called with the
fraction done (0 to 1). The engine calls it from the run at most every 0.1 s, so a run shorter
than that never creates a bar, and progress never changes a result.
"""

from __future__ import annotations

import sys
from collections.abc import Callable


def is_terminal() -> bool:
    """Whether stderr is a terminal (where a bar is shown by default)."""
    try:
        return sys.stderr.isatty()
    except (AttributeError, ValueError):  # replaced or closed stderr
        return False


class Bar:
    """A tqdm bar over ``total`` units, made on the first report (a run that ends before the
    engine's first poll never shows one). Called with the fraction done; ``close()`` ends it."""

    __slots__ = ("total", "unit", "description", "_bar")

    def __init__(self, total: float = 100.0, unit: str = "%", description: str = ""):
        self.total, self.unit, self.description = total, unit, description
        self._bar = None

    def __call__(self, fraction: float) -> None:
        if self._bar is None:
            from tqdm.auto import tqdm

            self._bar = tqdm(total=self.total, unit=self.unit, desc=self.description or None, file=sys.stderr,
                             leave=False, dynamic_ncols=True,
                             bar_format=None if self.unit != "%" else "{l_bar}{bar}| {elapsed}<{remaining}")
        done = min(max(float(fraction), 0.0), 1.0) * self.total
        self._bar.update(done - self._bar.n)

    def close(self) -> None:
        if self._bar is not None:
            self._bar.close()
            self._bar = None


_checked_stream = None  # the stderr last checked, and whether it is a terminal
_terminal = False


def default(total: float = 100.0, unit: str = "%", description: str = "") -> Bar | None:
    """``progress=None``: a bar when stderr is a terminal (checked once per stderr object, so
    that a short solve pays a comparison, not a system call)."""
    global _checked_stream, _terminal
    if sys.stderr is not _checked_stream:
        _checked_stream, _terminal = sys.stderr, is_terminal()
    return Bar(total, unit, description) if _terminal else None


def resolve(progress, *, total: float = 100.0, unit: str = "%", description: str = "") -> Callable | None:
    """The callable a run reports to (or None) for a ``progress=`` argument."""
    if progress is None:
        return default(total, unit, description)
    if progress is False:
        return None
    if progress is True:
        return Bar(total, unit, description)
    if callable(progress):
        return progress
    raise TypeError(f"progress must be None, a bool or a callable of the fraction done, not {type(progress).__name__}")


def close(report) -> None:
    """Ends a bar made by :func:`resolve` (nothing for a user's callable)."""
    if isinstance(report, Bar):
        report.close()
