"""What code a scene may run: the importable names of its user torques (``type = "custom"``).

A scene is data that people share, but a name such as ``function = "package.module:name"`` runs
code: importing the module runs its top level, and a factory is called with the scene's
``parameters``. So a scene names code only from places its user allowed:

* modules in the scene file's own folder or below it (``function = "user_torques:drag"`` beside
  the scene, ``"lib.torques:drag"`` in its sub-folder ``lib/``), found by their files, and
* modules its user lists (``gyrostat run --allow-import PACKAGE``; ``Scene.from_file(path,
  allow_import=["PACKAGE"])``, ``gyrostat.sweep(..., allow_import=...)``): each listed module and
  every module below it.

Anything else is refused while the scene is validated, before anything is imported or called,
with one line naming the scene, the key, the name and how to allow it. The validated value is a
:class:`CodeName` (a ``str``) that carries its allowance: building the torque
(:meth:`CodeName.load`) checks it again, so a sweep that ships the document to a worker process or
a Dask worker applies the same rule there. Nothing is imported or called until the scene's runs
are built, after the whole scene passed its checks (:class:`gyrostat.scene.Scene`).
"""

from __future__ import annotations

import contextlib
import contextvars
import importlib
import importlib.machinery
import sys
import threading
from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from pathlib import Path

from gyrostat.schema import SceneError, ValueType

__all__ = ["Allowance", "CodeName", "ImportName", "allowing", "module_names", "stand_ins", "standing_in"]


def _is_module_name(text: str) -> bool:
    return bool(text) and all(part.isidentifier() for part in text.split("."))


def module_names(names: Iterable[str] | str | None) -> tuple[str, ...]:
    """The modules a user allows (``allow_import``), checked: dotted Python names; ValueError otherwise."""
    if names is None:
        return ()
    if isinstance(names, str):
        names = [names]
    checked = []
    for name in names:
        if not isinstance(name, str) or not _is_module_name(name):
            raise ValueError(f"allow_import: {name!r} is not a module name such as 'package' or 'package.module'")
        checked.append(name)
    return tuple(checked)


def _split(name: str) -> tuple[str, str]:
    """``"package.module:attribute"`` → (module, attribute); ValueError naming what is wrong."""
    module, colon, attribute = name.partition(":")
    if not colon or not _is_module_name(module) or not _is_module_name(attribute):
        raise ValueError(f"must be an importable name 'module:attribute', got {name!r}")
    return module, attribute


@dataclass(frozen=True)
class Allowance:
    """Where the code a scene names may come from.

    Parameters
    ----------
    scene : str
        The scene's name, for messages.
    folder : str or None
        The scene file's folder (resolved): its modules and those below it are allowed. None for a
        scene given as a document.
    modules : tuple of str
        The modules the user allowed (each with every module below it).
    """

    scene: str = "scene"
    folder: str | None = None
    modules: tuple[str, ...] = ()

    def _file_in_folder(self, module: str) -> Path | None:
        """The file of ``module`` in the scene's folder or below it, if there is one."""
        if self.folder is None:
            return None
        base = Path(self.folder).joinpath(*module.split("."))
        for candidate in [base / "__init__.py"] + [base.with_name(base.name + s) for s in importlib.machinery.all_suffixes()]:
            if candidate.is_file():
                return candidate
        return None

    def source(self, module: str) -> str | None:
        """``"folder"``, ``"allowed"`` or None (refused) for ``module``."""
        if self._file_in_folder(module) is not None:
            return "folder"
        if any(module == allowed or module.startswith(allowed + ".") for allowed in self.modules):
            return "allowed"
        return None

    def refusal(self, key: str, name: str, module: str) -> str:
        """The one-line message that refuses ``name`` at ``key``."""
        where = (f"neither in the scene's folder ({self.folder}) nor allowed" if self.folder
                 else "not allowed (a scene given as a document has no folder)")
        listed = f" (allowed: {', '.join(self.modules)})" if self.modules else ""
        return (f"scene {self.scene!r}: {key} = {name!r} names code in module {module!r}, which is {where}{listed}: "
                f"a scene runs only code its user allows; if you trust it, allow it "
                f"with `--allow-import {module}` (gyrostat run, sweep, check) or allow_import=[{module!r}] "
                f"(Scene.from_file, gyrostat.sweep)")


_ALLOWANCE: contextvars.ContextVar[Allowance] = contextvars.ContextVar("gyrostat_scene_allowance", default=Allowance())
_STAND_INS: contextvars.ContextVar[bool] = contextvars.ContextVar("gyrostat_scene_stand_ins", default=False)
_IMPORTING = threading.Lock()  # sys.path is changed while a scene folder's module is imported


@contextlib.contextmanager
def allowing(allowance: Allowance) -> Iterator[Allowance]:
    """Validates scene documents under ``allowance`` (the names they hold are checked against it)."""
    token = _ALLOWANCE.set(allowance)
    try:
        yield allowance
    finally:
        _ALLOWANCE.reset(token)


@contextlib.contextmanager
def stand_ins() -> Iterator[None]:
    """Builds user torques as stand-ins that import and call nothing (:func:`standing_in`): the
    scene's models are checked before any of its code runs."""
    token = _STAND_INS.set(True)
    try:
        yield
    finally:
        _STAND_INS.reset(token)


def standing_in() -> bool:
    """True inside :func:`stand_ins`."""
    return _STAND_INS.get()


class CodeName(str):
    """An importable name (``"module:attribute"``) a scene's validation allowed, with its allowance."""

    allowance: Allowance
    key: str  # where the scene holds it: "[torques[0]] function"

    def __new__(cls, name: str, allowance: Allowance, key: str) -> "CodeName":
        self = super().__new__(cls, name)
        self.allowance, self.key = allowance, key
        return self

    @property
    def field(self) -> str:
        """The key's own name (``function``), for messages that the table's name prefixes."""
        return self.key.rsplit(" ", 1)[-1]

    def __reduce__(self):
        return CodeName, (str(self), self.allowance, self.key)

    def __deepcopy__(self, memo) -> "CodeName":
        return self

    def load(self):
        """The named object: its module imported (from the scene's folder, or as allowed), after the
        allowance is checked again: SceneError when it is refused, ValueError naming the key (its
        table's name left to the caller) when it is not found."""
        module_name, attribute = _split(self)
        source = self.allowance.source(module_name)
        if source is None:
            raise SceneError(self.allowance.refusal(self.key, str(self), module_name))
        try:
            module = _import_from_folder(module_name, self.allowance) if source == "folder" \
                else importlib.import_module(module_name)
        except ImportError as error:
            raise ValueError(f"{self.field} = {str(self)!r}: cannot import module {module_name!r}: {error}") from None
        target = module
        for part in attribute.split("."):
            if not hasattr(target, part):
                raise ValueError(f"{self.field} = {str(self)!r}: module {module_name!r} has no attribute {attribute!r}")
            target = getattr(target, part)
        return target


def _import_from_folder(module_name: str, allowance: Allowance):
    """``module_name`` imported from the scene's folder (on ``sys.path`` while it is imported, so
    that it may import its neighbours); refused when a module of that name was imported from
    elsewhere before (a scene cannot replace it)."""
    expected = allowance._file_in_folder(module_name)
    with _IMPORTING:
        sys.path.insert(0, allowance.folder)
        try:
            module = importlib.import_module(module_name)
        finally:
            sys.path.remove(allowance.folder)
    found = getattr(module, "__file__", None)
    if found is None or Path(found).resolve() != expected.resolve():
        raise ImportError(f"a module of that name is already imported from {found or 'a built-in'}, not from "
                          f"the scene's folder ({allowance.folder}): rename the scene's module")
    return module


class ImportName(ValueType):
    """A scene key that names code, ``"module:attribute"``: checked against the allowance the
    document is validated under (:func:`allowing`), never imported here."""

    kinds = frozenset({"string"})
    expected, name, plural = "an importable name 'module:attribute'", "importable name", "importable names"

    def convert(self, value, path):
        if not isinstance(value, str):
            self.fail(value, path)
        try:
            module, _ = _split(value)
        except ValueError as error:
            raise SceneError(f"{path.key()} = {value!r}: {error}") from None
        # a name allowed before (a sweep's member, a document a Scene made) keeps its allowance
        allowance = value.allowance if isinstance(value, CodeName) else _ALLOWANCE.get()
        if allowance.source(module) is None:
            raise SceneError(allowance.refusal(path.key(), value, module))
        return CodeName(str(value), allowance, path.key())
