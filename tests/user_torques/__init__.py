"""User torques for the tests of gyrostat.CustomTorque: Python callables and a compiled library
(drag.c, built on first use with the C compiler that builds the package), importable by name
from scenes ("user_torques:quadratic_drag")."""

from __future__ import annotations

import ctypes
import os
import subprocess
import sysconfig
import tempfile
from pathlib import Path

import numpy as np
from scipy import LowLevelCallable

HERE = Path(__file__).parent


def quadratic_drag(t, omega):
    """M = -c |omega| omega + (0, 0, a sin t), c = 0.05, a = 0.02: written again in the tests' SciPy run."""
    return -0.05 * np.linalg.norm(omega) * omega + np.array([0.0, 0.0, 0.02 * np.sin(t)])


def quadratic_drag_jacobian(t, omega):
    """dM/domega = -c (|omega| I + omega omega^T / |omega|)."""
    norm = np.linalg.norm(omega)
    return -0.05 * (norm * np.eye(3) + np.outer(omega, omega) / norm)


def drag_factory(c, a):
    """A factory (scenes' `parameters`): the drag above with its own c and a."""
    def drag(t, omega):
        return -c * np.linalg.norm(omega) * omega + np.array([0.0, 0.0, a * np.sin(t)])
    return drag


def inertial_moment(t, omega, quaternion):
    """R(q)^T M_I with M_I = (0.1, -0.2, 0.05): a torque fixed in inertial space, written by hand."""
    w, x, y, z = quaternion / np.linalg.norm(quaternion)
    R = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                  [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                  [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])
    return R.T @ np.array([0.1, -0.2, 0.05])


def failing(t, omega):
    if t > 1.0:
        raise ZeroDivisionError("the user's torque failed at t > 1")
    return np.zeros(3)


def wrong_shape(t, omega):
    return np.zeros(2)


_LIBRARY: ctypes.CDLL | None = None


def library() -> ctypes.CDLL:
    """drag.c compiled once per process into a temporary folder, loaded with ctypes."""
    global _LIBRARY
    if _LIBRARY is None:
        folder = Path(tempfile.mkdtemp(prefix="gyrostat-user-torques-"))
        target = folder / "libdrag.so"
        compiler = os.environ.get("CC") or sysconfig.get_config_var("CC").split()[0] or "cc"
        subprocess.run([compiler, "-O2", "-shared", "-fPIC", "-o", str(target), str(HERE / "drag.c"), "-lm"], check=True)
        _LIBRARY = ctypes.CDLL(str(target))
    return _LIBRARY


_ARGS = [ctypes.c_double, ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_double),
         ctypes.POINTER(ctypes.c_double), ctypes.c_void_p]
# the vectorised signature: int f(int n, const double *t, const double *omega, const double *quaternion,
# double *moment, void *user_data)
_LANE_ARGS = [ctypes.c_int] + [ctypes.POINTER(ctypes.c_double)] * 4 + [ctypes.c_void_p]


def compiled(name: str, user_data=None) -> LowLevelCallable:
    """The C function `name` of drag.c as a scipy.LowLevelCallable (the vectorised signature for
    the *_lanes functions)."""
    function = getattr(library(), name)
    function.restype = ctypes.c_int
    function.argtypes = _LANE_ARGS if name.endswith("_lanes") else _ARGS
    return LowLevelCallable(function, user_data)


def widest_call() -> int:
    """The largest n drag.c's vectorised functions were called with since reset_widest_call()."""
    return library().widest_call()


def reset_widest_call() -> None:
    library().reset_widest_call()


def compiled_drag() -> LowLevelCallable:
    return compiled("quadratic_drag")


def compiled_drag_jacobian() -> LowLevelCallable:
    return compiled("quadratic_drag_jacobian")


def compiled_drag_lanes() -> LowLevelCallable:
    """quadratic_drag, vectorised."""
    return compiled("quadratic_drag_lanes")


def compiled_linear(c: float, vectorised: bool = False) -> LowLevelCallable:
    """M = -c omega (linear_drag, or linear_drag_lanes when `vectorised`), c passed as the
    callable's user_data (a pointer to a double kept alive here)."""
    value = ctypes.c_double(c)
    _KEEP.append(value)
    return compiled("linear_drag_lanes" if vectorised else "linear_drag",
                    ctypes.cast(ctypes.pointer(value), ctypes.c_void_p))



_KEEP: list = []
