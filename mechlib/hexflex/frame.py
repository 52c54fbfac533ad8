"""Reduced beam model of the HexFlex: six L-shaped beams carrying one rigid body.

The HexFlex (:class:`~mechlib.hexflex.geometry.HexFlexGeometry`) as a frame of
:mod:`mechlib.hexflex.frame_solver`: the stage and tabs are one rigid body whose
*master* node sits at the stage centre; the six beams' attachment points are its *slaves*. Each
beam is a D1 segment (``beam_width``) from the tab's side to the corner and a radial segment
(``radial_width``) from the corner to the clamp, on the centre lines of ``geometry.py``.

Units: mm, N, MPa; compliances in µm/N and µrad/N as the FE model's. A frame ignores the corner
blocks, the joints' finite widths and the stage's own compliance: it is a fast first guess
(:func:`prefit`) and the Jacobian of the FE identification (:mod:`mechlib.hexflex.identify`),
not a replacement for FE.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from functools import partial

import numpy as np
from scipy.optimize import least_squares

from mechlib.hexflex import geometry as geo
from mechlib.hexflex.frame_solver import NDOF, Frame, check_material, solve_frame
from mechlib.hexflex.geometry import AL7075_POISSON, AL7075_YOUNG_MPA
from mechlib.hexflex.identify import check_free, check_target, target_values
from mechlib.params import check_int

#: Unit conversions of the output: mm → µm, rad → µrad, and mm⁻¹ → m⁻¹.
UM_PER_MM, URAD_PER_RAD, MM_PER_M = 1e3, 1e6, 1e3
#: Residual [log units] of a geometry the constructor rejects (e¹⁰ ≈ 2·10⁴ times off).
INFEASIBLE_RESIDUAL = 10.0
#: Weight of the log change from the start in :func:`prefit` (see there): small against the
#: magnitudes' sensitivities (singular values ≥ 0.1), so the fit still meets them to ~1e-6.
ANCHOR_WEIGHT = 1e-3
#: Stopping tolerances of :func:`prefit`'s least squares: the anchored problem is well posed, so
#: it is solved to round-off rather than stopped where scipy's defaults (1e-8) would leave it.
PREFIT_TOLERANCES = {"ftol": 1e-14, "xtol": 1e-14, "gtol": 1e-14}
#: Stated agreement of the beam model with FE on the magnitudes of Eq 8 (largest relative
#: difference): with the real, flexible stage and tabs, and with them made nearly rigid (the beam
#: model's assumption). Set from the first comparison in the hexflex notebook, whose records
#: fail if a change pushes the model past them.
FE_TOLERANCE, STIFF_BODY_FE_TOLERANCE = 0.10, 0.05
#: Largest number of elements per beam segment.
MAX_ELEMENTS = 64


# --- HexFlex --------------------------------------------------------------------------------
def hexflex_frame(g: geo.HexFlexGeometry, n_elements: int = 1) -> Frame:
    """The HexFlex as a frame: node 0 the rigid body's master at the origin (the stage centre).

    Per beam (tab k, side σ = ±1, in the tab's ``(r, s)`` frame): attachment ``(ρ, σ s₀)`` (a
    slave of node 0) → corner ``(ρ, σ (s₀ + L₁))`` → clamp ``(ρ + L₂, σ (s₀ + L₁))``, each
    segment split into ``n_elements`` beams.

    Parameters
    ----------
    g : HexFlexGeometry
    n_elements : int
        Beam elements per segment, in [1, ``MAX_ELEMENTS``] (one is exact for nodal loads).

    Returns
    -------
    Frame
    """
    n_el = check_int("n_elements", n_elements, low=1, high=MAX_ELEMENTS)
    e_r, e_s = geo.tab_frames()
    nodes, elements, widths, slaves, clamped = [np.zeros(3)], [], [], [], []
    steps = np.linspace(0, 1, n_el + 1)[1:]
    for k in range(3):
        for sigma in (1.0, -1.0):
            attach = np.r_[g.beam_radius * e_r[k] + sigma * g.tab_half_width * e_s[k], 0.0]
            corner = np.r_[g.beam_radius * e_r[k] + sigma * g.corner_s * e_s[k], 0.0]
            clamp = np.r_[g.ground_radius * e_r[k] + sigma * g.corner_s * e_s[k], 0.0]
            slaves.append(len(nodes))
            nodes.append(attach)
            segments = ((attach, corner, g.beam_width), (corner, clamp, g.radial_width))
            for start, end, width in segments:
                for t in steps:
                    nodes.append(start + t * (end - start))
                    elements.append((len(nodes) - 2, len(nodes) - 1))
                    widths.append(width)
            clamped.append(len(nodes) - 1)
    depths = np.full(len(widths), g.thickness)
    return Frame(np.array(nodes), np.array(elements), np.array(widths), depths, tuple(clamped),
                 {0: tuple(slaves)})  # fmt: skip


def actuator_wrenches(g: geo.HexFlexGeometry) -> np.ndarray:
    """(6, 6) wrenches at the origin, ``[F; r × F]`` [N, N·mm], of the six unit actuator forces."""
    points = np.c_[geo.actuator_points(g), np.zeros(3)]
    forces = geo.actuator_directions()
    arms = np.repeat(points, 2, axis=0)
    return np.vstack([forces.T, np.cross(arms, forces).T])


def stage_compliance(
    g: geo.HexFlexGeometry,
    young: float = AL7075_YOUNG_MPA,
    poisson: float = AL7075_POISSON,
    shear: bool = True,
    n_elements: int = 1,
) -> np.ndarray:
    """(6, 6) compliance of the rigid body at the origin [mm, rad per N, N·mm] (symmetric)."""
    frame = hexflex_frame(g, n_elements)
    loads = np.zeros((NDOF, len(frame.nodes), NDOF))
    loads[:, 0, :] = np.eye(NDOF)
    return solve_frame(frame, young, poisson, loads, shear)[:, 0, :].T


def hexflex_frame_compliance(
    g: geo.HexFlexGeometry,
    young: float = AL7075_YOUNG_MPA,
    poisson: float = AL7075_POISSON,
    shear: bool = True,
    n_elements: int = 1,
) -> np.ndarray:
    """(6, 6) compliance [µm/N, µrad/N]: rows x, y, z, θx, θy, θz of the stage centre, columns
    the unit actuator forces T1D1, T1D2, T2D1, T2D2, T3D1, T3D2 (Eq 4), as the FE model's."""
    scale = np.r_[np.full(3, UM_PER_MM), np.full(3, URAD_PER_RAD)][:, None]
    return scale * (stage_compliance(g, young, poisson, shear, n_elements) @ actuator_wrenches(g))


def compliance_maker(young: float, poisson: float) -> Callable[[geo.HexFlexGeometry], np.ndarray]:
    """Geometry → :func:`hexflex_frame_compliance` for this material (the identification's)."""
    return partial(hexflex_frame_compliance, young=young, poisson=poisson)


def point_support_ratio(g: geo.HexFlexGeometry) -> float:
    """θx←T1D2 / z←T1D2 [rad/m] of the rigid body on six vertical point springs.

    Six identical springs k at the attachment points ``p_i`` (no rotational stiffness), a unit
    force along z at ``(0, R_t)`` (T1's external edge). Vertical balance: ``z = 1/(6k)`` (the
    points' centroid is the origin). Moment balance: the tilt stiffness is ``k Σ p_i p_iᵀ``; by
    the three-fold symmetry this 2 × 2 tensor is isotropic, ``k/2 Σ |p_i|² I = 3k(ρ² + s₀²) I``
    (each ``|p_i|² = ρ² + s₀²``), and the load's moment is ``M_x = R_t``, so
    ``θx = R_t / (3k(ρ² + s₀²))`` and ``θx / z = 2 R_t / (ρ² + s₀²)`` [mm⁻¹], ×1e3 for rad/m.
    Beams also resist the tilt by their rotational stiffness, which lowers the ratio in every
    case computed here (tests, and the hexflex notebook's FE); it is an estimate, not a proven
    bound — a beam end's lift-rotation coupling could in principle act the other way.
    """
    return 2 * g.tab_outer / (g.beam_radius**2 + g.tab_half_width**2) * MM_PER_M


def prefit(
    target: Sequence[float],
    start: geo.HexFlexGeometry,
    free: Sequence[str],
    young: float = AL7075_YOUNG_MPA,
    poisson: float = AL7075_POISSON,
    bounds: Mapping[str, tuple[float, float]] | None = None,
    shear: bool = True,
) -> tuple[geo.HexFlexGeometry, np.ndarray]:
    """Fit the ``free`` dimensions of ``start`` so the frame reaches the four ``target`` magnitudes.

    Least squares (scipy's ``dogbox``) on ``log(achieved / target)`` over the logs of the free
    dimensions, within ``bounds`` (default :data:`geometry.DIMENSION_BOUNDS`), plus
    :data:`ANCHOR_WEIGHT` times the log change from ``start``: where the four magnitudes do not
    fix every free dimension (five free), the fit is the member nearest ``start``, a unique point
    that round-off cannot move; where they do, the anchor moves the fit by O(weight²). Geometries
    the constructor rejects give a residual of :data:`INFEASIBLE_RESIDUAL` in every component.

    Parameters
    ----------
    target : sequence of 4 floats > 0
        x←T1D1 [µm/N], z←T1D2 [µm/N], θx←T1D2 [µrad/N], |θz←T1D1| [µrad/N].
    start : HexFlexGeometry
        Start point; the dimensions not in ``free`` (names to fit) stay fixed.
    free : sequence of str
    young, poisson, shear
        As in :func:`hexflex_frame_compliance`.
    bounds : mapping name -> (low, high), optional
        Bounds [mm] of the free dimensions; must contain ``start``'s values.

    Returns
    -------
    geometry : HexFlexGeometry
    achieved : ndarray (4,)
        The frame's magnitudes at ``geometry``.

    Raises
    ------
    ValueError
        Bad target, names, bounds or material constants.
    """
    tgt = check_target(target)
    free = check_free(free)
    young, poisson = check_material(young, poisson)
    bounds = geo.DIMENSION_BOUNDS if bounds is None else bounds
    lo, hi = np.array([bounds.get(n, (np.nan, np.nan)) for n in free], dtype=float).T
    if not np.all((lo > 0) & (lo < hi)):  # also catches a missing name (NaN)
        raise ValueError(f"bounds must give 0 < low < high [mm] for each of {free}, got {bounds}")
    x0 = np.log([getattr(start, n) for n in free])
    if np.any(x0 < np.log(lo)) or np.any(x0 > np.log(hi)):
        raise ValueError(f"start must lie within bounds for {list(free)}, got {start}")

    def geometry_at(x: np.ndarray) -> geo.HexFlexGeometry:
        return start.replace(**dict(zip(free, np.clip(np.exp(x), lo, hi).tolist(), strict=True)))

    def residual(x: np.ndarray) -> np.ndarray:
        anchor = ANCHOR_WEIGHT * (x - x0)
        try:
            g = geometry_at(x)
        except ValueError:
            return np.r_[np.full(4, INFEASIBLE_RESIDUAL), anchor]
        c = target_values(hexflex_frame_compliance(g, young, poisson, shear))
        return np.r_[np.log(np.abs(c) / tgt), anchor]

    # dogbox: 20-30 evaluations; trf crawled on this rank-deficient fit (measured: > 1000)
    sol = least_squares(
        residual, x0, bounds=(np.log(lo), np.log(hi)), method="dogbox", **PREFIT_TOLERANCES
    )
    g = geometry_at(sol.x)
    return g, target_values(hexflex_frame_compliance(g, young, poisson, shear))
