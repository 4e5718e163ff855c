"""Type stubs for the C++ extension gyrostat._core (bindings only translate types)."""

from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

_Vec = Sequence[float] | npt.NDArray[np.float64]

__version__: str

class Body:
    def __init__(self, moments: _Vec, rotor: _Vec = ...) -> None: ...
    @property
    def moments(self) -> npt.NDArray[np.float64]: ...
    @property
    def rotor(self) -> npt.NDArray[np.float64]: ...

class ConstantTorque:
    moment: npt.NDArray[np.float64]
    def __init__(self, moment: _Vec) -> None: ...
    def __call__(self, t: float, omega: _Vec) -> npt.NDArray[np.float64]: ...

class LinearDamping:
    matrix: npt.NDArray[np.float64]
    def __init__(self, matrix: npt.ArrayLike) -> None: ...
    def __call__(self, t: float, omega: _Vec) -> npt.NDArray[np.float64]: ...

class FullModel:
    def __init__(self, body: Body, torques: Sequence[ConstantTorque | LinearDamping], attitude: bool = False) -> None: ...
    @property
    def dim(self) -> int: ...
    @property
    def attitude(self) -> bool: ...
    def rhs(self, t: float, y: _Vec) -> npt.NDArray[np.float64]: ...

class Stats:
    steps: int
    rhs_evals: int
    rejected_steps: int
    jacobian_evals: int
    nonlinear_conv_failures: int
    last_step: float

class Result:
    method: str
    t: npt.NDArray[np.float64]
    y: npt.NDArray[np.float64]
    invariant_names: list[str]
    invariants: npt.NDArray[np.float64]
    stats: Stats
    status: str
    message: str
    success: bool

class TorqueFreeSolution:
    def __init__(self, body: Body, omega0: _Vec, t0: float = 0.0) -> None: ...
    def omega(self, t: Sequence[float]) -> npt.NDArray[np.float64]: ...
    modulus_squared: float
    frequency: float
    period: float
    is_constant: bool

def solve(model: FullModel, y0: _Vec, t0: float, t1: float, method: str, rtol: float, atol: float,
          t_eval: Sequence[float], every_step: bool, max_steps: int, first_step: float, max_step: float) -> Result: ...
def solve_ensemble(models: Sequence[FullModel], y0s: npt.ArrayLike, t0: float, t1: float, method: str, rtol: float,
                   atol: float, t_eval: Sequence[float], every_step: bool, max_steps: int, first_step: float,
                   max_step: float, threads: int) -> list[Result]: ...
def methods() -> list[str]: ...
