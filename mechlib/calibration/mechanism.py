"""A parallel mechanism as a set of legs, for leg-wise (divide and conquer) calibration.

Thesis sec. 3.5: leg κ has a parameter vector φκ (Eq 12) and an inverse-kinematics function
``gκ(φκ, r) → qκ`` from the end-effector pose ``r`` to its active joint reading (Eq 13). A
:class:`Leg` carries φκ's names, units and nominal values, ``gκ`` and its identification
Jacobian ``Cκ = ∂gκ/∂φκ`` (Eq 17); a :class:`Mechanism` is its legs, the pose coordinates
and the region of the workspace where calibration poses may lie. Forward kinematics — needed only
to simulate measurements — is a vectorised Newton iteration on ``g(φ, r) = q`` unless the
mechanism supplies a closed form.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from mechlib.params import check_float

#: gκ(φκ, poses (N, d)) → readings (N,)
LegFunction = Callable[[np.ndarray, np.ndarray], np.ndarray]
#: Cκ(φκ, poses (N, d)) → (N, nκ)
LegJacobian = Callable[[np.ndarray, np.ndarray], np.ndarray]
#: forward(φ list, readings (N, n_limbs), guess poses (N, d)) → poses (N, d)
ForwardFunction = Callable[[Sequence[np.ndarray], np.ndarray, np.ndarray], np.ndarray]

#: Relative finite-difference step of the pose Jacobian ∂g/∂r (central differences).
POSE_STEP = 1e-6
#: Newton iterations of the generic forward kinematics, and its stopping step [pose units].
FORWARD_MAX_ITER = 50
FORWARD_TOL = 1e-13
#: Iterations between refreshes of the pose Jacobian in the forward kinematics (chord method).
JACOBIAN_EVERY = 12


@dataclass(frozen=True)
class Leg:
    """One leg: φκ (names, units, nominal values), gκ and Cκ.

    Parameters
    ----------
    names : tuple of str
        Parameter names, e.g. ``("l1", "L1", "A1x", …)``.
    units : tuple of str
        One unit per parameter (``"m"``, ``"rad"``, ``"-"``).
    nominal : numpy.ndarray, shape (nκ,)
    ik : callable
        ``ik(phi, poses)`` → joint readings (N,): the function gκ.
    jacobian : callable
        ``jacobian(phi, poses)`` → (N, nκ): ``∂gκ/∂φκ``.
    """

    names: tuple[str, ...]
    units: tuple[str, ...]
    nominal: np.ndarray
    ik: LegFunction
    jacobian: LegJacobian

    def __post_init__(self) -> None:
        nom = np.asarray(self.nominal, dtype=float)
        if nom.ndim != 1 or not (len(self.names) == len(self.units) == nom.size > 0):
            raise ValueError(
                f"a leg needs as many names, units and nominal values (at least one), got "
                f"{len(self.names)} names, {len(self.units)} units, nominal shape {nom.shape}"
            )
        if not np.all(np.isfinite(nom)):
            raise ValueError(f"nominal parameters of leg {self.names} must be finite, got {nom}")
        if len(set(self.names)) != len(self.names):
            raise ValueError(f"parameter names of a leg must be distinct, got {self.names}")
        object.__setattr__(self, "nominal", nom)

    @property
    def size(self) -> int:
        """Number of parameters nκ."""
        return len(self.names)

    def check_phi(self, phi: object) -> np.ndarray:
        """``phi`` as an array of this leg's size, or ``ValueError`` naming the leg."""
        p = np.asarray(phi, dtype=float)
        if p.shape != (self.size,) or not np.all(np.isfinite(p)):
            raise ValueError(
                f"parameters of the leg {self.names} must be {self.size} finite numbers, got "
                f"shape {p.shape}"
            )
        return p


@dataclass(frozen=True)
class Mechanism:
    """A parallel mechanism: legs, pose coordinates and the calibration region.

    Parameters
    ----------
    name : str
    legs : tuple of Leg
        Every leg has the same parameter count and units (a symmetrical mechanism, sec. 3.5).
    pose_names, pose_units : tuple of str
        Coordinates of the end-effector pose r (e.g. ``("x", "y", "phi")``, ``("m", "m", "rad")``).
    region : callable
        ``region(poses)`` → bool mask: inside the singularity-free region where calibration and
        evaluation poses lie (e.g. the MIW, a box).
    region_text : str
        The region in words, for error messages.
    min_conditioning : float
        Smallest accepted inverse condition number of the pose Jacobian ∂g/∂r (angles scaled by
        ``length_scale``): a pose below it is too close to a parallel singularity.
    length_scale : float
        Metres per radian used to compare position and orientation columns [m].
    forward : callable, optional
        Closed-form forward kinematics; default: Newton on ``g(φ, r) = q``.
    """

    name: str
    legs: tuple[Leg, ...]
    pose_names: tuple[str, ...]
    pose_units: tuple[str, ...]
    region: Callable[[np.ndarray], np.ndarray]
    region_text: str
    min_conditioning: float = 1e-3
    length_scale: float = 1.0
    forward: ForwardFunction | None = None

    def __post_init__(self) -> None:
        if len(self.legs) < 1:
            raise ValueError(f"{self.name}: a mechanism needs at least one leg, got none")
        first = self.legs[0]
        for i, leg in enumerate(self.legs):
            if leg.size != first.size or leg.units != first.units:
                raise ValueError(
                    f"{self.name}: leg {i + 1} has {leg.size} parameters in units {leg.units}; "
                    f"a symmetrical mechanism's legs must all match leg 1's {first.size} "
                    f"parameters in {first.units}"
                )
        names = [n for leg in self.legs for n in leg.names]
        if len(set(names)) != len(names):
            raise ValueError(f"{self.name}: parameter names must be unique across legs: {names}")
        if len(self.pose_names) != len(self.pose_units) or not self.pose_names:
            raise ValueError(
                f"{self.name}: pose_names {self.pose_names} and pose_units {self.pose_units} "
                "must have the same non-zero length"
            )
        check_float("min_conditioning", self.min_conditioning, low=0.0, high=1.0)
        check_float("length_scale", self.length_scale, low=0.0, low_open=True)

    @property
    def n_limbs(self) -> int:
        """Number of legs."""
        return len(self.legs)

    @property
    def dof(self) -> int:
        """Number of pose coordinates d."""
        return len(self.pose_names)

    @property
    def names(self) -> tuple[str, ...]:
        """Every parameter name, leg after leg."""
        return tuple(n for leg in self.legs for n in leg.names)

    @property
    def nominal(self) -> tuple[np.ndarray, ...]:
        """Nominal φκ of every leg."""
        return tuple(leg.nominal for leg in self.legs)

    @property
    def angular(self) -> np.ndarray:
        """Mask of the pose coordinates in radians."""
        return np.array([u == "rad" for u in self.pose_units])


def check_phis(mech: Mechanism, phis: Sequence[object]) -> tuple[np.ndarray, ...]:
    """Validate one parameter vector per leg."""
    if len(phis) != mech.n_limbs:
        raise ValueError(f"{mech.name} needs {mech.n_limbs} parameter vectors, got {len(phis)}")
    return tuple(leg.check_phi(p) for leg, p in zip(mech.legs, phis, strict=True))


def check_poses(mech: Mechanism, poses: object, name: str = "poses") -> np.ndarray:
    """``poses`` as (N, d) if every pose is inside the calibration region, else ``ValueError``
    naming the first pose outside and the region."""
    r = np.asarray(poses, dtype=float)
    r = r[None, :] if r.ndim == 1 else r
    if r.ndim != 2 or r.shape[1] != mech.dof or not np.all(np.isfinite(r)):
        raise ValueError(
            f"{name} must be finite (N, {mech.dof}) poses {mech.pose_names}, got shape {r.shape}"
        )
    inside = np.asarray(mech.region(r), dtype=bool)
    if not np.all(inside):
        i = int(np.argmin(inside))
        raise ValueError(
            f"{name} #{i} {np.round(r[i], 6).tolist()} is outside the calibration region of "
            f"{mech.name}: allowed {mech.region_text}"
        )
    return r


def readings(mech: Mechanism, phis: Sequence[object], poses: np.ndarray) -> np.ndarray:
    """Joint readings of every leg at every pose, shape (N, n_limbs)."""
    phis = check_phis(mech, phis)
    return np.column_stack([leg.ik(p, poses) for leg, p in zip(mech.legs, phis, strict=True)])


def pose_jacobian(mech: Mechanism, phis: Sequence[object], poses: np.ndarray) -> np.ndarray:
    """∂q/∂r at every pose by central differences, shape (N, n_limbs, d)."""
    r = np.asarray(poses, dtype=float)
    cols = []
    for i in range(mech.dof):
        h = np.zeros(mech.dof)
        h[i] = POSE_STEP
        cols.append((readings(mech, phis, r + h) - readings(mech, phis, r - h)) / (2 * POSE_STEP))
    return np.stack(cols, axis=2)


def conditioning(mech: Mechanism, phis: Sequence[object], poses: np.ndarray) -> np.ndarray:
    """Inverse condition number of ∂q/∂r (angles scaled by ``length_scale``) at every pose:
    0 at a parallel (type 2) singularity."""
    j = pose_jacobian(mech, phis, poses) / np.where(mech.angular, mech.length_scale, 1.0)
    s = np.linalg.svd(j, compute_uv=False)
    return s[:, -1] / s[:, 0]


def regular(mech: Mechanism, phis: Sequence[object], poses: np.ndarray) -> np.ndarray:
    """Mask of the poses inside the region, reachable by every leg and well conditioned."""
    r = np.atleast_2d(np.asarray(poses, dtype=float))
    ok = np.asarray(mech.region(r), dtype=bool)
    try:  # all at once when every leg reaches every pose
        ok[ok] = conditioning(mech, phis, r[ok]) >= mech.min_conditioning
        return ok
    except ValueError:
        pass
    for i in np.flatnonzero(ok):
        try:
            ok[i] = conditioning(mech, phis, r[i : i + 1])[0] >= mech.min_conditioning
        except ValueError:  # a leg cannot reach the pose
            ok[i] = False
    return ok


def forward(
    mech: Mechanism,
    phis: Sequence[object],
    q: object,
    guess: object,
    jacobian: np.ndarray | None = None,
) -> np.ndarray:
    """Poses reached for joint readings ``q`` (N, n_limbs): forward kinematics.

    The mechanism's closed form if it has one, else Newton's method on ``g(φ, r) = q`` from
    ``guess`` (the branch of the guess is kept), refreshing the finite-difference Jacobian every
    ``JACOBIAN_EVERY`` iterations.

    Raises
    ------
    RuntimeError
        If Newton's method does not converge for some pose (its index is named).
    """
    phis = check_phis(mech, phis)
    q = np.atleast_2d(np.asarray(q, dtype=float))
    r = np.atleast_2d(np.asarray(guess, dtype=float)).copy()
    if mech.forward is not None:
        return mech.forward(phis, q, r)
    step = np.full(len(r), np.inf)
    for it in range(FORWARD_MAX_ITER):
        if it % JACOBIAN_EVERY == 0:  # chord method: the Jacobian is refreshed now and then
            given = it == 0 and jacobian is not None
            jac = np.asarray(jacobian, dtype=float) if given else pose_jacobian(mech, phis, r)
        res = readings(mech, phis, r) - q
        dr = np.linalg.solve(jac, res[:, :, None])[:, :, 0]
        r -= dr
        step = np.max(np.abs(dr), axis=1)
        if np.all(step < FORWARD_TOL):
            return r
    i = int(np.argmax(step))
    raise RuntimeError(f"{mech.name}: forward kinematics did not converge for readings #{i}")


def candidate_poses(
    mech: Mechanism, low: object, high: object, n: int, rng: np.random.Generator
) -> np.ndarray:
    """``n`` seeded random poses, uniform in the box [low, high], kept if :func:`regular` at the
    nominal parameters (so fewer than ``n`` may be returned)."""
    lo, hi = np.asarray(low, dtype=float), np.asarray(high, dtype=float)
    if lo.shape != (mech.dof,) or hi.shape != (mech.dof,) or np.any(hi <= lo):
        raise ValueError(f"low < high must be two vectors of {mech.dof} pose coordinates")
    r = lo + (hi - lo) * rng.random((n, mech.dof))
    return r[regular(mech, mech.nominal, r)]


def pose_errors(
    mech: Mechanism,
    phis_model: Sequence[object],
    phis_real: Sequence[object],
    targets: object,
    jacobian: np.ndarray | None = None,
) -> np.ndarray:
    """Pose error (reached − target) when commanding ``targets`` with a model, shape (N, d).

    The controller computes joint readings with the model's inverse kinematics; the real
    mechanism reaches the forward kinematics of the real parameters.
    """
    t = check_poses(mech, targets, "targets")
    return forward(mech, phis_real, readings(mech, phis_model, t), t) - t


def simulate(
    mech: Mechanism,
    phis_real: Sequence[object],
    targets: object,
    sigma: float,
    rng: np.random.Generator,
    jacobian: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Simulated calibration measurements (thesis sec. 3.7 items 8–9) at ``targets``.

    The controller commands the nominal inverse kinematics of each target; the real mechanism
    reaches the forward kinematics of the real parameters; every pose coordinate and every
    joint reading is measured with Gaussian noise of standard deviation ``sigma`` (m, rad).

    Returns
    -------
    (poses (N, d), readings (N, n_limbs))

    Raises
    ------
    ValueError
        If ``sigma`` < 0 or a target lies outside the calibration region.
    """
    sigma = check_float("sigma [m, rad]", sigma, low=0.0)
    t = check_poses(mech, targets, "targets")
    q = readings(mech, mech.nominal, t)
    r = forward(mech, phis_real, q, t, jacobian)
    return r + rng.normal(0.0, sigma, r.shape), q + rng.normal(0.0, sigma, q.shape)
