"""Type stubs for the C++ extension gyrostat._core: bodies, torques, models, integrators, ensembles
(the bindings only translate types). Generated from the built module by docs/stubs.py
(pybind11-stubgen); `python docs/stubs.py` regenerates it after a binding changes, and
tests/test_generated.py fails while it is stale.
"""
from __future__ import annotations
import collections.abc
import numpy
import numpy.typing
import typing
__all__: list[str] = ['Body', 'ConstantTorque', 'CustomTorque', 'DipoleFieldTorque', 'Event', 'GravityGradient', 'InertialTorque', 'LagrangeNutation', 'LagrangeUnperturbed', 'LinearDamping', 'MagneticTorque', 'MagnitudeLaw', 'Model', 'Motion', 'MovingMassDamper', 'Options', 'Orbit', 'ResistiveMedium', 'Result', 'Stats', 'TorqueAssumption', 'TorqueFreeSolution', 'ViscousCavity', 'WindowRule', 'averaged_model', 'averaged_triaxial_model', 'companion_step_limit', 'complete_elliptic', 'elliptic_E', 'elliptic_K', 'euler_angles', 'grow', 'gyrostat_model', 'jacobi_sn_cn_dn', 'lagrange_averaged_model', 'lagrange_nutation', 'lagrange_nutation_slopes', 'lagrange_nutation_table', 'lagrange_top_model', 'large', 'load_batches', 'max_output_bytes', 'mean_sn_squared', 'method_descriptions', 'methods', 'moving_mass_model', 'orthogonal_model', 'quaternion_from_euler', 'quaternion_from_matrix', 'rotation_matrix', 'simd_instruction_set', 'simd_lanes', 'small', 'solve', 'solve_ensemble', 'solve_measured', 'solve_sensitivities', 'solve_sensitivities_ensemble', 'summaries', 'taylor_kernel', 'torque_free_model', 'torque_types', 'unit_vector', 'window_estimate', 'window_estimates', 'window_from_differences']
class Body:
    """
    A rigid body or gyrostat: its moments of inertia and the constant angular momentum of its rotors.
    
    Give either its principal moments (the body axes are then its principal axes) or its inertia
    tensor in any body frame. With a tensor, the models run in the principal axes (the rotation is
    ``principal_axes``) and every state, torque parameter given in body axes, rotor and event is
    given and returned in your frame; the named outputs (Euler angles, nutation angle) are those of
    the principal axes, body z being the third principal axis.
    
    Parameters
    ----------
    moments : array_like, shape (3,), optional
        Principal moments of inertia (A1, A2, A3), in kg m^2: finite, positive, and each at most
        the sum of the other two (the triangle inequality of a real body).
    rotor : array_like, shape (3,), optional
        Constant gyrostatic momentum k of rotors spinning at a constant rate relative to the
        carrier, in body axes, in kg m^2/s (N m s). Default: none (a rigid body).
    inertia : array_like, shape (3, 3), optional
        Instead of ``moments``: the inertia tensor in your body frame, in kg m^2 (products of
        inertia off the diagonal, I_xy = -sum m x y). Finite and symmetric; its eigenvalues, the
        principal moments, must satisfy the checks of ``moments``. Its principal axes are ordered
        and signed to be the rotation closest to the identity: a diagonal tensor keeps its axes.
    
    Examples
    --------
    >>> import gyrostat
    >>> gyrostat.Body([2.0, 2.0, 1.0])
    Body(A1=2, A2=2, A3=1, k=[0, 0, 0])
    >>> gyrostat.Body([3.0, 2.0, 1.0], rotor=[0.0, 0.0, 0.1])
    Body(A1=3, A2=2, A3=1, k=[0, 0, 0.1])
    >>> body = gyrostat.Body(inertia=[[2.5, 0.3, 0.0], [0.3, 2.0, 0.0], [0.0, 0.0, 1.0]])
    >>> body.moments.round(6)
    array([2.640512, 1.859488, 1.      ])
    >>> body.principal_axes.round(6)
    array([[ 0.905589, -0.424155,  0.      ],
           [ 0.424155,  0.905589,  0.      ],
           [ 0.      ,  0.      ,  1.      ]])
    """
    def __init__(self, moments: typing.Any = None, rotor: typing.Any = None, inertia: typing.Any = None) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def with_rotor(self, rotor: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"]) -> Body:
        """
        The same body with the rotors' momentum k (kg m^2/s, your body frame).
        
        Its moments and principal axes are this body's, bit for bit (a tensor given again would be
        decomposed again, and its axes could differ in their last bits).
        
        Parameters
        ----------
        rotor : array_like
            k, three numbers in your body frame.
        
        Examples
        --------
        >>> import gyrostat
        >>> gyrostat.Body([3.0, 2.0, 1.0]).with_rotor([0.0, 0.0, 0.5]).rotor
        array([0. , 0. , 0.5])
        """
    @property
    def inertia(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 3]"]:
        """
        The inertia tensor in your body frame, in kg m^2.
        
        Examples
        --------
        >>> import gyrostat
        >>> gyrostat.Body([3.0, 2.0, 1.0]).inertia
        array([[3., 0., 0.],
               [0., 2., 0.],
               [0., 0., 1.]])
        """
    @property
    def moments(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        The principal moments of inertia (A1, A2, A3), in kg m^2.
        
        Examples
        --------
        >>> import gyrostat
        >>> gyrostat.Body([2.0, 2.0, 1.0]).moments
        array([2., 2., 1.])
        """
    @property
    def principal(self) -> bool:
        """
        Whether the body was given in its principal axes (``principal_axes`` is the identity).
        
        Examples
        --------
        >>> import gyrostat
        >>> gyrostat.Body(inertia=[[2.0, 0.1, 0.0], [0.1, 2.0, 0.0], [0.0, 0.0, 1.0]]).principal
        False
        """
    @property
    def principal_axes(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 3]"]:
        """
        R: the principal axes as columns, in your body frame (v = R v_principal, det R = +1).
        
        The identity for a body given by its moments.
        
        Examples
        --------
        >>> import gyrostat
        >>> gyrostat.Body([3.0, 2.0, 1.0]).principal_axes
        array([[1., 0., 0.],
               [0., 1., 0.],
               [0., 0., 1.]])
        """
    @property
    def principal_rotor(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        The rotors' momentum k in principal axes, in kg m^2/s (``principal_axes.T @ rotor``).
        
        Examples
        --------
        >>> import gyrostat
        >>> gyrostat.Body(inertia=[[1.0, 0.0, 0.0], [0.0, 2.0, 0.3], [0.0, 0.3, 1.5]], rotor=[0.0, 0.0, 0.1]).principal_rotor.round(6)
        array([0.      , 0.042416, 0.090559])
        """
    @property
    def rotor(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        The rotors' constant momentum k in your body axes, in kg m^2/s (zero for a rigid body).
        
        Examples
        --------
        >>> import gyrostat
        >>> gyrostat.Body([3.0, 2.0, 1.0], rotor=[0.0, 0.0, 0.1]).rotor
        array([0. , 0. , 0.1])
        """
class Motion:
    """
    The motion a validity check looks at: the largest |omega|, |J omega| and |(C - A) r / A| over the angular velocities given (rows).
    """
    def __init__(self, moments: typing.Any, omegas: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 3]"]) -> None:
        ...
    @property
    def axial_frequency(self) -> float:
        ...
    @property
    def moments(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        ...
    @property
    def momentum(self) -> float:
        ...
    @property
    def speed(self) -> float:
        ...
class TorqueAssumption:
    """
    One assumption of a torque, measured (torque/parameter.hpp).
    """
    @property
    def holds(self) -> bool:
        ...
    @property
    def limit(self) -> float:
        ...
    @property
    def note(self) -> str:
        ...
    @property
    def part(self) -> str:
        ...
    @property
    def statement(self) -> str:
        ...
    @property
    def value(self) -> float:
        ...
class Orbit:
    """
    A circular orbit, given once to a model (``gyrostat.Model(..., orbit=...)``, a scene's ``[orbit]`` table):
    every orbit torque of the model (GravityGradient, DipoleFieldTorque) reads it, and the model reports the
    attitude relative to its orbit frame (docs/orbit_frame.md).
    
    The body is at c(t) = cos u e1 + sin u e2, u = n t + phase, from the planet, with e1 = z x N / |z x N|
    (x when N is along z) and e2 = N x e1: it moves about N. The orbit frame (LVLH) has x along track
    (N x c), y = -N, z nadir (-c).
    
    Parameters
    ----------
    rate : float
        The orbit's mean motion n = sqrt(mu / r^3), in rad/s (finite and positive).
    normal : array_like, shape (3,), optional
        The orbit plane's normal N in inertial axes, any length (default [0, 0, 1]).
    phase : float, optional
        The body's angle u(0) on the orbit from e1 at t = 0, in rad (default 0).
    
    Attributes
    ----------
    description : str
        What it is, in one line.
    parameters : tuple of dict
        Its declaration: one dict per parameter (name, label, shape, unit, description, constraint,
        choice, stored, default), for the scene schema and the docs.
    
    Examples
    --------
    >>> import gyrostat
    >>> orbit = gyrostat.Orbit(rate=0.001)
    >>> orbit
    Orbit(rate=0.001, normal=[0, 0, 1], phase=0)
    >>> orbit.position(0.0), orbit.frame(0.0)[:, 0]
    (array([1., 0., 0.]), array([0., 1., 0.]))
    """
    __hash__: typing.ClassVar[None] = None
    description: typing.ClassVar[str] = "a circular orbit: its rate, its plane's normal and the body's angle on it at t = 0 (docs/orbit_frame.md)"
    parameters: typing.ClassVar[tuple] = ({'name': 'rate', 'label': 'orbit rate n', 'shape': 'scalar', 'unit': 'rad/s', 'description': "the orbit's mean motion n = sqrt(mu / r^3)", 'constraint': 'positive', 'choice': 0, 'stored': True, 'default': None}, {'name': 'normal', 'label': 'orbit normal N', 'shape': 'vector3', 'unit': '1', 'description': "the orbit plane's normal in inertial axes (the sense of motion)", 'constraint': 'finite', 'choice': 0, 'stored': True, 'default': '[0, 0, 1]'}, {'name': 'phase', 'label': 'orbit phase', 'shape': 'scalar', 'unit': 'rad', 'description': "the body's angle u(0) on the orbit at t = 0 from e1 = z x N / |z x N| (x when N is along z)", 'constraint': 'finite', 'choice': 0, 'stored': True, 'default': '0'})
    def __eq__(self, arg0: Orbit) -> bool:
        ...
    def __init__(self, *args, **kwargs) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def frame(self, t: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 3]"]:
        """
        The orbit frame's axes (x along track, y = -N, z nadir) as the columns of a matrix, in inertial axes.
        
        Parameters
        ----------
        t : float
            Time, in s.
        
        Returns
        -------
        numpy.ndarray, shape (3, 3)
            The rotation orbit frame to inertial axes.
        
        Examples
        --------
        >>> import gyrostat
        >>> gyrostat.Orbit(1.0).frame(0.0)
        array([[ 0.,  0., -1.],
               [ 1.,  0.,  0.],
               [ 0., -1.,  0.]])
        """
    def position(self, t: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        The unit vector c(t) from the planet to the body, in inertial axes.
        
        Parameters
        ----------
        t : float
            Time, in s.
        
        Examples
        --------
        >>> import gyrostat
        >>> gyrostat.Orbit(1.0).position(0.5 * 3.141592653589793).round(12)
        array([0., 1., 0.])
        """
    @property
    def normal(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        The unit normal N of the orbit plane, in inertial axes.
        
        Examples
        --------
        >>> import gyrostat
        >>> gyrostat.Orbit(0.001, normal=[0.0, 0.0, 2.0]).normal
        array([0., 0., 1.])
        """
    @property
    def phase(self) -> float:
        """
        The body's angle on the orbit at t = 0 from e1, in rad.
        
        Examples
        --------
        >>> import gyrostat
        >>> gyrostat.Orbit(0.001, phase=0.5).phase
        0.5
        """
    @property
    def rate(self) -> float:
        """
        The orbit rate n, in rad/s.
        
        Examples
        --------
        >>> import gyrostat
        >>> gyrostat.Orbit(0.001).rate
        0.001
        """
class ConstantTorque:
    """
    A constant torque in body axes (scene type ``"constant"``): a torque in body axes acting on the body it is given to.
    
    Parameters
    ----------
    moment : array_like, shape (3,)
        M in body axes, in N m (finite).
    
    Attributes
    ----------
    kind : str
        Its type in a scene's ``[[torques]]`` table (``"constant"``).
    description : str
        What it is, in one line.
    parameters : tuple of dict
        Its declaration: one dict per parameter (name, label, shape, unit, description, constraint, choice, stored, default), for the scene schema and the docs.
    affine_in : tuple of str
        The stored parameters the torque is affine in (sensitivities take their derivative by a one-sided difference, exact to rounding).
    inverse_in : tuple of str
        The stored parameters the torque is inversely proportional to (the same difference, scaled).
    needs_attitude : bool
        Whether it depends on the attitude (then only models with the quaternion take it).
    has_averaged : bool
        Whether it has a contribution to the averaged (a, r) system.
    
    Examples
    --------
    >>> import gyrostat
    >>> torque = gyrostat.ConstantTorque(moment=[0.0, 0.0, 0.5])
    >>> torque
    ConstantTorque(moment=[0, 0, 0.5])
    >>> torque.kind, [p["unit"] for p in torque.parameters]
    ('constant', ['N m'])
    """
    affine_in: typing.ClassVar[tuple] = ('moment')
    description: typing.ClassVar[str] = 'a constant torque in body axes'
    has_averaged: typing.ClassVar[bool] = True
    inverse_in: typing.ClassVar[tuple] = tuple()
    kind: typing.ClassVar[str] = 'constant'
    needs_attitude: typing.ClassVar[bool] = False
    parameters: typing.ClassVar[tuple] = ({'name': 'moment', 'label': 'moment', 'shape': 'vector3', 'unit': 'N m', 'description': 'M in body axes', 'constraint': 'finite', 'choice': 0, 'stored': True, 'default': None})
    def __call__(self, t: typing.Any, omega: typing.Any, moments: typing.Any, quaternion: typing.Any = None) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        The torque in body axes at (t, omega) on a body with these moments.
        
        Parameters
        ----------
        t : float
            Time, in s.
        omega : array_like, shape (3,)
            Angular velocity in body axes, in rad/s.
        moments : array_like, shape (3,)
            Principal moments of inertia (A1, A2, A3), in kg m^2.
        quaternion : array_like, shape (4,), optional
            The attitude (w, x, y, z), body to inertial: not used by this torque.
        
        Returns
        -------
        numpy.ndarray, shape (3,)
            The torque, in N m.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.ConstantTorque(moment=[0.0, 0.0, 0.5])
        >>> torque(0.0, [0.1, 0.0, 1.0], [2.0, 2.0, 1.0])
        array([0. , 0. , 0.5])
        """
    def __init__(self, *args, **kwargs) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def assumptions(self, motion: Motion) -> list[TorqueAssumption]:
        """
        Its validity numbers over a motion (empty when it assumes nothing).
        
        Parameters
        ----------
        motion : gyrostat._core.Motion
            The largest |omega|, |J omega| and axial frequency over the states checked.
        
        Returns
        -------
        list of gyrostat._core.TorqueAssumption
            Each assumption measured: statement, value, limit, holds.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.ConstantTorque(moment=[0.0, 0.0, 0.5])
        >>> motion = gyrostat._core.Motion([2.0, 2.0, 1.0], [[0.1, 0.0, 1.0]])
        >>> len(torque.assumptions(motion))
        0
        """
    def averaged(self, t: typing.Any, a: typing.Any, r: typing.Any, A: typing.Any, C: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[2, 1]"]:
        """
        Its contribution (da/dt, dr/dt) to the system averaged over the symmetric Euler-Poinsot motion.
        
        Parameters
        ----------
        t : float
            Time, in s.
        a : float
            Equatorial angular speed a = sqrt(p^2 + q^2), in rad/s.
        r : float
            Axial angular velocity, in rad/s.
        A : float
            Equatorial moment of inertia, in kg m^2.
        C : float
            Axial moment of inertia, in kg m^2.
        
        Returns
        -------
        numpy.ndarray, shape (2,)
            (da/dt, dr/dt), in rad/s^2.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.ConstantTorque(moment=[0.0, 0.0, 0.5])
        >>> torque.averaged(0.0, 0.1, 1.0, 2.0, 1.0)
        array([0. , 0.5])
        """
    @property
    def moment(self) -> typing.Any:
        """
        M in body axes, in N m.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.ConstantTorque(moment=[0.0, 0.0, 0.5])
        >>> torque.moment
        array([0. , 0. , 0.5])
        """
class LinearDamping:
    """
    M = -D omega (scene type ``"linear_damping"``): a torque in body axes acting on the body it is given to.
    
    Parameters
    ----------
    matrix : array_like, shape (3, 3)
        D (M = -D omega), in N m s (finite; give exactly one of its choice).
    diagonal : array_like, shape (3,)
        The diagonal of D, in N m s (finite; give exactly one of its choice).
    
    Attributes
    ----------
    kind : str
        Its type in a scene's ``[[torques]]`` table (``"linear_damping"``).
    description : str
        What it is, in one line.
    parameters : tuple of dict
        Its declaration: one dict per parameter (name, label, shape, unit, description, constraint, choice, stored, default), for the scene schema and the docs.
    affine_in : tuple of str
        The stored parameters the torque is affine in (sensitivities take their derivative by a one-sided difference, exact to rounding).
    inverse_in : tuple of str
        The stored parameters the torque is inversely proportional to (the same difference, scaled).
    needs_attitude : bool
        Whether it depends on the attitude (then only models with the quaternion take it).
    has_averaged : bool
        Whether it has a contribution to the averaged (a, r) system.
    
    Examples
    --------
    >>> import gyrostat
    >>> torque = gyrostat.LinearDamping(matrix=[[0.5, 0.0, 0.0], [0.0, 0.5, 0.0], [0.0, 0.0, 0.5]])
    >>> torque
    LinearDamping(matrix=[[0.5, 0, 0], [0, 0.5, 0], [0, 0, 0.5]])
    >>> torque.kind, [p["unit"] for p in torque.parameters]
    ('linear_damping', ['N m s', 'N m s'])
    """
    affine_in: typing.ClassVar[tuple] = ('matrix')
    description: typing.ClassVar[str] = 'M = -D omega'
    has_averaged: typing.ClassVar[bool] = True
    inverse_in: typing.ClassVar[tuple] = tuple()
    kind: typing.ClassVar[str] = 'linear_damping'
    needs_attitude: typing.ClassVar[bool] = False
    parameters: typing.ClassVar[tuple] = ({'name': 'matrix', 'label': 'matrix D (column-major)', 'shape': 'matrix3', 'unit': 'N m s', 'description': 'D (M = -D omega)', 'constraint': 'finite', 'choice': 1, 'stored': True, 'default': None}, {'name': 'diagonal', 'label': 'diagonal of D', 'shape': 'vector3', 'unit': 'N m s', 'description': 'the diagonal of D', 'constraint': 'finite', 'choice': 1, 'stored': False, 'default': None})
    def __call__(self, t: typing.Any, omega: typing.Any, moments: typing.Any, quaternion: typing.Any = None) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        The torque in body axes at (t, omega) on a body with these moments.
        
        Parameters
        ----------
        t : float
            Time, in s.
        omega : array_like, shape (3,)
            Angular velocity in body axes, in rad/s.
        moments : array_like, shape (3,)
            Principal moments of inertia (A1, A2, A3), in kg m^2.
        quaternion : array_like, shape (4,), optional
            The attitude (w, x, y, z), body to inertial: not used by this torque.
        
        Returns
        -------
        numpy.ndarray, shape (3,)
            The torque, in N m.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.LinearDamping(matrix=[[0.5, 0.0, 0.0], [0.0, 0.5, 0.0], [0.0, 0.0, 0.5]])
        >>> torque(0.0, [0.1, 0.0, 1.0], [2.0, 2.0, 1.0])
        array([-0.05, -0.  , -0.5 ])
        """
    def __init__(self, *args, **kwargs) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def assumptions(self, motion: Motion) -> list[TorqueAssumption]:
        """
        Its validity numbers over a motion (empty when it assumes nothing).
        
        Parameters
        ----------
        motion : gyrostat._core.Motion
            The largest |omega|, |J omega| and axial frequency over the states checked.
        
        Returns
        -------
        list of gyrostat._core.TorqueAssumption
            Each assumption measured: statement, value, limit, holds.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.LinearDamping(matrix=[[0.5, 0.0, 0.0], [0.0, 0.5, 0.0], [0.0, 0.0, 0.5]])
        >>> motion = gyrostat._core.Motion([2.0, 2.0, 1.0], [[0.1, 0.0, 1.0]])
        >>> len(torque.assumptions(motion))
        0
        """
    def averaged(self, t: typing.Any, a: typing.Any, r: typing.Any, A: typing.Any, C: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[2, 1]"]:
        """
        Its contribution (da/dt, dr/dt) to the system averaged over the symmetric Euler-Poinsot motion.
        
        Parameters
        ----------
        t : float
            Time, in s.
        a : float
            Equatorial angular speed a = sqrt(p^2 + q^2), in rad/s.
        r : float
            Axial angular velocity, in rad/s.
        A : float
            Equatorial moment of inertia, in kg m^2.
        C : float
            Axial moment of inertia, in kg m^2.
        
        Returns
        -------
        numpy.ndarray, shape (2,)
            (da/dt, dr/dt), in rad/s^2.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.LinearDamping(matrix=[[0.5, 0.0, 0.0], [0.0, 0.5, 0.0], [0.0, 0.0, 0.5]])
        >>> torque.averaged(0.0, 0.1, 1.0, 2.0, 1.0)
        array([-0.025, -0.5  ])
        """
    @property
    def matrix(self) -> typing.Any:
        """
        D (M = -D omega), in N m s.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.LinearDamping(matrix=[[0.5, 0.0, 0.0], [0.0, 0.5, 0.0], [0.0, 0.0, 0.5]])
        >>> torque.matrix
        array([[0.5, 0. , 0. ],
               [0. , 0.5, 0. ],
               [0. , 0. , 0.5]])
        """
class ResistiveMedium:
    """
    A resistive medium whose resistance varies with time (scene type ``"resistive_medium"``): a torque in body axes acting on the body it is given to.
    
    Parameters
    ----------
    coefficients : sequence of array_like, shape (3, 3)
        D_0, D_1, ...: D(t) = sum D_k t^k (M = -D(t) omega), in N m s^(k+1) (finite).
    
    Attributes
    ----------
    kind : str
        Its type in a scene's ``[[torques]]`` table (``"resistive_medium"``).
    description : str
        What it is, in one line.
    parameters : tuple of dict
        Its declaration: one dict per parameter (name, label, shape, unit, description, constraint, choice, stored, default), for the scene schema and the docs.
    affine_in : tuple of str
        The stored parameters the torque is affine in (sensitivities take their derivative by a one-sided difference, exact to rounding).
    inverse_in : tuple of str
        The stored parameters the torque is inversely proportional to (the same difference, scaled).
    needs_attitude : bool
        Whether it depends on the attitude (then only models with the quaternion take it).
    has_averaged : bool
        Whether it has a contribution to the averaged (a, r) system.
    
    Examples
    --------
    >>> import gyrostat
    >>> torque = gyrostat.ResistiveMedium(coefficients=[[[0.5, 0.0, 0.0], [0.0, 0.5, 0.0], [0.0, 0.0, 0.5]]])
    >>> torque
    ResistiveMedium(coefficients=[[[0.5, 0, 0], [0, 0.5, 0], [0, 0, 0.5]]])
    >>> torque.kind, [p["unit"] for p in torque.parameters]
    ('resistive_medium', ['N m s^(k+1)'])
    """
    affine_in: typing.ClassVar[tuple] = ('coefficients')
    description: typing.ClassVar[str] = 'a resistive medium whose resistance varies with time'
    has_averaged: typing.ClassVar[bool] = True
    inverse_in: typing.ClassVar[tuple] = tuple()
    kind: typing.ClassVar[str] = 'resistive_medium'
    needs_attitude: typing.ClassVar[bool] = False
    parameters: typing.ClassVar[tuple] = ({'name': 'coefficients', 'label': 'coefficient', 'shape': 'matrices', 'unit': 'N m s^(k+1)', 'description': 'D_0, D_1, ...: D(t) = sum D_k t^k (M = -D(t) omega)', 'constraint': 'finite', 'choice': 0, 'stored': True, 'default': None})
    def __call__(self, t: typing.Any, omega: typing.Any, moments: typing.Any, quaternion: typing.Any = None) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        The torque in body axes at (t, omega) on a body with these moments.
        
        Parameters
        ----------
        t : float
            Time, in s.
        omega : array_like, shape (3,)
            Angular velocity in body axes, in rad/s.
        moments : array_like, shape (3,)
            Principal moments of inertia (A1, A2, A3), in kg m^2.
        quaternion : array_like, shape (4,), optional
            The attitude (w, x, y, z), body to inertial: not used by this torque.
        
        Returns
        -------
        numpy.ndarray, shape (3,)
            The torque, in N m.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.ResistiveMedium(coefficients=[[[0.5, 0.0, 0.0], [0.0, 0.5, 0.0], [0.0, 0.0, 0.5]]])
        >>> torque(0.0, [0.1, 0.0, 1.0], [2.0, 2.0, 1.0])
        array([-0.05, -0.  , -0.5 ])
        """
    def __init__(self, *args, **kwargs) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def assumptions(self, motion: Motion) -> list[TorqueAssumption]:
        """
        Its validity numbers over a motion (empty when it assumes nothing).
        
        Parameters
        ----------
        motion : gyrostat._core.Motion
            The largest |omega|, |J omega| and axial frequency over the states checked.
        
        Returns
        -------
        list of gyrostat._core.TorqueAssumption
            Each assumption measured: statement, value, limit, holds.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.ResistiveMedium(coefficients=[[[0.5, 0.0, 0.0], [0.0, 0.5, 0.0], [0.0, 0.0, 0.5]]])
        >>> motion = gyrostat._core.Motion([2.0, 2.0, 1.0], [[0.1, 0.0, 1.0]])
        >>> len(torque.assumptions(motion))
        0
        """
    def at(self, t: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 3]"]:
        """
        The resistance matrix D(t) = D0 + D1 t + D2 t^2 + ... at time t.
        
        Parameters
        ----------
        t : float
            Time, in s.
        
        Returns
        -------
        numpy.ndarray, shape (3, 3)
            D(t), in N m s (the torque is M = -D(t) omega).
        
        Examples
        --------
        >>> import gyrostat
        >>> medium = gyrostat.ResistiveMedium(coefficients=[[[0.5, 0, 0], [0, 0.5, 0], [0, 0, 0.5]],
        ...                                                 [[0.1, 0, 0], [0, 0.1, 0], [0, 0, 0.1]]])
        >>> medium.at(2.0)
        array([[0.7, 0. , 0. ],
               [0. , 0.7, 0. ],
               [0. , 0. , 0.7]])
        """
    def averaged(self, t: typing.Any, a: typing.Any, r: typing.Any, A: typing.Any, C: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[2, 1]"]:
        """
        Its contribution (da/dt, dr/dt) to the system averaged over the symmetric Euler-Poinsot motion.
        
        Parameters
        ----------
        t : float
            Time, in s.
        a : float
            Equatorial angular speed a = sqrt(p^2 + q^2), in rad/s.
        r : float
            Axial angular velocity, in rad/s.
        A : float
            Equatorial moment of inertia, in kg m^2.
        C : float
            Axial moment of inertia, in kg m^2.
        
        Returns
        -------
        numpy.ndarray, shape (2,)
            (da/dt, dr/dt), in rad/s^2.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.ResistiveMedium(coefficients=[[[0.5, 0.0, 0.0], [0.0, 0.5, 0.0], [0.0, 0.0, 0.5]]])
        >>> torque.averaged(0.0, 0.1, 1.0, 2.0, 1.0)
        array([-0.025, -0.5  ])
        """
    @property
    def coefficients(self) -> typing.Any:
        """
        D_0, D_1, ...: D(t) = sum D_k t^k (M = -D(t) omega), in N m s^(k+1).
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.ResistiveMedium(coefficients=[[[0.5, 0.0, 0.0], [0.0, 0.5, 0.0], [0.0, 0.0, 0.5]]])
        >>> torque.coefficients
        [array([[0.5, 0. , 0. ],
               [0. , 0.5, 0. ],
               [0. , 0. , 0.5]])]
        """
class ViscousCavity:
    """
    A cavity filled with a highly viscous fluid (scene type ``"viscous_cavity"``): a torque in body axes acting on the body it is given to.
    
    Parameters
    ----------
    density : float
        Rho, in kg/m^3 (finite and positive).
    viscosity : float
        Kinematic viscosity nu, in m^2/s (finite and positive).
    p0 : float
        P0 of the cavity tensor P = P0 I, in m^5 (finite and positive; give exactly one of its choice).
    radius : float
        Radius of a spherical cavity, in m (finite and positive; give exactly one of its choice).
    
    Attributes
    ----------
    kind : str
        Its type in a scene's ``[[torques]]`` table (``"viscous_cavity"``).
    description : str
        What it is, in one line.
    parameters : tuple of dict
        Its declaration: one dict per parameter (name, label, shape, unit, description, constraint, choice, stored, default), for the scene schema and the docs.
    affine_in : tuple of str
        The stored parameters the torque is affine in (sensitivities take their derivative by a one-sided difference, exact to rounding).
    inverse_in : tuple of str
        The stored parameters the torque is inversely proportional to (the same difference, scaled).
    needs_attitude : bool
        Whether it depends on the attitude (then only models with the quaternion take it).
    has_averaged : bool
        Whether it has a contribution to the averaged (a, r) system.
    
    Examples
    --------
    >>> import gyrostat
    >>> torque = gyrostat.ViscousCavity(density=0.5, viscosity=0.5, p0=0.5)
    >>> torque
    ViscousCavity(density=0.5, viscosity=0.5, p0=0.5)
    >>> torque.kind, [p["unit"] for p in torque.parameters]
    ('viscous_cavity', ['kg/m^3', 'm^2/s', 'm^5', 'm'])
    """
    affine_in: typing.ClassVar[tuple] = ('density', 'p0')
    description: typing.ClassVar[str] = 'a cavity filled with a highly viscous fluid'
    has_averaged: typing.ClassVar[bool] = True
    inverse_in: typing.ClassVar[tuple] = ('viscosity')
    kind: typing.ClassVar[str] = 'viscous_cavity'
    needs_attitude: typing.ClassVar[bool] = False
    parameters: typing.ClassVar[tuple] = ({'name': 'density', 'label': 'density ρ', 'shape': 'scalar', 'unit': 'kg/m^3', 'description': 'rho', 'constraint': 'positive', 'choice': 0, 'stored': True, 'default': None}, {'name': 'viscosity', 'label': 'kinematic viscosity ν', 'shape': 'scalar', 'unit': 'm^2/s', 'description': 'kinematic viscosity nu', 'constraint': 'positive', 'choice': 0, 'stored': True, 'default': None}, {'name': 'p0', 'label': 'cavity coefficient P0', 'shape': 'scalar', 'unit': 'm^5', 'description': 'P0 of the cavity tensor P = P0 I', 'constraint': 'positive', 'choice': 1, 'stored': True, 'default': None}, {'name': 'radius', 'label': 'cavity radius b', 'shape': 'scalar', 'unit': 'm', 'description': 'radius of a spherical cavity', 'constraint': 'positive', 'choice': 1, 'stored': False, 'default': None})
    @staticmethod
    def sphere(density: typing.Any, viscosity: typing.Any, radius: typing.Any) -> ViscousCavity:
        """
        A spherical cavity of this radius (P0 from the sphere's formula).
        
        Parameters
        ----------
        density : float
            Fluid density rho, in kg/m^3.
        viscosity : float
            Kinematic viscosity nu, in m^2/s.
        radius : float
            Cavity radius b, in m.
        
        Examples
        --------
        >>> import gyrostat
        >>> gyrostat.ViscousCavity.sphere(density=1000.0, viscosity=1e-3, radius=0.1)
        ViscousCavity(density=1000, viscosity=0.001, p0=4.787188805470163e-09)
        """
    def __call__(self, t: typing.Any, omega: typing.Any, moments: typing.Any, quaternion: typing.Any = None) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        The torque in body axes at (t, omega) on a body with these moments.
        
        Parameters
        ----------
        t : float
            Time, in s.
        omega : array_like, shape (3,)
            Angular velocity in body axes, in rad/s.
        moments : array_like, shape (3,)
            Principal moments of inertia (A1, A2, A3), in kg m^2.
        quaternion : array_like, shape (4,), optional
            The attitude (w, x, y, z), body to inertial: not used by this torque.
        
        Returns
        -------
        numpy.ndarray, shape (3,)
            The torque, in N m.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.ViscousCavity(density=0.5, viscosity=0.5, p0=0.5)
        >>> torque(0.0, [0.1, 0.0, 1.0], [2.0, 2.0, 1.0])
        array([ 0.0125,  0.    , -0.0025])
        """
    def __init__(self, *args, **kwargs) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def assumptions(self, motion: Motion) -> list[TorqueAssumption]:
        """
        Its validity numbers over a motion (empty when it assumes nothing).
        
        Parameters
        ----------
        motion : gyrostat._core.Motion
            The largest |omega|, |J omega| and axial frequency over the states checked.
        
        Returns
        -------
        list of gyrostat._core.TorqueAssumption
            Each assumption measured: statement, value, limit, holds.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.ViscousCavity(density=0.5, viscosity=0.5, p0=0.5)
        >>> motion = gyrostat._core.Motion([2.0, 2.0, 1.0], [[0.1, 0.0, 1.0]])
        >>> len(torque.assumptions(motion))
        2
        """
    def averaged(self, t: typing.Any, a: typing.Any, r: typing.Any, A: typing.Any, C: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[2, 1]"]:
        """
        Its contribution (da/dt, dr/dt) to the system averaged over the symmetric Euler-Poinsot motion.
        
        Parameters
        ----------
        t : float
            Time, in s.
        a : float
            Equatorial angular speed a = sqrt(p^2 + q^2), in rad/s.
        r : float
            Axial angular velocity, in rad/s.
        A : float
            Equatorial moment of inertia, in kg m^2.
        C : float
            Axial moment of inertia, in kg m^2.
        
        Returns
        -------
        numpy.ndarray, shape (2,)
            (da/dt, dr/dt), in rad/s^2.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.ViscousCavity(density=0.5, viscosity=0.5, p0=0.5)
        >>> torque.averaged(0.0, 0.1, 1.0, 2.0, 1.0)
        array([ 0.00625, -0.0025 ])
        """
    @property
    def density(self) -> typing.Any:
        """
        Rho, in kg/m^3.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.ViscousCavity(density=0.5, viscosity=0.5, p0=0.5)
        >>> torque.density
        0.5
        """
    @property
    def equivalent_radius(self) -> float:
        """
        The radius of the sphere with this P0, in m.
        
        Examples
        --------
        >>> import gyrostat
        >>> gyrostat.ViscousCavity.sphere(density=1000.0, viscosity=1e-3, radius=0.1).equivalent_radius
        0.10000000000000002
        """
    @property
    def kappa(self) -> float:
        """
        kappa = rho P0 / nu, in kg s: the strength of the cavity torque.
        
        Examples
        --------
        >>> import gyrostat
        >>> gyrostat.ViscousCavity.sphere(density=1000.0, viscosity=1e-3, radius=0.1).kappa
        0.004787188805470163
        """
    @property
    def p0(self) -> typing.Any:
        """
        P0 of the cavity tensor P = P0 I, in m^5.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.ViscousCavity(density=0.5, viscosity=0.5, p0=0.5)
        >>> torque.p0
        0.5
        """
    @property
    def viscosity(self) -> typing.Any:
        """
        Kinematic viscosity nu, in m^2/s.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.ViscousCavity(density=0.5, viscosity=0.5, p0=0.5)
        >>> torque.viscosity
        0.5
        """
class MovingMassDamper:
    """
    Chernousko's quasi-static moving-mass damper (scene type ``"moving_mass_damper"``): a torque in body axes acting on the body it is given to.
    
    Parameters
    ----------
    mass : float
        Mass m, in kg (finite and positive).
    arm : float
        Distance rho of the mass on the z axis, in m (finite and non-negative).
    frequency : float
        Omega = sqrt(c/m), in rad/s (finite and positive).
    damping : float
        Lambda = delta/m, in 1/s (finite and non-negative).
    
    Attributes
    ----------
    kind : str
        Its type in a scene's ``[[torques]]`` table (``"moving_mass_damper"``).
    description : str
        What it is, in one line.
    parameters : tuple of dict
        Its declaration: one dict per parameter (name, label, shape, unit, description, constraint, choice, stored, default), for the scene schema and the docs.
    affine_in : tuple of str
        The stored parameters the torque is affine in (sensitivities take their derivative by a one-sided difference, exact to rounding).
    inverse_in : tuple of str
        The stored parameters the torque is inversely proportional to (the same difference, scaled).
    needs_attitude : bool
        Whether it depends on the attitude (then only models with the quaternion take it).
    has_averaged : bool
        Whether it has a contribution to the averaged (a, r) system.
    
    Examples
    --------
    >>> import gyrostat
    >>> torque = gyrostat.MovingMassDamper(mass=0.5, arm=0.5, frequency=0.5, damping=0.5)
    >>> torque
    MovingMassDamper(mass=0.5, arm=0.5, frequency=0.5, damping=0.5)
    >>> torque.kind, [p["unit"] for p in torque.parameters]
    ('moving_mass_damper', ['kg', 'm', 'rad/s', '1/s'])
    """
    affine_in: typing.ClassVar[tuple] = tuple()
    description: typing.ClassVar[str] = "Chernousko's quasi-static moving-mass damper"
    has_averaged: typing.ClassVar[bool] = True
    inverse_in: typing.ClassVar[tuple] = tuple()
    kind: typing.ClassVar[str] = 'moving_mass_damper'
    needs_attitude: typing.ClassVar[bool] = False
    parameters: typing.ClassVar[tuple] = ({'name': 'mass', 'label': 'mass m', 'shape': 'scalar', 'unit': 'kg', 'description': 'mass m', 'constraint': 'positive', 'choice': 0, 'stored': True, 'default': None}, {'name': 'arm', 'label': 'arm rho', 'shape': 'scalar', 'unit': 'm', 'description': 'distance rho of the mass on the z axis', 'constraint': 'non_negative', 'choice': 0, 'stored': True, 'default': None}, {'name': 'frequency', 'label': 'frequency Omega', 'shape': 'scalar', 'unit': 'rad/s', 'description': 'Omega = sqrt(c/m)', 'constraint': 'positive', 'choice': 0, 'stored': True, 'default': None}, {'name': 'damping', 'label': 'damping lambda', 'shape': 'scalar', 'unit': '1/s', 'description': 'lambda = delta/m', 'constraint': 'non_negative', 'choice': 0, 'stored': True, 'default': None})
    def S(self, A: typing.Any, C: typing.Any) -> float:
        """
        S of paper 001 eq. (3) for a symmetric body (A, A, C).
        
        Parameters
        ----------
        A : float
            Equatorial moment of inertia, in kg m^2.
        C : float
            Axial moment of inertia, in kg m^2.
        
        Examples
        --------
        >>> import gyrostat
        >>> gyrostat.MovingMassDamper(mass=0.5, arm=0.5, frequency=0.5, damping=0.5).S(2.0, 1.0)
        0.0625
        """
    def __call__(self, t: typing.Any, omega: typing.Any, moments: typing.Any, quaternion: typing.Any = None) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        The torque in body axes at (t, omega) on a body with these moments.
        
        Parameters
        ----------
        t : float
            Time, in s.
        omega : array_like, shape (3,)
            Angular velocity in body axes, in rad/s.
        moments : array_like, shape (3,)
            Principal moments of inertia (A1, A2, A3), in kg m^2.
        quaternion : array_like, shape (4,), optional
            The attitude (w, x, y, z), body to inertial: not used by this torque.
        
        Returns
        -------
        numpy.ndarray, shape (3,)
            The torque, in N m.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.MovingMassDamper(mass=0.5, arm=0.5, frequency=0.5, damping=0.5)
        >>> torque(0.0, [0.1, 0.0, 1.0], [2.0, 2.0, 1.0])
        array([ 0.00625, -0.0065 , -0.00125])
        """
    def __init__(self, *args, **kwargs) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def assumptions(self, motion: Motion) -> list[TorqueAssumption]:
        """
        Its validity numbers over a motion (empty when it assumes nothing).
        
        Parameters
        ----------
        motion : gyrostat._core.Motion
            The largest |omega|, |J omega| and axial frequency over the states checked.
        
        Returns
        -------
        list of gyrostat._core.TorqueAssumption
            Each assumption measured: statement, value, limit, holds.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.MovingMassDamper(mass=0.5, arm=0.5, frequency=0.5, damping=0.5)
        >>> motion = gyrostat._core.Motion([2.0, 2.0, 1.0], [[0.1, 0.0, 1.0]])
        >>> len(torque.assumptions(motion))
        4
        """
    def averaged(self, t: typing.Any, a: typing.Any, r: typing.Any, A: typing.Any, C: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[2, 1]"]:
        """
        Its contribution (da/dt, dr/dt) to the system averaged over the symmetric Euler-Poinsot motion.
        
        Parameters
        ----------
        t : float
            Time, in s.
        a : float
            Equatorial angular speed a = sqrt(p^2 + q^2), in rad/s.
        r : float
            Axial angular velocity, in rad/s.
        A : float
            Equatorial moment of inertia, in kg m^2.
        C : float
            Axial moment of inertia, in kg m^2.
        
        Returns
        -------
        numpy.ndarray, shape (2,)
            (da/dt, dr/dt), in rad/s^2.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.MovingMassDamper(mass=0.5, arm=0.5, frequency=0.5, damping=0.5)
        >>> torque.averaged(0.0, 0.1, 1.0, 2.0, 1.0)
        array([ 0.003125, -0.00125 ])
        """
    @property
    def arm(self) -> typing.Any:
        """
        Distance rho of the mass on the z axis, in m.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.MovingMassDamper(mass=0.5, arm=0.5, frequency=0.5, damping=0.5)
        >>> torque.arm
        0.5
        """
    @property
    def damping(self) -> typing.Any:
        """
        Lambda = delta/m, in 1/s.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.MovingMassDamper(mass=0.5, arm=0.5, frequency=0.5, damping=0.5)
        >>> torque.damping
        0.5
        """
    @property
    def frequency(self) -> typing.Any:
        """
        Omega = sqrt(c/m), in rad/s.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.MovingMassDamper(mass=0.5, arm=0.5, frequency=0.5, damping=0.5)
        >>> torque.frequency
        0.5
        """
    @property
    def mass(self) -> typing.Any:
        """
        Mass m, in kg.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.MovingMassDamper(mass=0.5, arm=0.5, frequency=0.5, damping=0.5)
        >>> torque.mass
        0.5
        """
class GravityGradient:
    """
    The gravity-gradient torque on a circular orbit (needs the attitude) (scene type ``"gravity_gradient"``): a torque in body axes acting on the body it is given to.
    
    Parameters
    ----------
    orbit_rate : float
        The orbit's mean motion n = sqrt(mu / r^3); leave out the three orbit parameters to use the model's orbit, in rad/s (finite and positive; optional, default the model's orbit).
    orbit_normal : array_like, shape (3,)
        The orbit plane's normal in inertial axes (needs orbit_rate), in 1 (finite; optional, default [0, 0, 1]).
    phase : float
        The body's angle on the orbit at t = 0 from e1 = z x N / |z x N| (needs orbit_rate; docs/orbit_frame.md), in rad (finite; optional, default 0).
    
    Attributes
    ----------
    kind : str
        Its type in a scene's ``[[torques]]`` table (``"gravity_gradient"``).
    description : str
        What it is, in one line.
    parameters : tuple of dict
        Its declaration: one dict per parameter (name, label, shape, unit, description, constraint, choice, stored, default), for the scene schema and the docs.
    affine_in : tuple of str
        The stored parameters the torque is affine in (sensitivities take their derivative by a one-sided difference, exact to rounding).
    inverse_in : tuple of str
        The stored parameters the torque is inversely proportional to (the same difference, scaled).
    needs_attitude : bool
        Whether it depends on the attitude (then only models with the quaternion take it).
    has_averaged : bool
        Whether it has a contribution to the averaged (a, r) system.
    
    Examples
    --------
    >>> import gyrostat
    >>> torque = gyrostat.GravityGradient(orbit_rate=0.5, orbit_normal=[0.0, 0.0, 0.5], phase=0.5)
    >>> torque
    GravityGradient(orbit_rate=0.5, orbit_normal=[0, 0, 1], phase=0.5)
    >>> torque.kind, [p["unit"] for p in torque.parameters]
    ('gravity_gradient', ['rad/s', '1', 'rad'])
    """
    affine_in: typing.ClassVar[tuple] = tuple()
    description: typing.ClassVar[str] = 'the gravity-gradient torque on a circular orbit (needs the attitude)'
    has_averaged: typing.ClassVar[bool] = False
    inverse_in: typing.ClassVar[tuple] = tuple()
    kind: typing.ClassVar[str] = 'gravity_gradient'
    needs_attitude: typing.ClassVar[bool] = True
    parameters: typing.ClassVar[tuple] = ({'name': 'orbit_rate', 'label': 'orbit rate n', 'shape': 'scalar', 'unit': 'rad/s', 'description': "the orbit's mean motion n = sqrt(mu / r^3); leave out the three orbit parameters to use the model's orbit", 'constraint': 'positive', 'choice': 0, 'stored': True, 'default': "the model's orbit"}, {'name': 'orbit_normal', 'label': 'orbit normal N', 'shape': 'vector3', 'unit': '1', 'description': "the orbit plane's normal in inertial axes (needs orbit_rate)", 'constraint': 'finite', 'choice': 0, 'stored': True, 'default': '[0, 0, 1]'}, {'name': 'phase', 'label': 'orbit phase', 'shape': 'scalar', 'unit': 'rad', 'description': "the body's angle on the orbit at t = 0 from e1 = z x N / |z x N| (needs orbit_rate; docs/orbit_frame.md)", 'constraint': 'finite', 'choice': 0, 'stored': True, 'default': '0'})
    def __call__(self, t: typing.Any, omega: typing.Any, moments: typing.Any, quaternion: typing.Any = None) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        The torque in body axes at (t, omega) on a body with these moments and this attitude.
        
        Parameters
        ----------
        t : float
            Time, in s.
        omega : array_like, shape (3,)
            Angular velocity in body axes, in rad/s.
        moments : array_like, shape (3,)
            Principal moments of inertia (A1, A2, A3), in kg m^2.
        quaternion : array_like, shape (4,), optional
            The attitude (w, x, y, z), body to inertial: required (this torque depends on it).
        
        Returns
        -------
        numpy.ndarray, shape (3,)
            The torque, in N m.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.GravityGradient(orbit_rate=0.5, orbit_normal=[0.0, 0.0, 0.5], phase=0.5)
        >>> torque(0.0, [0.1, 0.0, 1.0], [2.0, 2.0, 1.0], quaternion=[1.0, 0.0, 0.0, 0.0])
        array([0., 0., 0.])
        """
    def __init__(self, *args, **kwargs) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def assumptions(self, motion: Motion) -> list[TorqueAssumption]:
        """
        Its validity numbers over a motion (empty when it assumes nothing).
        
        Parameters
        ----------
        motion : gyrostat._core.Motion
            The largest |omega|, |J omega| and axial frequency over the states checked.
        
        Returns
        -------
        list of gyrostat._core.TorqueAssumption
            Each assumption measured: statement, value, limit, holds.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.GravityGradient(orbit_rate=0.5, orbit_normal=[0.0, 0.0, 0.5], phase=0.5)
        >>> motion = gyrostat._core.Motion([2.0, 2.0, 1.0], [[0.1, 0.0, 1.0]])
        >>> len(torque.assumptions(motion))
        0
        """
    def precession_rate(self, moments: typing.Any, omega: typing.Any, quaternion: typing.Any, orbit: typing.Any = None) -> float:
        """
        The rate at which G precesses about the orbit normal, averaged over the orbit and the free motion.
        
        For a symmetric body (A, A, C): -3 n^2 (C - A)(3 cos^2 nutation - 1) cos i / (4 |G|), with the
        nutation angle between body z and G and i the angle between G and the orbit normal.
        
        Parameters
        ----------
        moments : array_like, shape (3,)
            Principal moments (A, A, C), in kg m^2.
        omega : array_like, shape (3,)
            Angular velocity in body axes, in rad/s.
        quaternion : array_like, shape (4,)
            The attitude (w, x, y, z), body to inertial.
        orbit : gyrostat.Orbit, optional
            The orbit (the model's); default: the torque's own (orbit_rate, orbit_normal, phase).
        
        Returns
        -------
        float
            The precession rate, in rad/s (about the orbit normal).
        
        Examples
        --------
        >>> import gyrostat as g
        >>> g.GravityGradient(0.01).precession_rate([1.0, 1.0, 2.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0, 0.0])
        -7.5e-05
        >>> g.GravityGradient().precession_rate([1.0, 1.0, 2.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0, 0.0], orbit=g.Orbit(0.01))
        -7.5e-05
        """
    @property
    def orbit_normal(self) -> typing.Any:
        """
        The orbit plane's normal in inertial axes (needs orbit_rate), in 1.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.GravityGradient(orbit_rate=0.5, orbit_normal=[0.0, 0.0, 0.5], phase=0.5)
        >>> torque.orbit_normal
        array([0., 0., 1.])
        """
    @property
    def orbit_rate(self) -> typing.Any:
        """
        The orbit's mean motion n = sqrt(mu / r^3); leave out the three orbit parameters to use the model's orbit, in rad/s.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.GravityGradient(orbit_rate=0.5, orbit_normal=[0.0, 0.0, 0.5], phase=0.5)
        >>> torque.orbit_rate
        0.5
        """
    @property
    def phase(self) -> typing.Any:
        """
        The body's angle on the orbit at t = 0 from e1 = z x N / |z x N| (needs orbit_rate; docs/orbit_frame.md), in rad.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.GravityGradient(orbit_rate=0.5, orbit_normal=[0.0, 0.0, 0.5], phase=0.5)
        >>> torque.phase
        0.5
        """
class MagneticTorque:
    """
    A magnetic dipole fixed in the body in a field constant in inertial space (needs the attitude) (scene type ``"magnetic"``): a torque in body axes acting on the body it is given to.
    
    Parameters
    ----------
    dipole : array_like, shape (3,)
        The body's magnetic dipole moment m in body axes, in A m^2 (finite).
    field : array_like, shape (3,)
        The magnetic field B in inertial axes, in T (finite).
    
    Attributes
    ----------
    kind : str
        Its type in a scene's ``[[torques]]`` table (``"magnetic"``).
    description : str
        What it is, in one line.
    parameters : tuple of dict
        Its declaration: one dict per parameter (name, label, shape, unit, description, constraint, choice, stored, default), for the scene schema and the docs.
    affine_in : tuple of str
        The stored parameters the torque is affine in (sensitivities take their derivative by a one-sided difference, exact to rounding).
    inverse_in : tuple of str
        The stored parameters the torque is inversely proportional to (the same difference, scaled).
    needs_attitude : bool
        Whether it depends on the attitude (then only models with the quaternion take it).
    has_averaged : bool
        Whether it has a contribution to the averaged (a, r) system.
    
    Examples
    --------
    >>> import gyrostat
    >>> torque = gyrostat.MagneticTorque(dipole=[0.0, 0.0, 0.5], field=[0.0, 0.0, 0.5])
    >>> torque
    MagneticTorque(dipole=[0, 0, 0.5], field=[0, 0, 0.5])
    >>> torque.kind, [p["unit"] for p in torque.parameters]
    ('magnetic', ['A m^2', 'T'])
    """
    affine_in: typing.ClassVar[tuple] = ('dipole', 'field')
    description: typing.ClassVar[str] = 'a magnetic dipole fixed in the body in a field constant in inertial space (needs the attitude)'
    has_averaged: typing.ClassVar[bool] = False
    inverse_in: typing.ClassVar[tuple] = tuple()
    kind: typing.ClassVar[str] = 'magnetic'
    needs_attitude: typing.ClassVar[bool] = True
    parameters: typing.ClassVar[tuple] = ({'name': 'dipole', 'label': 'dipole m', 'shape': 'vector3', 'unit': 'A m^2', 'description': "the body's magnetic dipole moment m in body axes", 'constraint': 'finite', 'choice': 0, 'stored': True, 'default': None}, {'name': 'field', 'label': 'field B', 'shape': 'vector3', 'unit': 'T', 'description': 'the magnetic field B in inertial axes', 'constraint': 'finite', 'choice': 0, 'stored': True, 'default': None})
    def __call__(self, t: typing.Any, omega: typing.Any, moments: typing.Any, quaternion: typing.Any = None) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        The torque in body axes at (t, omega) on a body with these moments and this attitude.
        
        Parameters
        ----------
        t : float
            Time, in s.
        omega : array_like, shape (3,)
            Angular velocity in body axes, in rad/s.
        moments : array_like, shape (3,)
            Principal moments of inertia (A1, A2, A3), in kg m^2.
        quaternion : array_like, shape (4,), optional
            The attitude (w, x, y, z), body to inertial: required (this torque depends on it).
        
        Returns
        -------
        numpy.ndarray, shape (3,)
            The torque, in N m.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.MagneticTorque(dipole=[0.0, 0.0, 0.5], field=[0.0, 0.0, 0.5])
        >>> torque(0.0, [0.1, 0.0, 1.0], [2.0, 2.0, 1.0], quaternion=[1.0, 0.0, 0.0, 0.0])
        array([0., 0., 0.])
        """
    def __init__(self, *args, **kwargs) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def assumptions(self, motion: Motion) -> list[TorqueAssumption]:
        """
        Its validity numbers over a motion (empty when it assumes nothing).
        
        Parameters
        ----------
        motion : gyrostat._core.Motion
            The largest |omega|, |J omega| and axial frequency over the states checked.
        
        Returns
        -------
        list of gyrostat._core.TorqueAssumption
            Each assumption measured: statement, value, limit, holds.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.MagneticTorque(dipole=[0.0, 0.0, 0.5], field=[0.0, 0.0, 0.5])
        >>> motion = gyrostat._core.Motion([2.0, 2.0, 1.0], [[0.1, 0.0, 1.0]])
        >>> len(torque.assumptions(motion))
        0
        """
    @property
    def dipole(self) -> typing.Any:
        """
        The body's magnetic dipole moment m in body axes, in A m^2.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.MagneticTorque(dipole=[0.0, 0.0, 0.5], field=[0.0, 0.0, 0.5])
        >>> torque.dipole
        array([0. , 0. , 0.5])
        """
    @property
    def field(self) -> typing.Any:
        """
        The magnetic field B in inertial axes, in T.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.MagneticTorque(dipole=[0.0, 0.0, 0.5], field=[0.0, 0.0, 0.5])
        >>> torque.field
        array([0. , 0. , 0.5])
        """
class DipoleFieldTorque:
    """
    A magnetic dipole fixed in the body on a circular orbit in a planet's tilted dipole field (needs the attitude) (scene type ``"dipole_field"``): a torque in body axes acting on the body it is given to.
    
    Parameters
    ----------
    dipole : array_like, shape (3,)
        The body's magnetic dipole moment m in body axes, in A m^2 (finite).
    field_strength : float
        B0 = mu0 |m_planet| / (4 pi r^3), the field at the magnetic equator at the orbit's radius, in T (finite and positive).
    orbit_rate : float
        The orbit's mean motion n = sqrt(mu / r^3); leave out the three orbit parameters to use the model's orbit, in rad/s (finite and positive; optional, default the model's orbit).
    dipole_axis : array_like, shape (3,)
        The direction of the planet's dipole moment in inertial axes (tilted from -z for a tilted dipole), in 1 (finite; optional, default [0, 0, -1]).
    orbit_normal : array_like, shape (3,)
        The orbit plane's normal in inertial axes (needs orbit_rate), in 1 (finite; optional, default [0, 0, 1]).
    phase : float
        The body's angle on the orbit at t = 0 from e1 = z x N / |z x N| (needs orbit_rate; docs/orbit_frame.md), in rad (finite; optional, default 0).
    
    Attributes
    ----------
    kind : str
        Its type in a scene's ``[[torques]]`` table (``"dipole_field"``).
    description : str
        What it is, in one line.
    parameters : tuple of dict
        Its declaration: one dict per parameter (name, label, shape, unit, description, constraint, choice, stored, default), for the scene schema and the docs.
    affine_in : tuple of str
        The stored parameters the torque is affine in (sensitivities take their derivative by a one-sided difference, exact to rounding).
    inverse_in : tuple of str
        The stored parameters the torque is inversely proportional to (the same difference, scaled).
    needs_attitude : bool
        Whether it depends on the attitude (then only models with the quaternion take it).
    has_averaged : bool
        Whether it has a contribution to the averaged (a, r) system.
    
    Examples
    --------
    >>> import gyrostat
    >>> torque = gyrostat.DipoleFieldTorque(dipole=[0.0, 0.0, 0.5], field_strength=0.5, orbit_rate=0.5, dipole_axis=[0.0, 0.0, 0.5], orbit_normal=[0.0, 0.0, 0.5], phase=0.5)
    >>> torque
    DipoleFieldTorque(dipole=[0, 0, 0.5], field_strength=0.5, orbit_rate=0.5, dipole_axis=[0, 0, 1], orbit_normal=[0, 0, 1], phase=0.5)
    >>> torque.kind, [p["unit"] for p in torque.parameters]
    ('dipole_field', ['A m^2', 'T', 'rad/s', '1', '1', 'rad'])
    """
    affine_in: typing.ClassVar[tuple] = ('dipole', 'field_strength')
    description: typing.ClassVar[str] = "a magnetic dipole fixed in the body on a circular orbit in a planet's tilted dipole field (needs the attitude)"
    has_averaged: typing.ClassVar[bool] = False
    inverse_in: typing.ClassVar[tuple] = tuple()
    kind: typing.ClassVar[str] = 'dipole_field'
    needs_attitude: typing.ClassVar[bool] = True
    parameters: typing.ClassVar[tuple] = ({'name': 'dipole', 'label': 'dipole m', 'shape': 'vector3', 'unit': 'A m^2', 'description': "the body's magnetic dipole moment m in body axes", 'constraint': 'finite', 'choice': 0, 'stored': True, 'default': None}, {'name': 'field_strength', 'label': 'field strength B0', 'shape': 'scalar', 'unit': 'T', 'description': "B0 = mu0 |m_planet| / (4 pi r^3), the field at the magnetic equator at the orbit's radius", 'constraint': 'positive', 'choice': 0, 'stored': True, 'default': None}, {'name': 'orbit_rate', 'label': 'orbit rate n', 'shape': 'scalar', 'unit': 'rad/s', 'description': "the orbit's mean motion n = sqrt(mu / r^3); leave out the three orbit parameters to use the model's orbit", 'constraint': 'positive', 'choice': 0, 'stored': True, 'default': "the model's orbit"}, {'name': 'dipole_axis', 'label': 'dipole axis d', 'shape': 'vector3', 'unit': '1', 'description': "the direction of the planet's dipole moment in inertial axes (tilted from -z for a tilted dipole)", 'constraint': 'finite', 'choice': 0, 'stored': True, 'default': '[0, 0, -1]'}, {'name': 'orbit_normal', 'label': 'orbit normal N', 'shape': 'vector3', 'unit': '1', 'description': "the orbit plane's normal in inertial axes (needs orbit_rate)", 'constraint': 'finite', 'choice': 0, 'stored': True, 'default': '[0, 0, 1]'}, {'name': 'phase', 'label': 'orbit phase', 'shape': 'scalar', 'unit': 'rad', 'description': "the body's angle on the orbit at t = 0 from e1 = z x N / |z x N| (needs orbit_rate; docs/orbit_frame.md)", 'constraint': 'finite', 'choice': 0, 'stored': True, 'default': '0'})
    def __call__(self, t: typing.Any, omega: typing.Any, moments: typing.Any, quaternion: typing.Any = None) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        The torque in body axes at (t, omega) on a body with these moments and this attitude.
        
        Parameters
        ----------
        t : float
            Time, in s.
        omega : array_like, shape (3,)
            Angular velocity in body axes, in rad/s.
        moments : array_like, shape (3,)
            Principal moments of inertia (A1, A2, A3), in kg m^2.
        quaternion : array_like, shape (4,), optional
            The attitude (w, x, y, z), body to inertial: required (this torque depends on it).
        
        Returns
        -------
        numpy.ndarray, shape (3,)
            The torque, in N m.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.DipoleFieldTorque(dipole=[0.0, 0.0, 0.5], field_strength=0.5, orbit_rate=0.5, dipole_axis=[0.0, 0.0, 0.5], orbit_normal=[0.0, 0.0, 0.5], phase=0.5)
        >>> torque(0.0, [0.1, 0.0, 1.0], [2.0, 2.0, 1.0], quaternion=[1.0, 0.0, 0.0, 0.0])
        array([-0.,  0.,  0.])
        """
    def __init__(self, *args, **kwargs) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def assumptions(self, motion: Motion) -> list[TorqueAssumption]:
        """
        Its validity numbers over a motion (empty when it assumes nothing).
        
        Parameters
        ----------
        motion : gyrostat._core.Motion
            The largest |omega|, |J omega| and axial frequency over the states checked.
        
        Returns
        -------
        list of gyrostat._core.TorqueAssumption
            Each assumption measured: statement, value, limit, holds.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.DipoleFieldTorque(dipole=[0.0, 0.0, 0.5], field_strength=0.5, orbit_rate=0.5, dipole_axis=[0.0, 0.0, 0.5], orbit_normal=[0.0, 0.0, 0.5], phase=0.5)
        >>> motion = gyrostat._core.Motion([2.0, 2.0, 1.0], [[0.1, 0.0, 1.0]])
        >>> len(torque.assumptions(motion))
        0
        """
    def field(self, t: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        The planet's field at the body, in inertial axes.
        
        Parameters
        ----------
        t : float
            Time, in s.
        
        Returns
        -------
        numpy.ndarray, shape (3,)
            B(t) = B0 [3 (d . c) c - d], in T.
        
        Examples
        --------
        >>> import gyrostat as g
        >>> g.DipoleFieldTorque(dipole=[0.0, 0.0, 1.0], field_strength=2e-5, orbit_rate=0.001).field(0.0)
        array([0.e+00, 0.e+00, 2.e-05])
        """
    @property
    def dipole(self) -> typing.Any:
        """
        The body's magnetic dipole moment m in body axes, in A m^2.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.DipoleFieldTorque(dipole=[0.0, 0.0, 0.5], field_strength=0.5, orbit_rate=0.5, dipole_axis=[0.0, 0.0, 0.5], orbit_normal=[0.0, 0.0, 0.5], phase=0.5)
        >>> torque.dipole
        array([0. , 0. , 0.5])
        """
    @property
    def dipole_axis(self) -> typing.Any:
        """
        The direction of the planet's dipole moment in inertial axes (tilted from -z for a tilted dipole), in 1.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.DipoleFieldTorque(dipole=[0.0, 0.0, 0.5], field_strength=0.5, orbit_rate=0.5, dipole_axis=[0.0, 0.0, 0.5], orbit_normal=[0.0, 0.0, 0.5], phase=0.5)
        >>> torque.dipole_axis
        array([0., 0., 1.])
        """
    @property
    def field_strength(self) -> typing.Any:
        """
        B0 = mu0 |m_planet| / (4 pi r^3), the field at the magnetic equator at the orbit's radius, in T.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.DipoleFieldTorque(dipole=[0.0, 0.0, 0.5], field_strength=0.5, orbit_rate=0.5, dipole_axis=[0.0, 0.0, 0.5], orbit_normal=[0.0, 0.0, 0.5], phase=0.5)
        >>> torque.field_strength
        0.5
        """
    @property
    def orbit_normal(self) -> typing.Any:
        """
        The orbit plane's normal in inertial axes (needs orbit_rate), in 1.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.DipoleFieldTorque(dipole=[0.0, 0.0, 0.5], field_strength=0.5, orbit_rate=0.5, dipole_axis=[0.0, 0.0, 0.5], orbit_normal=[0.0, 0.0, 0.5], phase=0.5)
        >>> torque.orbit_normal
        array([0., 0., 1.])
        """
    @property
    def orbit_rate(self) -> typing.Any:
        """
        The orbit's mean motion n = sqrt(mu / r^3); leave out the three orbit parameters to use the model's orbit, in rad/s.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.DipoleFieldTorque(dipole=[0.0, 0.0, 0.5], field_strength=0.5, orbit_rate=0.5, dipole_axis=[0.0, 0.0, 0.5], orbit_normal=[0.0, 0.0, 0.5], phase=0.5)
        >>> torque.orbit_rate
        0.5
        """
    @property
    def phase(self) -> typing.Any:
        """
        The body's angle on the orbit at t = 0 from e1 = z x N / |z x N| (needs orbit_rate; docs/orbit_frame.md), in rad.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.DipoleFieldTorque(dipole=[0.0, 0.0, 0.5], field_strength=0.5, orbit_rate=0.5, dipole_axis=[0.0, 0.0, 0.5], orbit_normal=[0.0, 0.0, 0.5], phase=0.5)
        >>> torque.phase
        0.5
        """
class InertialTorque:
    """
    A constant torque fixed in inertial space (needs the attitude) (scene type ``"inertial"``): a torque in body axes acting on the body it is given to.
    
    Parameters
    ----------
    moment : array_like, shape (3,)
        M_I in inertial axes, in N m (finite).
    
    Attributes
    ----------
    kind : str
        Its type in a scene's ``[[torques]]`` table (``"inertial"``).
    description : str
        What it is, in one line.
    parameters : tuple of dict
        Its declaration: one dict per parameter (name, label, shape, unit, description, constraint, choice, stored, default), for the scene schema and the docs.
    affine_in : tuple of str
        The stored parameters the torque is affine in (sensitivities take their derivative by a one-sided difference, exact to rounding).
    inverse_in : tuple of str
        The stored parameters the torque is inversely proportional to (the same difference, scaled).
    needs_attitude : bool
        Whether it depends on the attitude (then only models with the quaternion take it).
    has_averaged : bool
        Whether it has a contribution to the averaged (a, r) system.
    
    Examples
    --------
    >>> import gyrostat
    >>> torque = gyrostat.InertialTorque(moment=[0.0, 0.0, 0.5])
    >>> torque
    InertialTorque(moment=[0, 0, 0.5])
    >>> torque.kind, [p["unit"] for p in torque.parameters]
    ('inertial', ['N m'])
    """
    affine_in: typing.ClassVar[tuple] = ('moment')
    description: typing.ClassVar[str] = 'a constant torque fixed in inertial space (needs the attitude)'
    has_averaged: typing.ClassVar[bool] = False
    inverse_in: typing.ClassVar[tuple] = tuple()
    kind: typing.ClassVar[str] = 'inertial'
    needs_attitude: typing.ClassVar[bool] = True
    parameters: typing.ClassVar[tuple] = ({'name': 'moment', 'label': 'moment', 'shape': 'vector3', 'unit': 'N m', 'description': 'M_I in inertial axes', 'constraint': 'finite', 'choice': 0, 'stored': True, 'default': None})
    def __call__(self, t: typing.Any, omega: typing.Any, moments: typing.Any, quaternion: typing.Any = None) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        The torque in body axes at (t, omega) on a body with these moments and this attitude.
        
        Parameters
        ----------
        t : float
            Time, in s.
        omega : array_like, shape (3,)
            Angular velocity in body axes, in rad/s.
        moments : array_like, shape (3,)
            Principal moments of inertia (A1, A2, A3), in kg m^2.
        quaternion : array_like, shape (4,), optional
            The attitude (w, x, y, z), body to inertial: required (this torque depends on it).
        
        Returns
        -------
        numpy.ndarray, shape (3,)
            The torque, in N m.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.InertialTorque(moment=[0.0, 0.0, 0.5])
        >>> torque(0.0, [0.1, 0.0, 1.0], [2.0, 2.0, 1.0], quaternion=[1.0, 0.0, 0.0, 0.0])
        array([0. , 0. , 0.5])
        """
    def __init__(self, *args, **kwargs) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def assumptions(self, motion: Motion) -> list[TorqueAssumption]:
        """
        Its validity numbers over a motion (empty when it assumes nothing).
        
        Parameters
        ----------
        motion : gyrostat._core.Motion
            The largest |omega|, |J omega| and axial frequency over the states checked.
        
        Returns
        -------
        list of gyrostat._core.TorqueAssumption
            Each assumption measured: statement, value, limit, holds.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.InertialTorque(moment=[0.0, 0.0, 0.5])
        >>> motion = gyrostat._core.Motion([2.0, 2.0, 1.0], [[0.1, 0.0, 1.0]])
        >>> len(torque.assumptions(motion))
        0
        """
    @property
    def moment(self) -> typing.Any:
        """
        M_I in inertial axes, in N m.
        
        Examples
        --------
        >>> import gyrostat
        >>> torque = gyrostat.InertialTorque(moment=[0.0, 0.0, 0.5])
        >>> torque.moment
        array([0. , 0. , 0.5])
        """
class CustomTorque:
    """
    A torque the user writes, in body axes (scene type ``"custom"``).
    
    M = f(t, omega) or, with ``attitude=True``, f(t, omega, quaternion): omega in rad/s (body axes),
    the quaternion (w, x, y, z) body to inertial, M in N m (body axes).
    
    Parameters
    ----------
    function : callable or scipy.LowLevelCallable
        A Python callable (each call holds the GIL and costs the library 0.2-0.6 us when it returns a
        float64 NumPy array or a tuple or list of floats, plus the function's own time:
        bench/custom_torque.py; other returns, e.g. ints or a float32 array, take a general
        conversion, about 0.6 us more; an ensemble of such members runs on one thread, since more
        would only pass the GIL back and forth; its exception reaches the caller as raised, but
        Ctrl-C in it ends the run with status "interrupted", keeping what was computed), or a
        ``scipy.LowLevelCallable`` (from ``numba.cfunc``, ctypes or cffi) of one of the C signatures::
    
            int f(double t, const double *omega, const double *quaternion, double *moment, void *user_data)
            int f(int n, const double *t, const double *omega, const double *quaternion, double *moment,
                  void *user_data)
    
        called from C++ without the GIL on every thread (quaternion is NULL without the attitude;
        it returns 0, and a non-zero code stops the run with an error naming the torque). The
        second, vectorised, takes n members at once as structure of arrays: t[l] the time of member
        l, omega[i*n + l] its omega_i (3n numbers), quaternion[i*n + l] its q_i, i = w, x, y, z (4n
        numbers, or NULL), moment[i*n + l] its M_i (3n numbers to write); member l's M must depend on
        member l's numbers only. The SIMD batches of ``solve_ensemble`` (DOP853) call it once per
        stage for their lanes (n = ``gyrostat.simd_lanes``), every other path with n = 1; a scalar
        function keeps its members out of the batches (one at a time), and so does a body given by
        its inertia tensor (the batches do not rotate the user's frame). In numba::
    
            @numba.cfunc(numba.types.intc(numba.types.intc, *[numba.types.CPointer(numba.types.double)] * 4,
                                          numba.types.voidptr))
            def drag(n, t, omega, quaternion, moment, user_data):
                w, m = numba.carray(omega, (3, n)), numba.carray(moment, (3, n))
                for i in range(3):
                    for l in range(n):
                        m[i, l] = -0.1 * w[i, l]
                return 0
    
            g.CustomTorque(scipy.LowLevelCallable(drag.ctypes))
    jacobian : callable or scipy.LowLevelCallable, optional
        dM/domega, of the same kind and arguments as ``function`` (a 3x3 array; compiled: 9 numbers
        row-major, the scalar signature, also beside a vectorised function). None: central difference
        quotients (6 calls) for the implicit methods.
    attitude : bool
        The function takes the quaternion; only models with the attitude take the torque.
    name : str, optional
        The name in messages and the repr (default: the function's name).
    parameters : dict of str, optional
        The torque's own parameters (numbers, or any value a factory takes). Then ``function`` (and ``jacobian``) are factories: called once
        here as ``function(**parameters)``, they return the torque function (a Python callable or a
        ``scipy.LowLevelCallable``) as above. Sensitivities (``gyrostat.solve(..., sensitivities=
        ["CustomTorque.c"])``) move a number among them by calling the factory again, and take dM/dc
        as a central difference quotient of the two torques made.
    
    Examples
    --------
    >>> import numpy as np, gyrostat as g
    >>> drag = g.CustomTorque(lambda t, omega: -0.1 * omega, name="drag")
    >>> drag(0.0, [1.0, 0.0, 0.0], [1.0, 2.0, 3.0])
    array([-0.1, -0. , -0. ])
    >>> def drag_with(c):
    ...     return lambda t, omega: -c * omega
    >>> g.CustomTorque(drag_with, parameters={"c": 0.2}, name="drag")(0.0, [1.0, 0.0, 0.0], [1.0, 2.0, 3.0])
    array([-0.2, -0. , -0. ])
    """
    affine_in: typing.ClassVar[tuple] = tuple()
    description: typing.ClassVar[str] = 'a torque the user writes: M = f(t, omega) or f(t, omega, quaternion) in body axes, a Python callable or a compiled function'
    has_averaged: typing.ClassVar[bool] = False
    inverse_in: typing.ClassVar[tuple] = tuple()
    kind: typing.ClassVar[str] = 'custom'
    needs_attitude: typing.ClassVar[bool] = False
    parameters: typing.ClassVar[tuple] = tuple()
    def __call__(self, t: typing.Any, omega: typing.Any, moments: typing.Any, quaternion: typing.Any = None) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        The user's function at (t, omega[, quaternion]): the torque in body axes.
        
        Parameters
        ----------
        t : float
            Time, in s.
        omega : array_like, shape (3,)
            Angular velocity in body axes, in rad/s.
        moments : array_like, shape (3,)
            Principal moments of inertia, in kg m^2 (not passed to the function).
        quaternion : array_like, shape (4,), optional
            The attitude (w, x, y, z), body to inertial: required when the torque takes it.
        
        Returns
        -------
        numpy.ndarray, shape (3,)
            The torque, in N m.
        
        Examples
        --------
        >>> import gyrostat as g
        >>> g.CustomTorque(lambda t, omega: -0.5 * omega)(0.0, [0.0, 0.0, 2.0], [1.0, 1.0, 1.0])
        array([-0., -0., -1.])
        """
    def __init__(self, function: typing.Any, jacobian: typing.Any = None, *, attitude: bool = False, name: typing.Any = None, parameters: typing.Any = None) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def assumptions(self, motion: typing.Any) -> list:
        """
        A user's torque states no assumption.
        
        Parameters
        ----------
        motion : gyrostat._core.Motion
            The motion checked (not used).
        
        Returns
        -------
        list
            Empty.
        
        Examples
        --------
        >>> import gyrostat as g
        >>> g.CustomTorque(lambda t, omega: -omega).assumptions(g._core.Motion([1.0, 2.0, 3.0], [[0.0, 0.0, 1.0]]))
        []
        """
    @property
    def arguments(self) -> dict:
        """
        The parameters the factories were called with (a dict; empty without parameters).
        
        Examples
        --------
        >>> import gyrostat as g
        >>> g.CustomTorque(lambda c: (lambda t, omega: -c * omega), parameters={"c": 0.2}).arguments
        {'c': 0.2}
        """
    @property
    def attitude(self) -> bool:
        """
        Whether the function takes the quaternion (bool).
        
        Examples
        --------
        >>> import gyrostat as g
        >>> g.CustomTorque(lambda t, omega, q: -omega, attitude=True).attitude
        True
        """
    @property
    def factory(self) -> typing.Any:
        """
        The factory that made the function from ``arguments``, or None (a torque
        given without parameters).
        
        Examples
        --------
        >>> import gyrostat as g
        >>> def drag_with(c):
        ...     return lambda t, omega: -c * omega
        >>> g.CustomTorque(drag_with, parameters={"c": 0.2}).factory is drag_with
        True
        """
    @property
    def function(self) -> typing.Any:
        """
        The torque function the core calls (made by the factory when the torque has
        parameters).
        
        Examples
        --------
        >>> import gyrostat as g
        >>> g.CustomTorque(lambda t, omega: -0.3 * omega).function(0.0, 1.0)
        -0.3
        """
    @property
    def jacobian(self) -> typing.Any:
        """
        The Jacobian dM/domega the core calls, or None (difference quotients).
        
        Examples
        --------
        >>> import gyrostat as g
        >>> g.CustomTorque(lambda t, omega: -omega).jacobian is None
        True
        """
    @property
    def jacobian_factory(self) -> typing.Any:
        """
        The factory that made the Jacobian from ``arguments``, or None.
        
        Examples
        --------
        >>> import gyrostat as g
        >>> g.CustomTorque(lambda c: (lambda t, omega: -c * omega), parameters={"c": 0.2}).jacobian_factory is None
        True
        """
    @property
    def name(self) -> str:
        """
        The name used in messages and the repr (str).
        
        Examples
        --------
        >>> import gyrostat as g
        >>> g.CustomTorque(lambda t, omega: -omega, name="drag").name
        'drag'
        """
    @property
    def vectorised(self) -> bool:
        """
        Whether the function is compiled with the vectorised signature (bool): then the
        ensembles' SIMD batches take its members.
        
        Examples
        --------
        >>> import gyrostat as g
        >>> g.CustomTorque(lambda t, omega: -omega).vectorised
        False
        """
class MagnitudeLaw:
    """
    The magnitude L(t) of paper 004's servo torque, evaluated in C++.
    """
    @staticmethod
    def constant(value: typing.SupportsFloat | typing.SupportsIndex) -> MagnitudeLaw:
        ...
    @staticmethod
    def harmonic(mean: typing.SupportsFloat | typing.SupportsIndex, amplitudes: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], frequencies: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], phases: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex]) -> MagnitudeLaw:
        ...
    @staticmethod
    def polynomial(coefficients: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex]) -> MagnitudeLaw:
        ...
    @staticmethod
    def tabulated(times: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], values: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], cubic: bool = False) -> MagnitudeLaw:
        ...
    def __call__(self, t: typing.SupportsFloat | typing.SupportsIndex) -> float:
        ...
    def __repr__(self) -> str:
        ...
    def values(self, t: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"]) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    @property
    def kind(self) -> str:
        ...
class Model:
    """
    A model of any family, as the engine integrates it.
    """
    def exact_reduction(self) -> bool:
        """
        Whether the (a, r) system is exact (a symmetric body without rotor under axisymmetric torques).
        """
    def fast_frequency(self, r: typing.SupportsFloat | typing.SupportsIndex) -> float:
        ...
    def first_crossing(self, run: ..., after: typing.SupportsFloat | typing.SupportsIndex) -> float:
        """
        The first output time of the run past `after` (in its direction) at which its state has crossed a separatrix (separatrix's sign changed since the output before); NaN when none, or when the model declares none.
        """
    def from_orbit_frame(self, t: typing.SupportsFloat | typing.SupportsIndex, attitude: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[4, 1]"], omega: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"]) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        The state (omega, q) at t of a body with this attitude (body to orbit frame) and this angular velocity relative to the orbit frame (body axes).
        """
    def full_state(self, slow: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"], phase: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    def initial_state(self, given: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"]) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    def initial_states(self, given: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]", "flags.c_contiguous"]) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        """
        initial_state of every row of ``given`` (n, k): (n, dim).
        """
    def measured_differences(self, reference: ..., other: ..., reference_rows: typing.Any = None, other_rows: typing.Any = None) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        """
        How far two runs are apart on each measured quantity (rows: measured_quantities) at each pair of rows (empty: every row), relative to the quantity's largest size in the reference.
        """
    def outputs_along(self, t: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], y: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]", "flags.c_contiguous"]) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        """
        outputs_at at every time t[i] (n,) and state y[i] (n, dim): (n, outputs).
        """
    def outputs_at(self, t: typing.SupportsFloat | typing.SupportsIndex, y: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"]) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    def principal_states(self, states: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, n]"]) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        """
        States (rows) in the user's body frame, written in the model's principal axes.
        """
    def quasi_static_state(self, omega: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"]) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    def rate(self, t: typing.SupportsFloat | typing.SupportsIndex) -> float:
        ...
    def rhs(self, t: typing.SupportsFloat | typing.SupportsIndex, y: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"]) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    def separatrix(self, states: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, n]"]) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        The signed distance to a separatrix of the unperturbed motion at each state (rows): a change of sign along a run is a crossing; NaN where the model declares none.
        """
    def slow_rate(self, t: typing.SupportsFloat | typing.SupportsIndex, y: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[2, 1]"]) -> float:
        ...
    def tau_rate(self, t: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"], omega: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, n]"]) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    def watch_event(self, outputs: collections.abc.Sequence[typing.SupportsInt | typing.SupportsIndex], back: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], limit: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], name: str, direction: typing.SupportsInt | typing.SupportsIndex = -1, terminal: typing.SupportsInt | typing.SupportsIndex = 1, sample_interval: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> ...:
        """
        An engine event for a run of a model above this one on the ladder, evaluated in C++ at every step (or, with ``sample_interval`` > 0, at step ends that far apart in t, the crossing placed at the step end where it is seen): g(t, y) = the largest (o_i - back_i) / (limit_i - back_i) of this model's outputs o = outputs_at(t, y) (y mapped down as initial_state maps it) at the indices ``outputs`` (1 where one is not finite). It falls through 0 where every watched output is back below its ``back``.
        """
    @property
    def affine_in(self) -> list[str]:
        """
        The model's own numbers its right-hand side is affine in (sensitivities take their derivative by a one-sided difference, exact to rounding).
        """
    @property
    def analytic_in(self) -> list[str]:
        """
        The model's own numbers whose derivative of the right-hand side it gives in closed form (sensitivities take it instead of a difference quotient).
        """
    @property
    def dim(self) -> int:
        ...
    @property
    def family(self) -> str:
        ...
    @property
    def measured_quantities(self) -> list:
        """
        What a run's error is measured on (the accuracy contract): (name, role ('state' or 'output'), columns) per quantity; a vector's components (omega, quaternion, ...) as one quantity, labels left out.
        """
    @property
    def orbit(self) -> typing.Any:
        """
        The model's orbit (gyrostat.Orbit), or None.
        """
    @property
    def output_names(self) -> list[str]:
        ...
    @property
    def quantities(self) -> list:
        """
        What the model declares about its state and outputs: name, unit, description, role ('state' or 'output') and whether it is conserved without perturbation.
        """
    @property
    def state_names(self) -> list[str]:
        ...
class Event:
    """
    A zero crossing g(t, y) = quantity - value, located by the engine.
    """
    def __init__(self, quantity: str, index: typing.SupportsInt | typing.SupportsIndex, value: typing.SupportsFloat | typing.SupportsIndex, direction: typing.SupportsInt | typing.SupportsIndex, terminal: typing.SupportsInt | typing.SupportsIndex, name: str, function: typing.Any = None) -> None:
        ...
    @property
    def direction(self) -> int:
        ...
    @property
    def index(self) -> int:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def sample_interval(self) -> float:
        """
        > 0: g evaluated only at step ends this far apart, a crossing placed where it is seen (a costly watch; 0: every step, crossings located on the step's continuous extension).
        """
    @property
    def terminal(self) -> int:
        ...
    @property
    def value(self) -> float:
        ...
class Options:
    """
    Every integrator option with its default (the one place where defaults live).
    
    :func:`gyrostat.solve` makes one from its keywords; pass one as ``options=`` to reuse it. The
    attributes are the options (each one documented below).
    
    Examples
    --------
    >>> import gyrostat
    >>> options = gyrostat.Options()
    >>> options.rtol = 1e-10
    >>> options.rtol, options.method
    (1e-10, 'dop853')
    """
    @staticmethod
    def check(name: str, value: typing.SupportsFloat | typing.SupportsIndex) -> None:
        """
        The engine's rule for one scalar option (rtol, atol, n_out, max_steps, first_step, max_step, step, splitting_order): ValueError naming the value when it breaks it. The scene schema applies it too.
        
        Parameters
        ----------
        name : str
            The option.
        value : float
            Its value, in its unit.
        
        Examples
        --------
        >>> import gyrostat
        >>> gyrostat.Options.check('rtol', 1e-9)
        """
    def __copy__(self) -> Options:
        """
        A copy of every option (events included).
        """
    def __init__(self) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def to_dict(self) -> dict:
        """
        Every scalar option by name (not t_eval and events): what report.json records of a run.
        
        Examples
        --------
        >>> import gyrostat
        >>> gyrostat.Options().to_dict()['rtol']
        1e-08
        """
    def validate(self, t0: typing.SupportsFloat | typing.SupportsIndex, t1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        """
        The engine's checks of these options for a run over (t0, t1), without running: ValueError naming the value.
        
        Parameters
        ----------
        t0, t1 : float
            The span of the run, in s.
        
        Examples
        --------
        >>> import gyrostat
        >>> gyrostat.Options().validate(0.0, 10.0)
        """
    @property
    def atol(self) -> float:
        """
        Absolute tolerance of the adaptive methods, in the units of each state component.
        
        Examples
        --------
        >>> import gyrostat
        >>> gyrostat.Options().atol
        1e-10
        """
    @atol.setter
    def atol(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def dense_output(self) -> bool:
        """
        Keep each step's continuous extension, for ``solution(t)``.
        
        Examples
        --------
        >>> import gyrostat
        >>> gyrostat.Options().dense_output
        False
        """
    @dense_output.setter
    def dense_output(self, arg0: bool) -> None:
        ...
    @property
    def events(self) -> list[Event]:
        """
        The engine's events of a run (made by :func:`gyrostat.solve` from :class:`gyrostat.events.Event`).
        
        Examples
        --------
        >>> import gyrostat
        >>> gyrostat.Options().events
        []
        """
    @events.setter
    def events(self, arg0: collections.abc.Sequence[Event]) -> None:
        ...
    @property
    def every_step(self) -> bool:
        """
        Record every accepted step instead of the output times.
        
        Examples
        --------
        >>> import gyrostat
        >>> gyrostat.Options().every_step
        False
        """
    @every_step.setter
    def every_step(self, arg0: bool) -> None:
        ...
    @property
    def first_step(self) -> float:
        """
        Size of the first step, in s (0: the method picks it).
        
        Examples
        --------
        >>> import gyrostat
        >>> gyrostat.Options().first_step
        0.0
        """
    @first_step.setter
    def first_step(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def max_step(self) -> float:
        """
        Largest step, in s (inf: no limit).
        
        Examples
        --------
        >>> import gyrostat
        >>> gyrostat.Options().max_step
        inf
        """
    @max_step.setter
    def max_step(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def max_steps(self) -> int:
        """
        Most steps a run may take before it stops with status max_steps_reached.
        
        Examples
        --------
        >>> import gyrostat
        >>> gyrostat.Options().max_steps
        1000000
        """
    @max_steps.setter
    def max_steps(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def method(self) -> str:
        """
        The integrator (one of :data:`gyrostat.METHODS`, or ``"auto"``).
        
        Examples
        --------
        >>> import gyrostat
        >>> gyrostat.Options().method
        'dop853'
        """
    @method.setter
    def method(self, arg1: str) -> None:
        ...
    @property
    def n_out(self) -> int:
        """
        Number of equally spaced output times over the span when t_eval is empty.
        
        Examples
        --------
        >>> import gyrostat
        >>> gyrostat.Options().n_out
        1001
        """
    @n_out.setter
    def n_out(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def only_measured_outputs(self) -> bool:
        """
        Record only the outputs a run's error is measured on (:func:`gyrostat.accuracy.quantities`), NaN in the others: what the accuracy contract's probes and companions record.
        
        Examples
        --------
        >>> import gyrostat
        >>> gyrostat.Options().only_measured_outputs
        False
        """
    @only_measured_outputs.setter
    def only_measured_outputs(self, arg0: bool) -> None:
        ...
    @property
    def rtol(self) -> float:
        """
        Relative tolerance of the adaptive methods (1: dimensionless).
        
        Examples
        --------
        >>> import gyrostat
        >>> gyrostat.Options().rtol
        1e-08
        """
    @rtol.setter
    def rtol(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def sensitivity_error_control(self) -> bool:
        """
        A run with sensitivities: whether each sensitivity's error joins the state's in the step-size control (CVODES's errconS). False: the plain run's steps, the sensitivities' errors measured and reported but not held; True: held to the tolerances too, at the cost of more steps (dop853 and taylor; cvode_bdf holds them always).
        
        Examples
        --------
        >>> import gyrostat
        >>> gyrostat.Options().sensitivity_error_control
        False
        """
    @sensitivity_error_control.setter
    def sensitivity_error_control(self, arg0: bool) -> None:
        ...
    @property
    def splitting_order(self) -> int:
        """
        Order of method ``splitting``: 2, 4 or 6.
        
        Examples
        --------
        >>> import gyrostat
        >>> gyrostat.Options().splitting_order
        4
        """
    @splitting_order.setter
    def splitting_order(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def step(self) -> float:
        """
        Fixed step of method ``splitting``, in s (0: none given).
        
        Examples
        --------
        >>> import gyrostat
        >>> gyrostat.Options().step
        0.0
        """
    @step.setter
    def step(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def t_eval(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        Output times, in s (empty: n_out equally spaced times).
        
        Examples
        --------
        >>> import gyrostat
        >>> gyrostat.Options().t_eval
        array([], dtype=float64)
        """
    @t_eval.setter
    def t_eval(self, arg1: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> None:
        ...
class Stats:
    @property
    def jacobian_evals(self) -> int:
        ...
    @property
    def last_step(self) -> float:
        ...
    @property
    def nonlinear_conv_failures(self) -> int:
        ...
    @property
    def rejected_steps(self) -> int:
        ...
    @property
    def rhs_evals(self) -> int:
        ...
    @property
    def steps(self) -> int:
        ...
class Result:
    """
    A trajectory as the engine returns it; the arrays are views of its memory.
    """
    def dense(self, t: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> numpy.typing.NDArray[numpy.float64]:
        """
        The solution at the times t (1-D), from each step's continuous extension.
        """
    def dense_whole(self, t: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> numpy.typing.NDArray[numpy.float64]:
        """
        Everything the dense output keeps at the times t: the state, then what a run integrated beside it (a run with sensitivities: each sensitivity's column after the state, [time, (1 + columns) * dim]).
        """
    @property
    def dim(self) -> int:
        ...
    @property
    def error_estimate(self) -> float:
        """
        The run's own global error estimate relative to max|y_i| (splitting); NaN: none.
        """
    @property
    def event_names(self) -> list[str]:
        ...
    @property
    def h_next(self) -> float:
        """
        The step size the integrator would try next (0: its own choice).
        """
    @property
    def has_dense(self) -> bool:
        ...
    @property
    def message(self) -> str:
        ...
    @property
    def method(self) -> str:
        ...
    @property
    def methods_used(self) -> list[str]:
        """
        The integrators that carried the run, in order of first use.
        """
    @property
    def notes(self) -> list[str]:
        """
        What the run says about its own answer (information).
        """
    @property
    def options(self) -> Options:
        """
        The options the run was made with (without t_eval and events).
        """
    @property
    def output_conserved(self) -> list[bool]:
        ...
    @property
    def output_descriptions(self) -> list[str]:
        ...
    @property
    def output_kept(self) -> list[bool]:
        ...
    @property
    def output_names(self) -> list[str]:
        ...
    @property
    def output_units(self) -> list[str]:
        ...
    @property
    def outputs(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def remarked(self) -> bool:
        """
        Whether the run left notes or warnings (one test, where reading them converts their strings).
        """
    @property
    def state_descriptions(self) -> list[str]:
        ...
    @property
    def state_names(self) -> list[str]:
        ...
    @property
    def state_units(self) -> list[str]:
        ...
    @property
    def stats(self) -> Stats:
        ...
    @property
    def status(self) -> str:
        ...
    @property
    def success(self) -> bool:
        ...
    @property
    def switches(self) -> list:
        """
        Method 'auto': each switch as (t, method switched to, reason).
        """
    @property
    def t(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def t_events(self) -> list:
        ...
    @property
    def t_last(self) -> float:
        """
        Where the run stopped: the last accepted time.
        """
    @property
    def terminal_event(self) -> int:
        ...
    @property
    def warnings(self) -> list[str]:
        """
        What the run doubts about its own answer (warned in Python).
        """
    @property
    def y(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def y_events(self) -> list:
        ...
    @property
    def y_last(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        The state at t_last.
        """
class WindowRule:
    """
    The numbers a window estimate is made with (gyrostat/measure.hpp).
    """
    def __init__(self, fraction: typing.SupportsFloat | typing.SupportsIndex, least_times: typing.SupportsInt | typing.SupportsIndex, safety: typing.SupportsFloat | typing.SupportsIndex, floor: typing.SupportsFloat | typing.SupportsIndex, gain: typing.SupportsFloat | typing.SupportsIndex, fit_steps: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def fraction(self) -> float:
        ...
    @property
    def gain(self) -> float:
        ...
class TorqueFreeSolution:
    """
    The closed-form angular velocity of a torque-free rigid body (Jacobi elliptic functions).
    
    Parameters
    ----------
    body : gyrostat.Body
        The body (without rotor).
    omega0 : array_like, shape (3,)
        Angular velocity at t0 in body axes, in rad/s.
    t0 : float, optional
        Time of omega0, in s (default 0).
    
    Examples
    --------
    >>> import gyrostat
    >>> free = gyrostat.TorqueFreeSolution(gyrostat.Body([3.0, 2.0, 1.0]), [0.1, 0.2, 1.0])
    >>> free.period
    10.858161104747332
    """
    def __init__(self, body: Body, omega0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"], t0: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> None:
        ...
    def omega(self, t: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex]) -> numpy.typing.NDArray[numpy.float64]:
        """
        The angular velocity at each time.
        
        Parameters
        ----------
        t : sequence of float
            Times, in s.
        
        Returns
        -------
        numpy.ndarray, shape (n, 3)
            omega in body axes, in rad/s.
        
        Examples
        --------
        >>> import gyrostat
        >>> free = gyrostat.TorqueFreeSolution(gyrostat.Body([3.0, 2.0, 1.0]), [0.1, 0.2, 1.0])
        >>> free.omega([0.0])
        array([[0.1, 0.2, 1. ]])
        """
    @property
    def frequency(self) -> float:
        """
        The frequency of the elliptic functions' argument, in rad/s (signed).
        
        Examples
        --------
        >>> import gyrostat
        >>> free = gyrostat.TorqueFreeSolution(gyrostat.Body([3.0, 2.0, 1.0]), [0.1, 0.2, 1.0])
        >>> free.frequency
        -0.5887840577551898
        """
    @property
    def is_constant(self) -> bool:
        """
        Whether omega is constant (a permanent rotation about a principal axis).
        
        Examples
        --------
        >>> import gyrostat
        >>> free = gyrostat.TorqueFreeSolution(gyrostat.Body([3.0, 2.0, 1.0]), [0.1, 0.2, 1.0])
        >>> free.is_constant
        False
        """
    @property
    def modulus_squared(self) -> float:
        """
        The elliptic modulus squared m = k^2 (0 for a permanent rotation; 1: dimensionless).
        
        Examples
        --------
        >>> import gyrostat
        >>> free = gyrostat.TorqueFreeSolution(gyrostat.Body([3.0, 2.0, 1.0]), [0.1, 0.2, 1.0])
        >>> free.modulus_squared
        0.06730769230769232
        """
    @property
    def period(self) -> float:
        """
        The period of omega(t), in s.
        
        Examples
        --------
        >>> import gyrostat
        >>> free = gyrostat.TorqueFreeSolution(gyrostat.Body([3.0, 2.0, 1.0]), [0.1, 0.2, 1.0])
        >>> free.period
        10.858161104747332
        """
class LagrangeNutation:
    @property
    def alpha(self) -> float:
        ...
    @property
    def m(self) -> float:
        ...
    @property
    def period(self) -> float:
        ...
    @property
    def u1(self) -> float:
        ...
    @property
    def u2(self) -> float:
        ...
    @property
    def u3(self) -> float:
        ...
    @property
    def v(self) -> float:
        ...
class LagrangeUnperturbed:
    def __init__(self, A: typing.SupportsFloat | typing.SupportsIndex, C: typing.SupportsFloat | typing.SupportsIndex, mu: typing.SupportsFloat | typing.SupportsIndex, omega: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"], gamma: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"], t0: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> None:
        ...
    def u(self, t: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex]) -> list[float]:
        ...
    @property
    def G_z(self) -> float:
        ...
    @property
    def H(self) -> float:
        ...
    @property
    def beta(self) -> float:
        ...
    @property
    def nutation(self) -> LagrangeNutation:
        ...
    @property
    def r(self) -> float:
        ...
def averaged_model(body: Body, torques: collections.abc.Iterable) -> Model:
    ...
def averaged_triaxial_model(body: Body, torques: collections.abc.Iterable) -> Model:
    ...
def companion_step_limit(answer: Result, t0: typing.SupportsFloat | typing.SupportsIndex, first: Stats | None = None) -> float:
    """
    The largest step a companion measuring ``answer`` (a run from t0) may take: half the answer's mean step where it took fewer than 4 steps, or where ``first`` (a companion's Stats, run without the limit) took fewer than 1.05 times its steps for a Runge-Kutta pair of one order (its steps not its tolerance's); infinity otherwise (gyrostat/measure.hpp).
    """
def complete_elliptic(m: typing.SupportsFloat | typing.SupportsIndex, m1: typing.SupportsFloat | typing.SupportsIndex) -> tuple[float, float]:
    """
    (K(m), <sn^2> = (K - E)/(m K)) by polynomial pieces (the triaxial averaged model's), m read up to 1/2 and its complement m1 = 1 - m beyond
    """
def elliptic_E(m: typing.SupportsFloat | typing.SupportsIndex) -> float:
    """
    E(m), parameter m = k^2 (GSL)
    """
def elliptic_K(m: typing.SupportsFloat | typing.SupportsIndex) -> float:
    """
    K(m), parameter m = k^2 (GSL)
    """
def euler_angles(q: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], convention: str = 'zxz') -> numpy.typing.NDArray[numpy.float64]:
    """
    Euler angles (psi, theta, phi) of quaternions (w, x, y, z), shape (4,) or (n, 4), body -> inertial;
    convention 'zxz' (R = Rz(psi) Rx(theta) Rz(phi)) or 'zyx' (R = Rz(psi) Ry(theta) Rx(phi)).
    At a singular theta the free rotation is in psi and phi = 0. Returns shape (3,) or (n, 3).
    """
def grow(last: typing.SupportsFloat | typing.SupportsIndex, half: typing.SupportsFloat | typing.SupportsIndex, end: typing.SupportsFloat | typing.SupportsIndex, middle: typing.SupportsFloat | typing.SupportsIndex, far: typing.SupportsFloat | typing.SupportsIndex, least: typing.SupportsFloat | typing.SupportsIndex = 1.0) -> tuple[float, float]:
    """
    A difference's running maximum over a window (``last`` at its end, ``half`` at its middle output time) grown to the horizon as t^k, k fitted over the window's second half and kept within [least, 2]; (value, k). ``end``, ``middle``, ``far``: the distances from t0 of the window's end, its middle output time and the horizon.
    """
def gyrostat_model(body: Body, torques: collections.abc.Iterable, attitude: bool, orbit: typing.Any = None) -> Model:
    ...
def jacobi_sn_cn_dn(u: typing.SupportsFloat | typing.SupportsIndex, m: typing.SupportsFloat | typing.SupportsIndex) -> typing.Annotated[list[float], "FixedSize(3)"]:
    """
    (sn, cn, dn)(u | m) (GSL)
    """
def lagrange_averaged_model(body: Body, mu: typing.SupportsFloat | typing.SupportsIndex, torques: collections.abc.Iterable) -> Model:
    ...
def lagrange_nutation(A: typing.SupportsFloat | typing.SupportsIndex, C: typing.SupportsFloat | typing.SupportsIndex, mu: typing.SupportsFloat | typing.SupportsIndex, G_z: typing.SupportsFloat | typing.SupportsIndex, H: typing.SupportsFloat | typing.SupportsIndex, r: typing.SupportsFloat | typing.SupportsIndex) -> LagrangeNutation:
    ...
def lagrange_nutation_slopes(A: typing.SupportsFloat | typing.SupportsIndex, C: typing.SupportsFloat | typing.SupportsIndex, mu: typing.SupportsFloat | typing.SupportsIndex, G_z: typing.SupportsFloat | typing.SupportsIndex, H: typing.SupportsFloat | typing.SupportsIndex, r: typing.SupportsFloat | typing.SupportsIndex) -> tuple[float, float, float, float]:
    """
    (dv/dG_z, dv/dH, dv/dr, dv/dmu) of v = <cos theta> over the nutation, at fixed A and C
    """
def lagrange_nutation_table(A: typing.SupportsFloat | typing.SupportsIndex, C: typing.SupportsFloat | typing.SupportsIndex, mu: typing.SupportsFloat | typing.SupportsIndex, G_z: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], H: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], r: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex]) -> numpy.typing.NDArray[numpy.float64]:
    """
    Rows (u1, u2, u3, m, alpha, v, period) for each (G_z, H, r).
    """
def lagrange_top_model(body: Body, mu: typing.SupportsFloat | typing.SupportsIndex, torques: collections.abc.Iterable) -> Model:
    ...
def load_batches(directory: str, asked: str = '') -> tuple[str, int]:
    """
    Installs the widest SIMD form of the ensemble batches the CPU runs, from the plugins in ``directory`` (or the one ``asked`` names: sse2, avx2, avx512); returns (instruction set, lanes).
    """
def mean_sn_squared(m: typing.SupportsFloat | typing.SupportsIndex) -> float:
    """
    W(m) = (K - E)/(m K) = <sn^2>
    """
def method_descriptions() -> list[str]:
    """
    One line per integrator, in the order of methods(): what it is and what it is for.
    """
def methods() -> list[str]:
    ...
def moving_mass_model(body: Body, mass: typing.Any, arm: typing.Any, frequency: typing.Any, damping: typing.Any, torques: collections.abc.Iterable) -> Model:
    ...
def orthogonal_model(body: Body, law: MagnitudeLaw, torques: collections.abc.Iterable, attitude: bool, eta: typing.SupportsFloat | typing.SupportsIndex, smooth: bool) -> Model:
    ...
def quaternion_from_euler(angles: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], convention: str = 'zxz') -> numpy.typing.NDArray[numpy.float64]:
    """
    Unit quaternions (w, x, y, z), w >= 0, of Euler angles (psi, theta, phi), shape (3,) or (n, 3),
    convention 'zxz' or 'zyx'. Returns shape (4,) or (n, 4).
    """
def quaternion_from_matrix(R: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> numpy.typing.NDArray[numpy.float64]:
    """
    Unit quaternions (w, x, y, z), w >= 0, of rotation matrices, shape (3, 3) or (n, 3, 3) (Shepperd's
    method). Returns shape (4,) or (n, 4).
    """
def rotation_matrix(q: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> numpy.typing.NDArray[numpy.float64]:
    """
    Body -> inertial rotation matrices R(q) of quaternions (w, x, y, z) (normalised first), shape (4,)
    or (n, 4). Returns shape (3, 3) or (n, 3, 3).
    """
def solve(model: Model, y0: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], t0: typing.SupportsFloat | typing.SupportsIndex, t1: typing.SupportsFloat | typing.SupportsIndex, options: Options, progress: typing.Any = None, interval: typing.SupportsFloat | typing.SupportsIndex = 0.1) -> Result:
    ...
def solve_ensemble(models: collections.abc.Sequence[Model], y0s: typing.Any, t0: typing.SupportsFloat | typing.SupportsIndex, t1: typing.SupportsFloat | typing.SupportsIndex, options: Options, threads: typing.SupportsInt | typing.SupportsIndex = 0, progress: typing.Any = None, interval: typing.SupportsFloat | typing.SupportsIndex = 0.1, batch: bool = True) -> list[Result]:
    ...
def solve_measured(model: Model, y0: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], t0: typing.SupportsFloat | typing.SupportsIndex, t1: typing.SupportsFloat | typing.SupportsIndex, options: Options, companion: Options, rule: WindowRule, progress: typing.Any = None, whole_span: bool = False, measured_only: bool = False) -> tuple[Result, typing.Any]:
    """
    A run and its window estimate in one call (gyrostat/measure.hpp: solve_measured): (the Result, window_estimate's tuple or None where none is made here; with ``measured_only``, a whole span's companion records only the measured outputs and the tuple ends with its Stats).
    """
def solve_sensitivities(model: Model, columns: collections.abc.Sequence[tuple], y0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"], t0: typing.SupportsFloat | typing.SupportsIndex, t1: typing.SupportsFloat | typing.SupportsIndex, options: Options, progress: typing.Any = None, interval: typing.SupportsFloat | typing.SupportsIndex = 0.1) -> tuple:
    """
    The run with its forward sensitivities (the variational equations by DOP853): (Result, d state / d column [time, component, column], d outputs / d column [time, output, column]). A column is (component, None, None, 0, atol) for an initial component, (-1, model with the parameter + step, model with it - step, step, atol) for a parameter.
    """
def solve_sensitivities_ensemble(models: collections.abc.Sequence[Model], columns: collections.abc.Sequence[collections.abc.Sequence[tuple]], y0s: typing.Any, t0: typing.SupportsFloat | typing.SupportsIndex, t1: typing.SupportsFloat | typing.SupportsIndex, options: Options, threads: typing.SupportsInt | typing.SupportsIndex = 0, progress: typing.Any = None, interval: typing.SupportsFloat | typing.SupportsIndex = 0.1) -> list:
    """
    solve_sensitivities for every member on a pool of threads (models and column sets: one, or one per member); a list of (Result, d state, d outputs), a member with bad input with status invalid_input and empty arrays.
    """
def summaries(results: list, state_names: collections.abc.Sequence[str], output_names: collections.abc.Sequence[str], extrema: bool = False) -> dict:
    """
    Many Results as columns: status, message, first warning (lists), the statistics, rows, terminal_event, t_final, named (the names are these), final (the last state and outputs; NaN without rows or under other names) and, with extrema, their min and max over the rows.
    """
def torque_free_model(body: Body, attitude: bool = False) -> Model:
    ...
def unit_vector(v: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], name: str = 'v') -> numpy.typing.NDArray[numpy.float64]:
    """
    The unit vector along v, shape (n,), whatever its length: v / max|v_i| normalised (no overflow or
    underflow). ValueError naming `name` and v when v is zero or not finite.
    """
def window_estimate(model: Model, answer: Result, t0: typing.SupportsFloat | typing.SupportsIndex, y0: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], t1: typing.SupportsFloat | typing.SupportsIndex, companion: Options, rule: WindowRule, progress: typing.Any = None, whole_span: bool = False) -> typing.Any:
    """
    The window estimate of a run (gyrostat/measure.hpp), or with ``whole_span`` its measurement over every output time: (each measured quantity's estimate, the largest growth exponent, whether grown to the horizon, the window's end, the times compared, why there is none or '', the companion's Result with ``whole_span``, else its Stats, the largest step the companion was allowed (infinity: no limit; ``companion_step_limit``)); None where the window cannot be measured here (too few output times in it, a separatrix crossed).
    """
def window_estimates(models: collections.abc.Sequence[Model], answers: collections.abc.Sequence[Result], t0: typing.SupportsFloat | typing.SupportsIndex, y0s: typing.Any, t1: typing.SupportsFloat | typing.SupportsIndex, companion: Options, rule: WindowRule, threads: typing.SupportsInt | typing.SupportsIndex = 0, progress: typing.Any = None, batch: bool = True, whole_span: bool = False) -> list:
    """
    Each member's window_estimate (or whole-span measurement), the companions run as one ensemble (gyrostat/measure.hpp): a list of window_estimate's tuples, None for a member left to the caller.
    """
def window_from_differences(apart: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]", "flags.f_contiguous"], times: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], t0: typing.SupportsFloat | typing.SupportsIndex, horizon: typing.SupportsFloat | typing.SupportsIndex, rule: WindowRule, to_horizon: bool = True, companion_steps: typing.SupportsInt | typing.SupportsIndex | None = None) -> tuple:
    """
    A window estimate from the quantities' differences (quantities x times) at the window's times, as window_estimate's tuple without the companion; ``companion_steps``: the companion's steps over the window (fewer than ``rule``'s fit_steps: k = 1, not fitted; None: fitted).
    """
__version__: str = '0.1.0'
large: float = 10.0
max_output_bytes: float = 2147483648.0
simd_instruction_set: str
simd_lanes: int
small: float = 0.1
taylor_kernel: str
torque_types: list = [ConstantTorque, LinearDamping, ResistiveMedium, ViscousCavity, MovingMassDamper, GravityGradient, MagneticTorque, DipoleFieldTorque, InertialTorque, CustomTorque]
