"""The interface every valvetrain model implements, and the factory that picks one.

A valvetrain model turns a cam, a parameter set and a tribology law into a first-order
system y' = f(t, y) with y = [q, q̇, W_cam, D] (generalised displacements and velocities,
then the cam-work and dissipation accumulators), which :func:`simulate_valvetrain`
integrates, samples, balances and scans for events without knowing which model it is.

Implementations: :class:`~tribodyn.valvetrain.model.ValvetrainModel` (lumped masses,
:class:`~tribodyn.valvetrain.parameters.ValvetrainParameters`) and
:class:`~tribodyn.valvetrain.flexible_model.FlexibleValvetrainModel` (Craig–Bampton
bodies, :class:`~tribodyn.valvetrain.flexible.FlexibleValvetrain`). :func:`system_class`
asks each registered class whether it ``handles`` the parameter object, so a new model is
one class plus one entry in :data:`SYSTEMS`.
"""

from __future__ import annotations

from typing import Any, Protocol, runtime_checkable

import numpy as np

from .._validation import InputError
from .cams import CamProfile
from .flexible_model import FlexibleValvetrainModel
from .model import ValvetrainModel
from .tribology import TribologyModel

__all__ = ["ValvetrainSystem", "SystemClass", "SYSTEMS", "system_class"]


@runtime_checkable
class ValvetrainSystem(Protocol):
    """What the time integration needs from a valvetrain model (SI units throughout).

    Attributes: ``cam``, ``trib`` (tribology), ``w`` (cam speed ω [rad/s]), ``theta0``
    (cam angle at t = 0 [rad]), ``n`` (number of generalised coordinates; the state has
    2n + 2 entries, 2n + 3 with ``film_state``), ``d_seat`` (static seat compression [m]:
    valve lift = y[1] − d_seat), ``has_film`` (the tribology has a film law),
    ``film_state`` (the film h is the last state, ``h_supply`` its supply bound [m]),
    ``compilable`` (a compiled right-hand side exists:
    :func:`~tribodyn.valvetrain.compiled.compiled_model`)."""

    cam: CamProfile
    trib: TribologyModel
    w: float
    theta0: float
    n: int
    d_seat: float
    has_film: bool
    film_state: bool
    h_supply: float
    compilable: bool

    @property
    def PARAMS(self) -> type:
        """The parameter class it is built from."""
        ...

    @classmethod
    def handles(cls, params: Any) -> bool:
        """True if this model is built from ``params``."""
        ...

    def rhs(self, t: float, y: np.ndarray) -> np.ndarray:
        """dy/dt."""
        ...

    def jacobian(self, t: float, y: np.ndarray) -> np.ndarray:
        """∂(dy/dt)/∂y."""
        ...

    def evaluate(self, t: float, y: np.ndarray, jac: bool = False) -> dict:
        """Forces and kinematics at one state (keys s, s1, s2, R, ue, us, Fc, P, film,
        Ftv, Fs, Fb, acc, Fseg)."""
        ...

    def energy(self, t: float, y: np.ndarray, evaluated: dict | None = None) -> tuple:
        """(kinetic, elastic) energy [J] relative to static equilibrium."""
        ...

    def static_state(self) -> np.ndarray:
        """Static equilibrium on the base circle (the initial state)."""
        ...

    def film(self, t: float, force: float, ue: float, R: float) -> tuple[float, float]:
        """Series film h [m] and dh/dP at the cam contact (0, 0 without a film law)."""
        ...

    def lobe_angle(self, t: float, y: np.ndarray) -> float:
        """Cam angle of the lobe at the contact [rad] (θ₀ + ωt for a rigid camshaft)."""
        ...

    def unresolved_clash(self, Y: np.ndarray) -> float:
        """Largest coil-clash overlap [m] the model cannot represent (−inf if none)."""
        ...


class SystemClass(Protocol):
    """A valvetrain model class as :func:`system_class` returns it: ``PARAMS`` (the parameter
    class it is built from), ``handles(params)`` and the constructor."""

    @property
    def PARAMS(self) -> type: ...

    def handles(self, params: Any) -> bool: ...

    def __call__(
        self,
        cam: CamProfile,
        params: Any,
        cam_speed: float,
        tribology: TribologyModel,
        /,
        start_angle: float = 0.0,
    ) -> ValvetrainSystem: ...


#: The valvetrain models, asked in this order by :func:`system_class`.
SYSTEMS: list[SystemClass] = [ValvetrainModel, FlexibleValvetrainModel]


def system_class(params: Any) -> SystemClass:
    """The valvetrain model class that handles ``params`` (see :data:`SYSTEMS`), called
    as ``cls(cam, params, cam_speed, tribology, start_angle=…)``."""
    for cls in SYSTEMS:
        if cls.handles(params):
            return cls
    names = " or a ".join(c.PARAMS.__name__ for c in SYSTEMS)
    raise InputError(f"params must be a {names} (got {type(params).__name__})")
