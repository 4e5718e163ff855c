"""How a schema's errors read: :class:`SceneError` (one line naming the key, its table and what
was expected, or the nearest valid key), and values and places shown in messages, cut short."""

from __future__ import annotations

import difflib
import json
import re
from collections.abc import Iterable, Mapping
from typing import Any

_LIMIT = 60  # values shown in messages are cut to this many characters


class SceneError(ValueError):
    """A document does not match its schema; the message is a single line naming the key, its
    table and, for a misspelled key, the nearest valid one.

    Examples
    --------
    >>> from gyrostat.scene import Scene, SceneError
    >>> try:
    ...     Scene.from_dict({"body": {"moment": [1.0, 2.0, 3.0]}})
    ... except SceneError as error:
    ...     print(error)
    unknown key 'moment' in [body]; did you mean 'moments'?
    """


SceneError.__module__ = "gyrostat.schema"  # the name users catch and tracebacks show, as before the split


class _Missing:
    def __repr__(self) -> str:
        return "MISSING"


MISSING: Any = _Missing()  # "no default": an optional key without a default stays absent


# ---------------------------------------------------------------------------------------------
# Showing values and places in messages


def _render(value: Any, budget: int) -> str:
    """TOML-like text of a value, built only as far as about ``budget`` characters."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return repr(value[: budget + 1])
    if isinstance(value, (int, float)):
        return repr(value)
    if isinstance(value, (list, tuple)):
        items: list[str] = []
        size = 2
        for item in value:
            if size > budget:
                items.append("...")
                break
            text = _render(item, budget - size)
            items.append(text)
            size += len(text) + 2
        return "[" + ", ".join(items) + "]"
    if isinstance(value, Mapping):
        items = []
        size = 2
        for key, item in value.items():
            if size > budget:
                items.append("...")
                break
            text = f"{_bare(str(key))} = {_render(item, budget - size)}"
            items.append(text)
            size += len(text) + 2
        return "{" + ", ".join(items) + "}"
    return " ".join(str(value).split())


def _show(value: Any) -> str:
    """One line, at most ``_LIMIT`` characters, ending with '...' when cut."""
    text = _render(value, _LIMIT)
    return text if len(text) <= _LIMIT else text[: _LIMIT - 3] + "..."


def _got(value: Any) -> str:
    text = _show(value)
    if isinstance(value, str):
        try:
            float(value)
        except ValueError:
            if value.strip().lower() in ("true", "false"):
                text += " (a string)"
        else:
            text += " (a string)"
    return text


def _one_line(error: Exception) -> str:
    return " ".join(str(error).split()) or type(error).__name__


def _bare(key: str) -> str:
    return key if re.fullmatch(r"[A-Za-z0-9_-]+", key) else json.dumps(key)


def _dotted(parts: tuple) -> str:
    text = ""
    for part in parts:
        text += f"[{part}]" if isinstance(part, int) else ("." if text else "") + _bare(part)
    return text


def _suggest(word: Any, options: Iterable[str]) -> str:
    if not isinstance(word, str):
        return ""
    close = difflib.get_close_matches(word, list(options), n=1, cutoff=0.6)
    return f"; did you mean '{close[0]}'?" if close else ""


def _alternatives(names: Iterable[str], quote: str = "'") -> str:
    names = [f"{quote}{name}{quote}" for name in names]
    return names[0] if len(names) == 1 else ", ".join(names[:-1]) + " or " + names[-1]


class _Path:
    """Where a value sits: the document's name and the keys / indices leading to it."""

    __slots__ = ("root", "parts")

    def __init__(self, root: str, parts: tuple = ()):
        self.root = root
        self.parts = parts

    def __truediv__(self, part: str | int) -> "_Path":
        return _Path(self.root, self.parts + (part,))

    def table(self) -> str:
        """``[integration]``, ``[torques[1]]``; the document's name at the top level."""
        return f"[{_dotted(self.parts)}]" if self.parts else self.root

    def inside(self) -> str:
        return f"in [{_dotted(self.parts)}]" if self.parts else "at the top level"

    def key(self) -> str:
        """``[integration] n_out``, ``[outputs] plots[1]``, ``scene: title``."""
        cut = max((i for i, part in enumerate(self.parts) if isinstance(part, str)), default=0)
        head, tail = self.parts[:cut], self.parts[cut:]
        return f"[{_dotted(head)}] {_dotted(tail)}" if head else f"{self.root}: {_dotted(tail)}"


def _kind_of(value: Any) -> str:
    if isinstance(value, bool):
        return "boolean"
    if isinstance(value, (int, float)):
        return "number"
    if isinstance(value, str):
        return "string"
    if isinstance(value, (list, tuple)):
        return "array"
    if isinstance(value, Mapping):
        return "table"
    return "other"
