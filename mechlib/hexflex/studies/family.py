"""Other members of the family of HexFlex layouts that have Eq 8's compliance.

Eq 8's four independent magnitudes fix only about four combinations of the planform's nine
dimensions (the identification page), so a whole family of parts has Eq 8's compliance. A member
is picked here by fixing the plate thickness and re-identifying the in-plane flexure dimensions:
first on the reduced beam model (:func:`mechlib.hexflex.frame.prefit`, milliseconds), then on the
FE model (:func:`mechlib.hexflex.identify.identify`, one FE model per step). The beam model alone
also tells which thicknesses cannot reach Eq 8 within the layout's bounds at all
(:func:`frame_reach`).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from mechlib.hexflex import compliance as cc
from mechlib.hexflex import frame
from mechlib.hexflex import identify as ident
from mechlib.hexflex.geometry import (
    AL7075_POISSON,
    AL7075_YOUNG_MPA,
    DIMENSION_BOUNDS,
    HexFlexGeometry,
)
from mechlib.params import check_choice, check_float, check_increasing

#: The dimensions re-identified for a member: the flexures' in-plane widths and lengths and the
#: radius of the beams (four magnitudes, five dimensions: the beam model's pre-fit picks the
#: member nearest the start).
FAMILY_FREE: tuple[str, ...] = (
    "beam_width",
    "beam_length",
    "radial_length",
    "radial_width",
    "beam_radius",
)
#: The dimensions the FE fit of a member moves: as many as magnitudes, so that the FE members
#: meeting the target form isolated points (not a curve), and fits that converge end within the
#: tolerance of one of them (the radial width keeps the pre-fit's value). The beam model's
#: log-sensitivities of these four are well conditioned at the members' pre-fits (smallest
#: singular value about 0.2 at 0.45 and 0.55 mm).
FE_FREE: tuple[str, ...] = ("beam_width", "beam_length", "radial_length", "beam_radius")
#: Decimals [mm] of the pre-fit that starts a member's FE fit (1 µm): the pre-fit's least squares
#: ends within ~3e-7 mm of its optimum, differently on another processor, so on a finer grid
#: the start (and the radial width kept) would depend on round-off.
START_DECIMALS = 3
#: log(achieved / target) of a member's FE fit is read to this quantum
#: (:func:`mechlib.hexflex.identify.identify`'s ``log_quantum``): far above the FE's
#: round-off between processors (measured on a 0.45 mm member, OpenBLAS Haswell vs
#: Sandybridge kernels: 4.6e-9 of the compliance) and ten times below the default tolerance.
FIT_LOG_QUANTUM = 1e-4


def fit_log_quantum(tol: float) -> float | None:
    """The quantum a member's FE fit reads its misfits to at tolerance ``tol``:
    :data:`FIT_LOG_QUANTUM`, or a tenth of ``tol`` when that is smaller; None (no rounding)
    below a tolerance of 1e-7, where the quantum would reach the FE's own round-off."""
    tol = check_float("tol", tol, low=0.0, high=1.0, low_open=True)
    return min(FIT_LOG_QUANTUM, tol / 10) if tol >= 1e-7 else None


@dataclass(frozen=True)
class Member:
    """One identified member: its geometry, its FE magnitudes (4,) in the order of
    :data:`mechlib.hexflex.identify.TARGET_LABELS`, their worst relative error [%] against the
    target, and the FE models the identification built."""

    geometry: HexFlexGeometry
    achieved: np.ndarray
    worst_pct: float
    evaluations: int


def check_thickness(thickness: float) -> float:
    """A plate thickness [mm] within :data:`DIMENSION_BOUNDS`.

    Parameters
    ----------
    thickness : float
        The plate thickness [mm].

    Returns
    -------
    float
        ``thickness`` as a float.

    Raises
    ------
    ValueError, TypeError
        If it is not a finite number within ``DIMENSION_BOUNDS["thickness"]`` (named, with the
        bounds).
    """
    lo, hi = DIMENSION_BOUNDS["thickness"]
    return check_float("thickness [mm]", thickness, low=lo, high=hi)


def check_member_thicknesses(thicknesses: Sequence[float], identified: float) -> list[float]:
    """The plate thicknesses [mm] of the members to identify besides the identified one.

    Parameters
    ----------
    thicknesses : sequence of float
        The other members' plate thicknesses [mm], each within the layout's bounds.
    identified : float
        The identified member's plate thickness [mm] (that member is not identified again).

    Returns
    -------
    list of float
        ``thicknesses`` as floats, in the order given.

    Raises
    ------
    ValueError
        On no thickness (the chapter compares the identified member with at least one other), a
        thickness out of bounds, one given twice, or one equal to ``identified`` (its member
        would replace the identified one).
    """
    if isinstance(thicknesses, (str, bytes)) or np.ndim(thicknesses) != 1 or not len(thicknesses):
        raise ValueError(
            "thicknesses must list at least one other member's plate thickness [mm] "
            f"(each in the layout's bounds), got {thicknesses!r}"
        )
    out = [check_thickness(t) for t in thicknesses]
    if identified in out:
        raise ValueError(
            f"thicknesses must not contain the identified member's thickness {identified!r} mm "
            f"(that member is the model page's own), got {out}"
        )
    if len(set(out)) != len(out):
        raise ValueError(f"thicknesses must not repeat a value, got {out}")
    return out


def frame_reach(
    target: Sequence[float],
    start: HexFlexGeometry,
    thicknesses: Sequence[float],
    free: Sequence[str] = FAMILY_FREE,
    young: float = AL7075_YOUNG_MPA,
    poisson: float = AL7075_POISSON,
) -> np.ndarray:
    """How close the beam model gets to ``target`` at each fixed thickness.

    A thickness whose error stays large has no member of the family with this layout.

    Parameters
    ----------
    target : sequence of 4 floats
        The magnitudes of :data:`mechlib.hexflex.identify.TARGET_LABELS` (Eq 8's).
    start : HexFlexGeometry
        Where each fit starts; its dimensions other than ``thickness`` and ``free`` are kept.
    thicknesses : sequence of float
        Plate thicknesses [mm], each within the layout's bounds.
    free : sequence of str
        The dimensions :func:`mechlib.hexflex.frame.prefit` fits at each thickness.
    young, poisson : float
        Young's modulus [MPa] and Poisson's ratio of the beam model.

    Returns
    -------
    numpy.ndarray (len(thicknesses),)
        Per thickness, the worst relative error [%] of the four magnitudes against ``target``
        after the beam model's fit of ``free`` within the layout's bounds.

    Raises
    ------
    ValueError
        On a thickness out of bounds (before any fit).
    """
    out = []
    for t in thicknesses:
        g = start.replace(thickness=check_thickness(t))
        _, achieved = frame.prefit(target, g, free, young, poisson)
        out.append(100 * np.abs(np.asarray(achieved) / np.asarray(target) - 1).max())
    return np.array(out)


def check_mesh_fractions(fractions: object) -> list[float]:
    """The mesh study's flexure element sizes (fractions of the narrowest flexure width): at
    least two, strictly decreasing, each in [0.1, 1] (the first is the chapter's own).

    Raises
    ------
    ValueError
        Naming ``mesh_fractions`` and the values as given.
    """
    arr = np.asarray(fractions, dtype=object)
    what = "mesh_fractions must list at least 2 strictly decreasing values in [0.1, 1.0], got "
    if arr.ndim != 1:
        raise ValueError(what + f"{fractions!r}")
    try:
        return check_increasing("mesh_fractions", arr[::-1], low=0.1, high=1.0)[::-1].tolist()
    except ValueError as err:
        raise ValueError(what + f"{arr.tolist()}") from err


def identify_member(
    target: Sequence[float],
    start: HexFlexGeometry,
    thickness: float,
    mesh_fraction: float,
    free: Sequence[str] = FAMILY_FREE,
    max_evaluations: int = ident.MAX_EVALUATIONS,
    tol: float = 1e-3,
    young: float = AL7075_YOUNG_MPA,
    poisson: float = AL7075_POISSON,
    cache_dir: Path | None = None,
    fe_free: Sequence[str] = FE_FREE,
) -> Member:
    """The member of the family with plate ``thickness`` [mm]: ``free`` re-identified so that
    the Q2 FE model (flexure elements ``mesh_fraction`` of the narrowest width) meets ``target``.

    The beam model's pre-fit picks the member nearest ``start`` (:func:`frame.prefit`, ``free``
    fitted), rounded to :data:`START_DECIMALS`; the FE fit then moves ``fe_free`` alone (as many
    dimensions as magnitudes: the members meeting the target are isolated points, and a fit
    that converges ends within ``tol`` of one) with secant-updated steps, reading the FE's
    misfits to :func:`fit_log_quantum` (:func:`identify.identify`). Which point within ``tol``
    it stops at depends on its path, and the path on nothing but rounded values: on another
    processor the pre-fit's spread (~3e-7 mm against the 1 µm grid) and the FE's round-off
    (~5e-9 against the quantum) change a rounded value only where it lies that close to a
    rounding boundary (a chance of order 1e-3 for a member); then the path changes and the
    member moves within the fit's tolerance.

    Parameters
    ----------
    target : sequence of 4 floats
        The magnitudes of :data:`mechlib.hexflex.identify.TARGET_LABELS` (Eq 8's).
    start : HexFlexGeometry
        Where the search starts; its other dimensions are kept.
    thickness : float
        The member's plate thickness [mm], within the layout's bounds.
    mesh_fraction : float
        As for :func:`mechlib.hexflex.fe.model.model_maker`.
    free : sequence of str
        The dimensions the beam model's pre-fit moves.
    max_evaluations, tol
        As for :func:`mechlib.hexflex.identify.identify`: ``tol`` is the largest
        |log(achieved / target)| over the four magnitudes that the member may keep.
    young, poisson : float
        Young's modulus [MPa] and Poisson's ratio of the FE and beam models.
    cache_dir : Path, optional
        FE cache of the compliances of the models built
        (:mod:`mechlib.hexflex.compliance`).
    fe_free : sequence of str
        The dimensions the FE fit moves: at most four, each in ``free``.

    Returns
    -------
    Member
        The identified geometry, its FE magnitudes, their worst relative error [%] against
        ``target`` and the number of FE models built.

    Raises
    ------
    ValueError
        On a thickness out of bounds or bad identification settings.
    IdentificationError
        When the FE fit does not meet ``tol`` within ``max_evaluations`` FE models (the message
        names the thickness, the misfit reached and ``tol``).
    """
    g = start.replace(thickness=check_thickness(thickness))
    free = ident.check_free(free)
    fe_free = [check_choice("fe_free", n, tuple(free)) for n in fe_free]
    if not 0 < len(set(fe_free)) == len(fe_free) <= len(ident.TARGET_LABELS):
        raise ValueError(
            f"fe_free must be 1 to {len(ident.TARGET_LABELS)} distinct names of free = "
            f"{free}, got {fe_free}"
        )
    prefit, _ = frame.prefit(target, g, free, young, poisson)
    prefit = prefit.replace(**{n: round(getattr(prefit, n), START_DECIMALS) for n in free})
    specs = cc.default_specs(
        young=young, poisson=poisson, element="q2", mesh_fraction=mesh_fraction
    )
    try:
        fit = ident.identify(
            prefit,
            target,
            fe_free,
            cc.compliance_maker(specs, cache_dir),
            frame.compliance_maker(young, poisson),
            max_evaluations=max_evaluations,
            tol=tol,
            jacobian="secant",
            log_quantum=fit_log_quantum(tol),
        )
    except ident.IdentificationError as err:
        raise ident.IdentificationError(
            f"the member with plate thickness {g.thickness:g} mm: {err}", err.result
        ) from err
    worst = float(100 * np.abs(fit.achieved / np.asarray(target) - 1).max())
    return Member(fit.geometry, np.asarray(fit.achieved), worst, fit.n_evaluations)
