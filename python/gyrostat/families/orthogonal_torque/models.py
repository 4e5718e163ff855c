"""The orthogonal torque family's model: :class:`OrthogonalModel`, a gyrostat under the servo
torque L(t) Q/|Q| (regularised near Q = 0), and its torque-free Zhukovsky-Volterra gyrostat."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from gyrostat import _core
from gyrostat.families.orthogonal_torque.laws import ETA, _finite, constant
from gyrostat.families.rigid_body import Model
from gyrostat.modelbase import ModelBase, check_torques, flag


class OrthogonalModel(ModelBase):
    """Gyrostat under the servo torque L(t) Q/|Q| (regularised), plus optional other torques.

    State: (p, q, r, τ) or, with ``attitude=True``, (p, q, r, q_w, q_x, q_y, q_z, τ); ω alone (or
    ω and the quaternion) as y0 starts τ at 0. Outputs: ``angular_momentum_norm`` |G| and ``h`` =
    ω·Jω (exact without other torques), ``g`` = dτ/dt, ``L``, ``Q_norm`` |Q|, ``delta`` δ,
    ``regularised`` (1 where |Q| < δ or Q = 0: the prescribed L was not applied; at Q = 0 the servo applies nothing and g = 1), ``theta_G``, ``phi_G``
    (the angles of G in body axes, paper (15)) and, with attitude, the z-x-z Euler angles.

    ``regularisation``: ``"threshold"`` (default: the paper's torque wherever |Q| ≥ δ = η|ω||G|,
    tapered to L Q/n, n = (|Q|² + δ²)/(2δ), below) or ``"smooth"`` (L Q/√(|Q|² + δ²) everywhere:
    smooth, but the applied L is off by a relative δ²/2|Q|² at every |Q|).

    Parameters
    ----------
    body : gyrostat.Body
        Moments (kg m^2) and rotor momentum k (kg m^2/s).
    law : gyrostat.orthogonal law or float
        The magnitude L(t) of the torque, in N m (:func:`constant`, :func:`polynomial`,
        :func:`harmonic`, :func:`tabulated`; a number is a constant law).
    torques : sequence of torques, optional
        Other torques, added.
    attitude : bool, optional
        Integrate the attitude quaternion too.
    eta : float, optional
        The regularisation's scale η (δ = η|ω||G|; dimensionless).
    regularisation : {"threshold", "smooth"}, optional
        How the torque is tapered near Q = 0 (above).

    Examples
    --------
    The torque is orthogonal to G and ω: |G| and h = ω·Jω stay constant.

    >>> import gyrostat
    >>> from gyrostat import orthogonal
    >>> model = orthogonal.OrthogonalModel(gyrostat.Body([3.0, 2.0, 1.0]), 0.1)
    >>> model.state_names
    ('p', 'q', 'r', 'tau')
    >>> sol = gyrostat.solve(model, [0.1, 0.2, 1.0], (0.0, 10.0))
    >>> bool(abs(sol["angular_momentum_norm"][-1] / sol["angular_momentum_norm"][0] - 1) < 1e-8)
    True

    The examples of its attributes use this ``model``.
    """

    kind = "orthogonal_torque"

    def __init__(self, body: _core.Body, law: _core.MagnitudeLaw | float, torques: Sequence = (),
                 attitude: bool = False, eta: float = ETA, regularisation: str = "threshold"):
        if not isinstance(body, _core.Body):
            raise TypeError(f"body must be a gyrostat.Body, not {type(body).__name__}")
        if not isinstance(law, _core.MagnitudeLaw):
            law = constant(law)
        self.body, self.law = body, law
        self.torques = check_torques(torques)
        self.eta = _finite(eta, "eta")
        if regularisation not in ("threshold", "smooth"):
            raise ValueError(f"regularisation = {regularisation!r}: choose 'threshold' or 'smooth'")
        self.regularisation = regularisation
        self._core = _core.orthogonal_model(body, law, self.torques, flag(attitude, "attitude"), self.eta,
                                            regularisation == "smooth")

    def _arguments(self) -> dict:
        """What it was built from, as its constructor takes it (gyrostat.sensitivity rebuilds from it)."""
        return {"body": self.body, "law": self.law, "torques": self.torques, "attitude": self.attitude,
                "eta": self.eta, "regularisation": self.regularisation}

    @property
    def moments(self) -> np.ndarray:
        """The body's principal moments (A1, A2, A3), in kg m^2.

        Examples
        --------
        >>> model.moments
        array([3., 2., 1.])
        """
        return np.asarray(self.body.moments, float)

    @property
    def rotor(self) -> np.ndarray:
        """The rotor momentum k in body axes, in kg m^2/s.

        Examples
        --------
        >>> model.rotor
        array([0., 0., 0.])
        """
        return np.asarray(self.body.rotor, float)

    def tau_rate(self, t, omega) -> np.ndarray:
        """g = dτ/dt = 1 − L/|Q| at times t for angular velocities omega (dimensionless).

        Parameters
        ----------
        t : float or array_like, shape (n,)
            Times, in s.
        omega : array_like, shape (n, 3)
            Angular velocities in body axes, in rad/s.

        Examples
        --------
        >>> model.tau_rate([0.0], [[0.1, 0.2, 1.0]]).round(6)
        array([0.647327])
        """
        t = np.atleast_1d(np.asarray(t, float))
        return np.asarray(self._core.tau_rate(t, np.atleast_2d(np.asarray(omega, float))))

    def torque_free(self, attitude: bool | None = None) -> Model:
        """The Zhukovsky–Volterra gyrostat of the same body (the full model without torque).

        Parameters
        ----------
        attitude : bool, optional
            With the attitude quaternion (default: as this model).

        Examples
        --------
        >>> model.torque_free()
        Model(Body(A1=3, A2=2, A3=1, k=[0, 0, 0]), torques=[], attitude=False)
        """
        return Model(self.body, attitude=self.attitude if attitude is None else attitude)

    def __repr__(self) -> str:
        return (f"OrthogonalModel({self.body!r}, law={self.law.kind}, attitude={self.attitude}, eta={self.eta}, "
                f"regularisation={self.regularisation!r})")

