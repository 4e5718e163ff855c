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
__all__: list[str] = ['Body', 'ConstantTorque', 'CustomTorque', 'DipoleFieldTorque', 'Event', 'GravityGradient', 'InertialTorque', 'LagrangeNutation', 'LagrangeUnperturbed', 'LinearDamping', 'MagneticTorque', 'MagnitudeLaw', 'Model', 'Motion', 'MovingMassDamper', 'Options', 'ResistiveMedium', 'Result', 'Stats', 'TorqueAssumption', 'TorqueFreeSolution', 'ViscousCavity', 'averaged_model', 'elliptic_E', 'elliptic_K', 'euler_angles', 'gyrostat_model', 'jacobi_sn_cn_dn', 'lagrange_averaged_model', 'lagrange_nutation', 'lagrange_nutation_table', 'lagrange_top_model', 'large', 'max_output_bytes', 'mean_sn_squared', 'method_descriptions', 'methods', 'moving_mass_model', 'orthogonal_model', 'quaternion_from_euler', 'quaternion_from_matrix', 'rotation_matrix', 'simd_instruction_set', 'simd_lanes', 'small', 'solve', 'solve_ensemble', 'taylor_kernel', 'torque_free_model', 'torque_types']
class Body:
    def __init__(self, moments: typing.Any, rotor: typing.Any = None) -> None:
        ...
    def __repr__(self) -> str:
        ...
    @property
    def moments(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        ...
    @property
    def rotor(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        ...
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
class ConstantTorque:
    """
    a constant torque in body axes (scene type "constant").
    
    Parameters:
        moment [N m]: M in body axes (finite)
    """
    description: typing.ClassVar[str] = 'a constant torque in body axes'
    has_averaged: typing.ClassVar[bool] = True
    kind: typing.ClassVar[str] = 'constant'
    needs_attitude: typing.ClassVar[bool] = False
    parameters: typing.ClassVar[list] = [{'name': 'moment', 'label': 'moment', 'shape': 'vector3', 'unit': 'N m', 'description': 'M in body axes', 'constraint': 'finite', 'choice': 0, 'stored': True, 'default': None}]
    def __call__(self, t: typing.Any, omega: typing.Any, moments: typing.Any, quaternion: typing.Any = None) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        The torque in body axes at (t, omega) on a body with these moments (and this attitude, body to inertial, for a torque that needs it).
        """
    def __init__(self, *args, **kwargs) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def assumptions(self, motion: Motion) -> list[TorqueAssumption]:
        """
        Its validity numbers over a motion: a list of Assumption (empty when it assumes nothing).
        """
    def averaged(self, t: typing.Any, a: typing.Any, r: typing.Any, A: typing.Any, C: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[2, 1]"]:
        """
        Its contribution (da/dt, dr/dt) to the system averaged over the symmetric Euler-Poinsot motion.
        """
    @property
    def moment(self) -> typing.Any:
        """
        M in body axes [N m]
        """
class LinearDamping:
    """
    M = -D omega (scene type "linear_damping").
    
    Parameters:
        matrix [N m s]: D (M = -D omega) (finite; one of a choice)
        diagonal [N m s]: the diagonal of D (finite; one of a choice)
    """
    description: typing.ClassVar[str] = 'M = -D omega'
    has_averaged: typing.ClassVar[bool] = True
    kind: typing.ClassVar[str] = 'linear_damping'
    needs_attitude: typing.ClassVar[bool] = False
    parameters: typing.ClassVar[list] = [{'name': 'matrix', 'label': 'matrix D (column-major)', 'shape': 'matrix3', 'unit': 'N m s', 'description': 'D (M = -D omega)', 'constraint': 'finite', 'choice': 1, 'stored': True, 'default': None}, {'name': 'diagonal', 'label': 'diagonal of D', 'shape': 'vector3', 'unit': 'N m s', 'description': 'the diagonal of D', 'constraint': 'finite', 'choice': 1, 'stored': False, 'default': None}]
    def __call__(self, t: typing.Any, omega: typing.Any, moments: typing.Any, quaternion: typing.Any = None) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        The torque in body axes at (t, omega) on a body with these moments (and this attitude, body to inertial, for a torque that needs it).
        """
    def __init__(self, *args, **kwargs) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def assumptions(self, motion: Motion) -> list[TorqueAssumption]:
        """
        Its validity numbers over a motion: a list of Assumption (empty when it assumes nothing).
        """
    def averaged(self, t: typing.Any, a: typing.Any, r: typing.Any, A: typing.Any, C: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[2, 1]"]:
        """
        Its contribution (da/dt, dr/dt) to the system averaged over the symmetric Euler-Poinsot motion.
        """
    @property
    def matrix(self) -> typing.Any:
        """
        D (M = -D omega) [N m s]
        """
class ResistiveMedium:
    """
    a resistive medium whose resistance varies with time (scene type "resistive_medium").
    
    Parameters:
        coefficients [N m s^(k+1)]: D_0, D_1, ...: D(t) = sum D_k t^k (M = -D(t) omega) (finite)
    """
    description: typing.ClassVar[str] = 'a resistive medium whose resistance varies with time'
    has_averaged: typing.ClassVar[bool] = True
    kind: typing.ClassVar[str] = 'resistive_medium'
    needs_attitude: typing.ClassVar[bool] = False
    parameters: typing.ClassVar[list] = [{'name': 'coefficients', 'label': 'coefficient', 'shape': 'matrices', 'unit': 'N m s^(k+1)', 'description': 'D_0, D_1, ...: D(t) = sum D_k t^k (M = -D(t) omega)', 'constraint': 'finite', 'choice': 0, 'stored': True, 'default': None}]
    def __call__(self, t: typing.Any, omega: typing.Any, moments: typing.Any, quaternion: typing.Any = None) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        The torque in body axes at (t, omega) on a body with these moments (and this attitude, body to inertial, for a torque that needs it).
        """
    def __init__(self, *args, **kwargs) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def assumptions(self, motion: Motion) -> list[TorqueAssumption]:
        """
        Its validity numbers over a motion: a list of Assumption (empty when it assumes nothing).
        """
    def at(self, t: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 3]"]:
        """
        D(t).
        """
    def averaged(self, t: typing.Any, a: typing.Any, r: typing.Any, A: typing.Any, C: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[2, 1]"]:
        """
        Its contribution (da/dt, dr/dt) to the system averaged over the symmetric Euler-Poinsot motion.
        """
    @property
    def coefficients(self) -> typing.Any:
        """
        D_0, D_1, ...: D(t) = sum D_k t^k (M = -D(t) omega) [N m s^(k+1)]
        """
class ViscousCavity:
    """
    a cavity filled with a highly viscous fluid (scene type "viscous_cavity").
    
    Parameters:
        density [kg/m^3]: rho (finite and positive)
        viscosity [m^2/s]: kinematic viscosity nu (finite and positive)
        p0 [m^5]: P0 of the cavity tensor P = P0 I (finite and positive; one of a choice)
        radius [m]: radius of a spherical cavity (finite and positive; one of a choice)
    """
    description: typing.ClassVar[str] = 'a cavity filled with a highly viscous fluid'
    has_averaged: typing.ClassVar[bool] = True
    kind: typing.ClassVar[str] = 'viscous_cavity'
    needs_attitude: typing.ClassVar[bool] = False
    parameters: typing.ClassVar[list] = [{'name': 'density', 'label': 'density ρ', 'shape': 'scalar', 'unit': 'kg/m^3', 'description': 'rho', 'constraint': 'positive', 'choice': 0, 'stored': True, 'default': None}, {'name': 'viscosity', 'label': 'kinematic viscosity ν', 'shape': 'scalar', 'unit': 'm^2/s', 'description': 'kinematic viscosity nu', 'constraint': 'positive', 'choice': 0, 'stored': True, 'default': None}, {'name': 'p0', 'label': 'cavity coefficient P0', 'shape': 'scalar', 'unit': 'm^5', 'description': 'P0 of the cavity tensor P = P0 I', 'constraint': 'positive', 'choice': 1, 'stored': True, 'default': None}, {'name': 'radius', 'label': 'cavity radius b', 'shape': 'scalar', 'unit': 'm', 'description': 'radius of a spherical cavity', 'constraint': 'positive', 'choice': 1, 'stored': False, 'default': None}]
    @staticmethod
    def sphere(density: typing.Any, viscosity: typing.Any, radius: typing.Any) -> ViscousCavity:
        """
        A spherical cavity of this radius.
        """
    def __call__(self, t: typing.Any, omega: typing.Any, moments: typing.Any, quaternion: typing.Any = None) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        The torque in body axes at (t, omega) on a body with these moments (and this attitude, body to inertial, for a torque that needs it).
        """
    def __init__(self, *args, **kwargs) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def assumptions(self, motion: Motion) -> list[TorqueAssumption]:
        """
        Its validity numbers over a motion: a list of Assumption (empty when it assumes nothing).
        """
    def averaged(self, t: typing.Any, a: typing.Any, r: typing.Any, A: typing.Any, C: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[2, 1]"]:
        """
        Its contribution (da/dt, dr/dt) to the system averaged over the symmetric Euler-Poinsot motion.
        """
    @property
    def density(self) -> typing.Any:
        """
        rho [kg/m^3]
        """
    @property
    def equivalent_radius(self) -> float:
        """
        the radius of the sphere with this P0
        """
    @property
    def kappa(self) -> float:
        """
        kappa = rho P0 / nu
        """
    @property
    def p0(self) -> typing.Any:
        """
        P0 of the cavity tensor P = P0 I [m^5]
        """
    @property
    def viscosity(self) -> typing.Any:
        """
        kinematic viscosity nu [m^2/s]
        """
class MovingMassDamper:
    """
    Chernousko's quasi-static moving-mass damper (scene type "moving_mass_damper").
    
    Parameters:
        mass [kg]: mass m (finite and positive)
        arm [m]: distance rho of the mass on the z axis (finite and non-negative)
        frequency [rad/s]: Omega = sqrt(c/m) (finite and positive)
        damping [1/s]: lambda = delta/m (finite and non-negative)
    """
    description: typing.ClassVar[str] = "Chernousko's quasi-static moving-mass damper"
    has_averaged: typing.ClassVar[bool] = True
    kind: typing.ClassVar[str] = 'moving_mass_damper'
    needs_attitude: typing.ClassVar[bool] = False
    parameters: typing.ClassVar[list] = [{'name': 'mass', 'label': 'mass m', 'shape': 'scalar', 'unit': 'kg', 'description': 'mass m', 'constraint': 'positive', 'choice': 0, 'stored': True, 'default': None}, {'name': 'arm', 'label': 'arm rho', 'shape': 'scalar', 'unit': 'm', 'description': 'distance rho of the mass on the z axis', 'constraint': 'non_negative', 'choice': 0, 'stored': True, 'default': None}, {'name': 'frequency', 'label': 'frequency Omega', 'shape': 'scalar', 'unit': 'rad/s', 'description': 'Omega = sqrt(c/m)', 'constraint': 'positive', 'choice': 0, 'stored': True, 'default': None}, {'name': 'damping', 'label': 'damping lambda', 'shape': 'scalar', 'unit': '1/s', 'description': 'lambda = delta/m', 'constraint': 'non_negative', 'choice': 0, 'stored': True, 'default': None}]
    def S(self, A: typing.Any, C: typing.Any) -> float:
        """
        S of paper 001 eq. (3) for a symmetric body (A, A, C).
        """
    def __call__(self, t: typing.Any, omega: typing.Any, moments: typing.Any, quaternion: typing.Any = None) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        The torque in body axes at (t, omega) on a body with these moments (and this attitude, body to inertial, for a torque that needs it).
        """
    def __init__(self, *args, **kwargs) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def assumptions(self, motion: Motion) -> list[TorqueAssumption]:
        """
        Its validity numbers over a motion: a list of Assumption (empty when it assumes nothing).
        """
    def averaged(self, t: typing.Any, a: typing.Any, r: typing.Any, A: typing.Any, C: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[2, 1]"]:
        """
        Its contribution (da/dt, dr/dt) to the system averaged over the symmetric Euler-Poinsot motion.
        """
    @property
    def arm(self) -> typing.Any:
        """
        distance rho of the mass on the z axis [m]
        """
    @property
    def damping(self) -> typing.Any:
        """
        lambda = delta/m [1/s]
        """
    @property
    def frequency(self) -> typing.Any:
        """
        Omega = sqrt(c/m) [rad/s]
        """
    @property
    def mass(self) -> typing.Any:
        """
        mass m [kg]
        """
class GravityGradient:
    """
    the gravity-gradient torque on a circular orbit (needs the attitude) (scene type "gravity_gradient").
    
    Parameters:
        orbit_rate [rad/s]: the orbit's mean motion n = sqrt(mu / r^3) (finite and positive)
        orbit_normal [1]: the orbit plane's normal in inertial axes (finite; default [0, 0, 1])
        phase [rad]: the body's angle on the orbit from the ascending node at t = 0 (finite; default 0)
    """
    description: typing.ClassVar[str] = 'the gravity-gradient torque on a circular orbit (needs the attitude)'
    has_averaged: typing.ClassVar[bool] = False
    kind: typing.ClassVar[str] = 'gravity_gradient'
    needs_attitude: typing.ClassVar[bool] = True
    parameters: typing.ClassVar[list] = [{'name': 'orbit_rate', 'label': 'orbit rate n', 'shape': 'scalar', 'unit': 'rad/s', 'description': "the orbit's mean motion n = sqrt(mu / r^3)", 'constraint': 'positive', 'choice': 0, 'stored': True, 'default': None}, {'name': 'orbit_normal', 'label': 'orbit normal N', 'shape': 'vector3', 'unit': '1', 'description': "the orbit plane's normal in inertial axes", 'constraint': 'finite', 'choice': 0, 'stored': True, 'default': '[0, 0, 1]'}, {'name': 'phase', 'label': 'orbit phase', 'shape': 'scalar', 'unit': 'rad', 'description': "the body's angle on the orbit from the ascending node at t = 0", 'constraint': 'finite', 'choice': 0, 'stored': True, 'default': '0'}]
    def __call__(self, t: typing.Any, omega: typing.Any, moments: typing.Any, quaternion: typing.Any = None) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        The torque in body axes at (t, omega) on a body with these moments (and this attitude, body to inertial, for a torque that needs it).
        """
    def __init__(self, *args, **kwargs) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def assumptions(self, motion: Motion) -> list[TorqueAssumption]:
        """
        Its validity numbers over a motion: a list of Assumption (empty when it assumes nothing).
        """
    def precession_rate(self, moments: typing.Any, omega: typing.Any, quaternion: typing.Any) -> float:
        """
        The rate (rad/s) at which G precesses about the orbit normal, averaged over the orbit and the free motion of a symmetric body (A, A, C): -3 n^2 (C - A)(3 cos^2 nutation - 1) cos i / (4 |G|).
        """
    @property
    def orbit_normal(self) -> typing.Any:
        """
        the orbit plane's normal in inertial axes [1]
        """
    @property
    def orbit_rate(self) -> typing.Any:
        """
        the orbit's mean motion n = sqrt(mu / r^3) [rad/s]
        """
    @property
    def phase(self) -> typing.Any:
        """
        the body's angle on the orbit from the ascending node at t = 0 [rad]
        """
class MagneticTorque:
    """
    a magnetic dipole fixed in the body in a field constant in inertial space (needs the attitude) (scene type "magnetic").
    
    Parameters:
        dipole [A m^2]: the body's magnetic dipole moment m in body axes (finite)
        field [T]: the magnetic field B in inertial axes (finite)
    """
    description: typing.ClassVar[str] = 'a magnetic dipole fixed in the body in a field constant in inertial space (needs the attitude)'
    has_averaged: typing.ClassVar[bool] = False
    kind: typing.ClassVar[str] = 'magnetic'
    needs_attitude: typing.ClassVar[bool] = True
    parameters: typing.ClassVar[list] = [{'name': 'dipole', 'label': 'dipole m', 'shape': 'vector3', 'unit': 'A m^2', 'description': "the body's magnetic dipole moment m in body axes", 'constraint': 'finite', 'choice': 0, 'stored': True, 'default': None}, {'name': 'field', 'label': 'field B', 'shape': 'vector3', 'unit': 'T', 'description': 'the magnetic field B in inertial axes', 'constraint': 'finite', 'choice': 0, 'stored': True, 'default': None}]
    def __call__(self, t: typing.Any, omega: typing.Any, moments: typing.Any, quaternion: typing.Any = None) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        The torque in body axes at (t, omega) on a body with these moments (and this attitude, body to inertial, for a torque that needs it).
        """
    def __init__(self, *args, **kwargs) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def assumptions(self, motion: Motion) -> list[TorqueAssumption]:
        """
        Its validity numbers over a motion: a list of Assumption (empty when it assumes nothing).
        """
    @property
    def dipole(self) -> typing.Any:
        """
        the body's magnetic dipole moment m in body axes [A m^2]
        """
    @property
    def field(self) -> typing.Any:
        """
        the magnetic field B in inertial axes [T]
        """
class DipoleFieldTorque:
    """
    a magnetic dipole fixed in the body on a circular orbit in a planet's tilted dipole field (needs the attitude) (scene type "dipole_field").
    
    Parameters:
        dipole [A m^2]: the body's magnetic dipole moment m in body axes (finite)
        field_strength [T]: B0 = mu0 |m_planet| / (4 pi r^3), the field at the magnetic equator at the orbit's radius (finite and positive)
        orbit_rate [rad/s]: the orbit's mean motion n = sqrt(mu / r^3) (finite and positive)
        dipole_axis [1]: the direction of the planet's dipole moment in inertial axes (tilted from -z for a tilted dipole) (finite; default [0, 0, -1])
        orbit_normal [1]: the orbit plane's normal in inertial axes (finite; default [0, 0, 1])
        phase [rad]: the body's angle on the orbit from the ascending node at t = 0 (finite; default 0)
    """
    description: typing.ClassVar[str] = "a magnetic dipole fixed in the body on a circular orbit in a planet's tilted dipole field (needs the attitude)"
    has_averaged: typing.ClassVar[bool] = False
    kind: typing.ClassVar[str] = 'dipole_field'
    needs_attitude: typing.ClassVar[bool] = True
    parameters: typing.ClassVar[list] = [{'name': 'dipole', 'label': 'dipole m', 'shape': 'vector3', 'unit': 'A m^2', 'description': "the body's magnetic dipole moment m in body axes", 'constraint': 'finite', 'choice': 0, 'stored': True, 'default': None}, {'name': 'field_strength', 'label': 'field strength B0', 'shape': 'scalar', 'unit': 'T', 'description': "B0 = mu0 |m_planet| / (4 pi r^3), the field at the magnetic equator at the orbit's radius", 'constraint': 'positive', 'choice': 0, 'stored': True, 'default': None}, {'name': 'orbit_rate', 'label': 'orbit rate n', 'shape': 'scalar', 'unit': 'rad/s', 'description': "the orbit's mean motion n = sqrt(mu / r^3)", 'constraint': 'positive', 'choice': 0, 'stored': True, 'default': None}, {'name': 'dipole_axis', 'label': 'dipole axis d', 'shape': 'vector3', 'unit': '1', 'description': "the direction of the planet's dipole moment in inertial axes (tilted from -z for a tilted dipole)", 'constraint': 'finite', 'choice': 0, 'stored': True, 'default': '[0, 0, -1]'}, {'name': 'orbit_normal', 'label': 'orbit normal N', 'shape': 'vector3', 'unit': '1', 'description': "the orbit plane's normal in inertial axes", 'constraint': 'finite', 'choice': 0, 'stored': True, 'default': '[0, 0, 1]'}, {'name': 'phase', 'label': 'orbit phase', 'shape': 'scalar', 'unit': 'rad', 'description': "the body's angle on the orbit from the ascending node at t = 0", 'constraint': 'finite', 'choice': 0, 'stored': True, 'default': '0'}]
    def __call__(self, t: typing.Any, omega: typing.Any, moments: typing.Any, quaternion: typing.Any = None) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        The torque in body axes at (t, omega) on a body with these moments (and this attitude, body to inertial, for a torque that needs it).
        """
    def __init__(self, *args, **kwargs) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def assumptions(self, motion: Motion) -> list[TorqueAssumption]:
        """
        Its validity numbers over a motion: a list of Assumption (empty when it assumes nothing).
        """
    def field(self, t: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        The planet's field B(t) at the body, in inertial axes [T].
        """
    @property
    def dipole(self) -> typing.Any:
        """
        the body's magnetic dipole moment m in body axes [A m^2]
        """
    @property
    def dipole_axis(self) -> typing.Any:
        """
        the direction of the planet's dipole moment in inertial axes (tilted from -z for a tilted dipole) [1]
        """
    @property
    def field_strength(self) -> typing.Any:
        """
        B0 = mu0 |m_planet| / (4 pi r^3), the field at the magnetic equator at the orbit's radius [T]
        """
    @property
    def orbit_normal(self) -> typing.Any:
        """
        the orbit plane's normal in inertial axes [1]
        """
    @property
    def orbit_rate(self) -> typing.Any:
        """
        the orbit's mean motion n = sqrt(mu / r^3) [rad/s]
        """
    @property
    def phase(self) -> typing.Any:
        """
        the body's angle on the orbit from the ascending node at t = 0 [rad]
        """
class InertialTorque:
    """
    a constant torque fixed in inertial space (needs the attitude) (scene type "inertial").
    
    Parameters:
        moment [N m]: M_I in inertial axes (finite)
    """
    description: typing.ClassVar[str] = 'a constant torque fixed in inertial space (needs the attitude)'
    has_averaged: typing.ClassVar[bool] = False
    kind: typing.ClassVar[str] = 'inertial'
    needs_attitude: typing.ClassVar[bool] = True
    parameters: typing.ClassVar[list] = [{'name': 'moment', 'label': 'moment', 'shape': 'vector3', 'unit': 'N m', 'description': 'M_I in inertial axes', 'constraint': 'finite', 'choice': 0, 'stored': True, 'default': None}]
    def __call__(self, t: typing.Any, omega: typing.Any, moments: typing.Any, quaternion: typing.Any = None) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        The torque in body axes at (t, omega) on a body with these moments (and this attitude, body to inertial, for a torque that needs it).
        """
    def __init__(self, *args, **kwargs) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def assumptions(self, motion: Motion) -> list[TorqueAssumption]:
        """
        Its validity numbers over a motion: a list of Assumption (empty when it assumes nothing).
        """
    @property
    def moment(self) -> typing.Any:
        """
        M_I in inertial axes [N m]
        """
class CustomTorque:
    """
    A torque the user writes, in body axes.
    
    M = f(t, omega) or, with ``attitude=True``, f(t, omega, quaternion): omega in rad/s (body axes),
    the quaternion (w, x, y, z) body to inertial, M in N m (body axes).
    
    Parameters
    ----------
    function : callable or scipy.LowLevelCallable
        A Python callable (each call holds the GIL, about a microsecond of Python per call; an
        ensemble runs it one thread at a time; its exception reaches the caller as raised), or a
        ``scipy.LowLevelCallable`` (from ``numba.cfunc``, ctypes or cffi) of the C signature::
    
            int f(double t, const double *omega, const double *quaternion, double *moment, void *user_data)
    
        called from C++ without the GIL on every thread (quaternion is NULL without the attitude;
        it returns 0, and a non-zero code stops the run with an error naming the torque).
    jacobian : callable or scipy.LowLevelCallable, optional
        dM/domega, of the same kind and arguments as ``function`` (a 3x3 array; compiled: 9 numbers
        row-major). None: central difference quotients (6 calls) for the implicit methods.
    attitude : bool
        The function takes the quaternion; only models with the attitude take the torque.
    name : str, optional
        The name in messages and the repr (default: the function's name).
    
    Examples
    --------
    >>> import numpy as np, gyrostat as g
    >>> drag = g.CustomTorque(lambda t, omega: -0.1 * omega, name="drag")
    >>> drag(0.0, [1.0, 0.0, 0.0], [1.0, 2.0, 3.0])
    array([-0.1, -0. , -0. ])
    """
    description: typing.ClassVar[str] = 'a torque the user writes: M = f(t, omega) or f(t, omega, quaternion) in body axes, a Python callable or a compiled function'
    has_averaged: typing.ClassVar[bool] = False
    kind: typing.ClassVar[str] = 'custom'
    needs_attitude: typing.ClassVar[bool] = False
    parameters: typing.ClassVar[list] = list()
    def __call__(self, t: typing.Any, omega: typing.Any, moments: typing.Any, quaternion: typing.Any = None) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        The torque in body axes at (t, omega) (and the attitude, when it takes it).
        """
    def __init__(self, function: typing.Any, jacobian: typing.Any = None, *, attitude: bool = False, name: typing.Any = None) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def assumptions(self, motion: typing.Any) -> list:
        """
        A user's torque states no assumption: an empty list.
        """
    @property
    def attitude(self) -> bool:
        ...
    @property
    def name(self) -> str:
        ...
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
    def full_state(self, slow: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"], phase: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    def initial_state(self, given: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"]) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    def outputs_at(self, t: typing.SupportsFloat | typing.SupportsIndex, y: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"]) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    def quasi_static_state(self, omega: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"]) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    def rate(self, t: typing.SupportsFloat | typing.SupportsIndex) -> float:
        ...
    def rhs(self, t: typing.SupportsFloat | typing.SupportsIndex, y: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"]) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    def slow_rate(self, t: typing.SupportsFloat | typing.SupportsIndex, y: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[2, 1]"]) -> float:
        ...
    def tau_rate(self, t: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"], omega: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, n]"]) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    @property
    def dim(self) -> int:
        ...
    @property
    def family(self) -> str:
        ...
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
    def terminal(self) -> int:
        ...
    @property
    def value(self) -> float:
        ...
class Options:
    """
    Every integrator option with its default (the one place where defaults live).
    """
    dense_output: bool
    every_step: bool
    method: str
    @staticmethod
    def check(name: str, value: typing.SupportsFloat | typing.SupportsIndex) -> None:
        """
        The engine's rule for one scalar option (rtol, atol, n_out, max_steps, first_step, max_step, step, splitting_order): ValueError naming the value when it breaks it. The scene schema applies it too.
        """
    def __init__(self) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def to_dict(self) -> dict:
        """
        Every scalar option by name (not t_eval and events): what report.json records of a run.
        """
    def validate(self, t0: typing.SupportsFloat | typing.SupportsIndex, t1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        """
        The engine's checks of these options for a run over (t0, t1), without running: ValueError naming the value.
        """
    @property
    def atol(self) -> float:
        ...
    @atol.setter
    def atol(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def events(self) -> list[Event]:
        ...
    @events.setter
    def events(self, arg0: collections.abc.Sequence[Event]) -> None:
        ...
    @property
    def first_step(self) -> float:
        ...
    @first_step.setter
    def first_step(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def max_step(self) -> float:
        ...
    @max_step.setter
    def max_step(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def max_steps(self) -> int:
        ...
    @max_steps.setter
    def max_steps(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def n_out(self) -> int:
        ...
    @n_out.setter
    def n_out(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def rtol(self) -> float:
        ...
    @rtol.setter
    def rtol(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def splitting_order(self) -> int:
        ...
    @splitting_order.setter
    def splitting_order(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def step(self) -> float:
        ...
    @step.setter
    def step(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def t_eval(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
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
class TorqueFreeSolution:
    def __init__(self, body: Body, omega0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"], t0: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> None:
        ...
    def omega(self, t: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex]) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def frequency(self) -> float:
        ...
    @property
    def is_constant(self) -> bool:
        ...
    @property
    def modulus_squared(self) -> float:
        ...
    @property
    def period(self) -> float:
        ...
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
def gyrostat_model(body: Body, torques: collections.abc.Iterable, attitude: bool) -> Model:
    ...
def jacobi_sn_cn_dn(u: typing.SupportsFloat | typing.SupportsIndex, m: typing.SupportsFloat | typing.SupportsIndex) -> typing.Annotated[list[float], "FixedSize(3)"]:
    """
    (sn, cn, dn)(u | m) (GSL)
    """
def lagrange_averaged_model(body: Body, mu: typing.SupportsFloat | typing.SupportsIndex, torques: collections.abc.Iterable) -> Model:
    ...
def lagrange_nutation(A: typing.SupportsFloat | typing.SupportsIndex, C: typing.SupportsFloat | typing.SupportsIndex, mu: typing.SupportsFloat | typing.SupportsIndex, G_z: typing.SupportsFloat | typing.SupportsIndex, H: typing.SupportsFloat | typing.SupportsIndex, r: typing.SupportsFloat | typing.SupportsIndex) -> LagrangeNutation:
    ...
def lagrange_nutation_table(A: typing.SupportsFloat | typing.SupportsIndex, C: typing.SupportsFloat | typing.SupportsIndex, mu: typing.SupportsFloat | typing.SupportsIndex, G_z: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], H: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], r: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex]) -> numpy.typing.NDArray[numpy.float64]:
    """
    Rows (u1, u2, u3, m, alpha, v, period) for each (G_z, H, r).
    """
def lagrange_top_model(body: Body, mu: typing.SupportsFloat | typing.SupportsIndex, torques: collections.abc.Iterable) -> Model:
    ...
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
def torque_free_model(body: Body, attitude: bool = False) -> Model:
    ...
__version__: str = '0.1.0'
large: float = 10.0
max_output_bytes: float = 2147483648.0
simd_instruction_set: str
simd_lanes: int
small: float = 0.1
taylor_kernel: str
torque_types: list = [ConstantTorque, LinearDamping, ResistiveMedium, ViscousCavity, MovingMassDamper, GravityGradient, MagneticTorque, DipoleFieldTorque, InertialTorque, CustomTorque]
