"""Kinematics of the planar 5R symmetrical parallel mechanism (thesis sec. 3.7, Figs 10–11).

Leg κ (κ = 1, 2) has the parameter vector of Eq 21, ``φκ = [lκ, Lκ, Aκx, Aκy, kκ, γκ]``: the
proximal link ``l`` turns about the base point ``A`` by the active angle
``θ = k ψ + γ`` (Eq 20, ``ψ`` is the joint reading) and the distal link ``L`` joins its elbow
``B = A + l (cos θ, sin θ)`` to the end-effector point ``P`` (Eq 23: ``|P − B| = L``).

Modes are explicit: the *working mode* ``σκ = ±1`` of a leg picks the elbow side
(``θ = atan2(P − A) + σ acos(…)``: +1 puts the elbow counter-clockwise of the line A→P);
the *assembly mode* ``±1`` picks the side of the line B1→B2 on which P lies (+1: to its left).

A leg is the RR dyad of :mod:`mechlib.dyad`, whose formulas (reach, active angle,
reading, identification Jacobian) this chapter calls after checking its input.
"""

from __future__ import annotations

import numpy as np

from mechlib import dyad
from mechlib.params import check_choice, check_float, check_matrix

PARAM_NAMES: tuple[str, ...] = ("l", "L", "Ax", "Ay", "k", "gamma")
"""Order of a leg's parameters (Eq 21)."""
N_LEG_PARAMS = len(PARAM_NAMES)
NOMINAL_MODES: tuple[int, int] = (1, -1)
"""Working modes of legs 1 and 2 for the thesis's mechanism: both elbows outward (Fig 10)."""
NOMINAL_ASSEMBLY = 1
"""End-effector above the elbows (Fig 10)."""
SINGULAR_TOL = 1e-6
"""Smallest |sine| of a link angle (see :func:`singularity_measures`) accepted as a regular pose:
:func:`check_regular`'s default, and the serial-singularity guard of the identification
Jacobian (``min_sine`` of :func:`mechlib.dyad.jacobian`)."""


def leg_keys(leg: int) -> tuple[str, ...]:
    """Table 7 names of leg ``leg``'s parameters, in Eq 21 order."""
    check_choice("leg", leg, (1, 2))
    return (f"l{leg}", f"L{leg}", f"A{leg}x", f"A{leg}y", f"k{leg}", f"gamma{leg}")


def leg_vector(values: dict[str, float], leg: int) -> np.ndarray:
    """Leg parameter vector (Eq 21 order) from a dict keyed like Table 7 (``"A1x"``, ``"k2"``).

    Parameters
    ----------
    values : dict
        Keys ``l{κ}``, ``L{κ}``, ``A{κ}x``, ``A{κ}y``, ``k{κ}``, ``gamma{κ}``.
    leg : {1, 2}
    """
    return np.array([float(values[k]) for k in leg_keys(leg)])


def check_leg(phi: object, name: str = "phi") -> np.ndarray:
    """Validate a leg parameter vector: positive lengths, non-zero gain, finite numbers.

    Examples
    --------
    >>> check_leg([1.2, -1.0, -0.5, 0.0, 1.0, 0.0])
    Traceback (most recent call last):
    ...
    ValueError: phi.L must be > 0.0, got -1.0
    """
    p = np.asarray(phi, dtype=float)
    if p.shape != (N_LEG_PARAMS,):
        raise ValueError(
            f"{name} must have {N_LEG_PARAMS} entries {PARAM_NAMES}, got shape {p.shape}"
        )
    if not np.all(np.isfinite(p)):
        raise ValueError(f"{name} must be finite, got {p}")
    check_float(f"{name}.l", p[0], low=0.0, low_open=True)
    check_float(f"{name}.L", p[1], low=0.0, low_open=True)
    if p[4] == 0:
        raise ValueError(f"{name}.k (joint gain) must be non-zero, got 0")
    return p


def check_points(points: object) -> np.ndarray:
    """End-effector points as a float array (n, 2); one point (2,) becomes (1, 2)."""
    p = np.asarray(points, dtype=float)
    return check_matrix("points", p[None, :] if p.ndim == 1 else p, shape=(None, 2))


def check_mode(name: str, mode: object) -> int:
    """A working or assembly mode: 1 or -1."""
    return int(check_choice(name, mode, (1, -1)))


def joint_reading(points: object, phi: object, mode: int) -> np.ndarray:
    """Joint reading ψ = (θ − γ)/k of one leg for end-effector points (the function gκ, Eq 13):
    :func:`mechlib.dyad.reading` on checked input.

    θ is wrapped to the branch nearest the offset γ so that ψ is continuous over the workspace.

    Parameters
    ----------
    points : array_like, shape (n, 2) or (2,)
    phi : array_like, shape (6,)
        Leg parameters (Eq 21).
    mode : {1, -1}
        Working mode.

    Returns
    -------
    numpy.ndarray, shape (n,)

    Raises
    ------
    ValueError
        Invalid parameters or mode, or a point outside the leg's reach (the point is named).

    Examples
    --------
    >>> phi1 = [1.2, 1.0, -0.5, 0.0, 1.0, 0.0]  # l, L, Ax, Ay, k, γ (Eq 21)
    >>> joint_reading([[5.0, 5.0]], phi1, mode=1)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: point #0 [5.0, 5.0] is out of the leg's reach, ... = [0.2, 2.2] m
    >>> joint_reading([[0.0, 1.5]], phi1, mode=0)
    Traceback (most recent call last):
    ...
    ValueError: mode must be one of [1, -1], got 0
    """
    phi = check_leg(phi)
    mode = check_mode("mode", mode)
    return dyad.reading(check_points(points), phi, mode)


def elbow(psi: object, phi: object) -> np.ndarray:
    """Elbow points B = A + l (cos θ, sin θ) for joint readings ψ."""
    return dyad.elbow(psi, check_leg(phi))


def forward(
    psi1: object, psi2: object, phi1: object, phi2: object, assembly: int = NOMINAL_ASSEMBLY
) -> np.ndarray:
    """End-effector points from joint readings (forward kinematics, circle intersection).

    Raises
    ------
    ValueError
        If the distal links cannot close the loop for some reading (the index is named).

    Examples
    --------
    The readings of two points (inverse kinematics, both elbows outward) give the points back,
    and each distal link closes the loop, ``|P − Bκ| = Lκ`` (Eq 23):

    >>> phi1 = [1.2, 1.0, -0.5, 0.0, 1.0, 0.0]  # l, L, Ax, Ay, k, γ (Eq 21)
    >>> phi2 = [1.2, 1.0, 0.5, 0.0, 1.0, 0.0]
    >>> p = np.array([[0.0, 1.5], [0.3, 1.2]])
    >>> psi1, psi2 = joint_reading(p, phi1, mode=1), joint_reading(p, phi2, mode=-1)
    >>> bool(np.allclose(forward(psi1, psi2, phi1, phi2), p))
    True
    >>> bool(np.allclose(np.hypot(*(p - elbow(psi1, phi1)).T), 1.0))
    True
    >>> bool(np.allclose(np.hypot(*(p - elbow(psi2, phi2)).T), 1.0))
    True
    """
    assembly = check_mode("assembly", assembly)
    phi1, phi2 = check_leg(phi1, "phi1"), check_leg(phi2, "phi2")
    b1, b2 = elbow(psi1, phi1), elbow(psi2, phi2)
    d = b2 - b1
    dist = np.hypot(d[:, 0], d[:, 1])
    r1, r2 = phi1[1], phi2[1]
    a = (dist**2 + r1**2 - r2**2) / (2 * dist)
    h2 = r1**2 - a**2
    bad = ~(h2 >= -dyad.REACH_TOL)
    if np.any(bad):
        i = int(np.argmax(bad))
        raise ValueError(f"joint readings #{i} cannot be assembled: elbows {dist[i]:g} apart")
    h = np.sqrt(np.clip(h2, 0.0, None))
    u = d / dist[:, None]
    normal = np.column_stack([-u[:, 1], u[:, 0]])  # left of B1→B2
    return b1 + a[:, None] * u + assembly * h[:, None] * normal


def singularity_measures(
    points: object, phi1: object, phi2: object, modes=NOMINAL_MODES
) -> dict[str, np.ndarray]:
    """Sines of the angles whose zeros are the singularities, at end-effector points.

    Returns
    -------
    dict
        ``serial1``, ``serial2``: sin of the angle between proximal and distal link of each leg
        (zero when a leg is stretched or folded: serial singularity); ``parallel``: sin of the
        angle between the two distal links (zero when they are aligned: parallel singularity).
    """
    p = check_points(points)
    out = {}
    elbows = []
    for name, phi, mode in (("serial1", phi1, modes[0]), ("serial2", phi2, modes[1])):
        phi = check_leg(phi)
        th = dyad.active_angle(p, phi, check_mode("mode", mode))
        b = np.column_stack([phi[2] + phi[0] * np.cos(th), phi[3] + phi[0] * np.sin(th)])
        pa, pb = b - phi[2:4], p - b
        out[name] = (pa[:, 0] * pb[:, 1] - pa[:, 1] * pb[:, 0]) / (phi[0] * phi[1])
        elbows.append((b, phi[1]))
    (b1, r1), (b2, r2) = elbows
    d1, d2 = p - b1, p - b2
    out["parallel"] = (d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]) / (r1 * r2)
    return out


def check_regular(
    points: object, phi1: object, phi2: object, modes=NOMINAL_MODES, min_sine: float = SINGULAR_TOL
) -> np.ndarray:
    """Return ``points`` if no pose is singular; otherwise raise naming the first singular one.

    Raises
    ------
    ValueError
        If a point is outside the workspace, or if a serial (leg stretched or folded) or
        parallel (distal links aligned) singularity measure has ``|sine| < min_sine``.
    """
    min_sine = check_float("min_sine", min_sine, low=0.0)
    p = check_points(points)
    for name, value in singularity_measures(p, phi1, phi2, modes).items():
        bad = np.abs(value) < min_sine
        if np.any(bad):
            i = int(np.argmax(bad))
            kind = (
                "parallel (distal links aligned)"
                if name == "parallel"
                else (f"serial (leg {name[-1]} stretched or folded)")
            )
            raise ValueError(
                f"point #{i} {p[i].tolist()} is at a {kind} singularity: |sine| = "
                f"{abs(value[i]):.2g}, allowed |sine| >= {min_sine:g}"
            )
    return p


def in_circle_grid(
    center: object, radius: float, n_rings: int = 40, n_angles: int = 181
) -> np.ndarray:
    """Points filling a disc on a polar grid (center included)."""
    c = np.asarray(center, dtype=float)
    radius = check_float("radius", radius, low=0.0)
    r = np.linspace(0, radius, n_rings)[1:]
    t = np.linspace(0, 2 * np.pi, n_angles, endpoint=False)
    rr, tt = np.meshgrid(r, t)
    pts = np.column_stack([c[0] + (rr * np.cos(tt)).ravel(), c[1] + (rr * np.sin(tt)).ravel()])
    return np.vstack([c[None, :], pts])


def disc_is_regular(
    center: object,
    radius: float,
    phi1: object,
    phi2: object,
    modes=NOMINAL_MODES,
    n_rings: int = 40,
    n_angles: int = 181,
) -> bool:
    """True if every grid point of the disc is reachable and no singularity measure changes sign."""
    pts = in_circle_grid(center, radius, n_rings, n_angles)
    for phi in (phi1, phi2):
        if np.any(np.abs(dyad.reach_cosine(pts, check_leg(phi))) >= 1):
            return False
    meas = singularity_measures(pts, phi1, phi2, modes)
    return all(np.all(m > 0) or np.all(m < 0) for m in meas.values())


def miw_numeric(
    phi1: object,
    phi2: object,
    modes=NOMINAL_MODES,
    y_range=(0.2, 2.0),
    n_centers: int = 181,
    tol: float = 1e-5,
) -> dict[str, float]:
    """Maximal inscribed workspace found numerically: the largest singularity-free disc.

    Centres are searched on the mechanism's axis of symmetry (x midway between the bases) over
    ``y_range``; for each, the radius is found by bisection on :func:`disc_is_regular`, and the
    best centre is refined by a golden-section search.

    Returns
    -------
    dict
        ``cx``, ``cy``, ``radius``.
    """
    phi1, phi2 = check_leg(phi1, "phi1"), check_leg(phi2, "phi2")
    cx = 0.5 * (phi1[2] + phi2[2])
    r_max = phi1[0] + phi1[1]

    def radius_at(cy: float) -> float:
        if not disc_is_regular((cx, cy), 0.0, phi1, phi2, modes, 2, 4):
            return 0.0
        lo, hi = 0.0, r_max
        while hi - lo > tol:
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if disc_is_regular((cx, cy), mid, phi1, phi2, modes) else (lo, mid)
        return lo

    ys = np.linspace(*y_range, n_centers)
    radii = np.array([radius_at(y) for y in ys])
    i = int(np.argmax(radii))
    a, b = ys[max(i - 1, 0)], ys[min(i + 1, len(ys) - 1)]
    g = (np.sqrt(5) - 1) / 2
    while b - a > tol:
        c1, c2 = b - g * (b - a), a + g * (b - a)
        if radius_at(c1) >= radius_at(c2):
            b = c2
        else:
            a = c1
    cy = 0.5 * (a + b)
    return {"cx": float(cx), "cy": float(cy), "radius": float(radius_at(cy))}


def miw_closed_form(l: float, L: float, a: float) -> dict[str, float]:
    """Closed-form MIW of a symmetric 5R (bases at (±a, 0), both elbows outward, P above).

    Derivation (see the chapter): on the symmetry axis the parallel singularity (distal links
    aligned, here horizontal) lies at ``y_p = sqrt(l² − (L − a)²)``; the outer workspace boundary
    is at distance ``l + L`` from each base. A disc centred at ``(0, c)`` is bounded by
    ``c − y_p`` below and ``l + L − sqrt(a² + c²)`` outward; equating the two gives
    ``c = ((l + L + y_p)² − a²) / (2 (l + L + y_p))`` and ``r = c − y_p``. Valid when
    ``L > a`` and ``l > L − a`` (the singular point exists) and the inner boundary
    ``sqrt(a² + c²) − |L − l|`` is not binding.

    Examples
    --------
    The closed-form disc is the largest regular one: 1 % smaller it is regular, 1 % larger it
    crosses the parallel singularity.

    >>> miw = miw_closed_form(l=1.2, L=1.0, a=0.5)
    >>> abs(miw["cy"] - miw["radius"] - miw["y_parallel"]) < 1e-12  # touches it on the axis
    True
    >>> phi1, phi2 = [1.2, 1.0, -0.5, 0.0, 1.0, 0.0], [1.2, 1.0, 0.5, 0.0, 1.0, 0.0]
    >>> disc_is_regular((0.0, miw["cy"]), 0.99 * miw["radius"], phi1, phi2)
    True
    >>> disc_is_regular((0.0, miw["cy"]), 1.01 * miw["radius"], phi1, phi2)
    False
    >>> miw_closed_form(l=0.4, L=1.0, a=0.5)
    Traceback (most recent call last):
    ...
    ValueError: closed form needs L > a and l > L - a, got l=0.4, L=1.0, a=0.5
    """
    l = check_float("l", l, low=0.0, low_open=True)
    L = check_float("L", L, low=0.0, low_open=True)
    a = check_float("a", a, low=0.0, low_open=True)
    if not (L > a and l > L - a):
        raise ValueError(f"closed form needs L > a and l > L - a, got l={l}, L={L}, a={a}")
    y_p = np.sqrt(l**2 - (L - a) ** 2)
    s = l + L + y_p
    c = (s**2 - a**2) / (2 * s)
    r = c - y_p
    inner = np.sqrt(a**2 + c**2) - abs(L - l)
    if inner < r:
        raise ValueError("closed form not valid: the inner workspace boundary binds first")
    return {"cx": 0.0, "cy": float(c), "radius": float(r), "y_parallel": float(y_p)}
