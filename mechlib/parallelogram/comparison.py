"""Our elastica beside the published 3-D FE of the parallelogram flexure (Su & Survey).

The published sweep (:mod:`.published`) is compared with the elastica (:mod:`.elastica`) row by
row, under the loads the FE really applied (:func:`applied_loads`: the couple's sign was lost in
the FE runs) and against the rotation the FE's stage really made (:func:`fe_poses`: the file's φ
comes from a formula with a sign error). The rows compared and the bounds the comparison is held
to are fixed here, from the physics of the two models, before any difference is measured:

- the 3-D FE's beams (H/T = 10) are plates more than beams: their bending stiffness lies between
  E·I and E·I/(1 − ν²), so beam theory may be more compliant in u_y by up to
  :data:`PLATE_BOUND`; the shortening u_x grows as u_y², so by up to :data:`SHORTENING_BOUND`;
- u_x is compared where the beams' shortening is at least ten times their axial stretch
  (|A_y| ≥ :data:`SHORTENING_MIN_A_Y`); u_y and φ wherever a load makes them non-zero;
- at small loads (|A_y| ≤ :data:`SMALL_A_Y`) φ is held to the plate bound of the FE's largest
  rotation there.

Every function takes and returns numpy arrays; rows are (A_x, A_y, B) loads and (u_x/L, u_y/L,
φ [rad]) poses, in the order given.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from mechlib.metamodels.metrics import full_scale_pct
from mechlib.parallelogram import elastica as el
from mechlib.parallelogram import published as pub

#: the pose components compared, in column order
COMPONENTS: tuple[str, ...] = ("u_x/L", "u_y/L", "phi")
#: 1/(1 − ν²): a plate's bending stiffness over a beam's of the same E and I
PLATE_FACTOR: float = 1.0 / (1.0 - pub.POISSON**2)
#: the largest relative excess of beam theory over a plate-like FE in u_y (and φ): 9.9 %
PLATE_BOUND: float = PLATE_FACTOR - 1.0
#: the same for the shortening u_x, which grows as u_y²: 20.8 %
SHORTENING_BOUND: float = PLATE_FACTOR**2 - 1.0
#: u_x is compared from this |A_y| on: there the shortening 0.6 u_y² (guided beams) is ten times
#: the axial stretch |A_x| c / 2 or more for |A_x| ≤ 6 (6.25 times at |A_x| = 10): the
#: transcribed lines have |A_x| ≤ 5
SHORTENING_MIN_A_Y: float = 1.0
#: "small loads": |A_y| up to this
SMALL_A_Y: float = 2.0
#: under a couple, an inextensible model that misses more than this share of the rotation shows
#: that the stage turns mainly by stretching its beams
STRETCH_SHARE: float = 0.5
#: d/L of the centre of the 50 mm stage, beyond the beam tips: where the paper says the loads act
STAGE_CENTRE_OFFSET: float = pub.STAGE_LENGTH_MM / 2.0 / pub.LENGTH_MM


def as_rows(name: str, value: object, width: int = 3) -> np.ndarray:
    """``value`` as a finite (n, ``width``) float array, else ValueError naming ``name``."""
    arr = np.asarray(value, dtype=float)
    if arr.ndim != 2 or arr.shape[1] != width or not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} must be a finite (n, {width}) array, got shape {arr.shape}")
    return arr


def applied_loads(sweep: object) -> np.ndarray:
    """(A_x, A_y, B) the FE really applied in each row of a sweep (columns
    :data:`.published.SWEEP_COLUMNS`): B = +|B| for A_y ≥ 0, -|B| for A_y < 0.

    Raises
    ------
    ValueError
        If ``sweep`` is not a finite (n, 6) array.
    """
    s = as_rows("sweep", sweep, 6)
    return np.column_stack([s[:, 0], s[:, 1], pub.applied_b(s[:, 1], s[:, 2])])


def fe_poses(sweep: object) -> np.ndarray:
    """(u_x/L, u_y/L, φ) of the FE's stage in each row: φ is the rigid rotation whose reported
    value the file holds (:func:`.published.rotation_from_reported`).

    Raises
    ------
    ValueError
        If ``sweep`` is not a finite (n, 6) array.
    """
    s = as_rows("sweep", sweep, 6)
    return np.column_stack([s[:, 3], s[:, 4], pub.rotation_from_reported(s[:, 5])])


def solve_loads(
    loads: object, *, axial_compliance: float = 0.0, load_offset: float = 0.0
) -> np.ndarray:
    """Elastica poses at many loads, each distinct load solved once.

    A load with A_y < 0 (or A_y = 0 and B < 0) is solved as its mirror image about the x-axis,
    (A_x, -A_y, -B) → (u_x, -u_y, -φ), exact for the symmetric mechanism. The loads are then
    solved line by line, at fixed (A_x, B) in increasing A_y, each continued from the previous
    one (the first from the unloaded state along the straight load path).

    Parameters
    ----------
    loads : array_like, shape (n, 3)
        Rows (A_x, A_y, B), each in the elastica's ranges (:func:`.elastica.check_loads`).
    axial_compliance, load_offset : float
        As in :func:`.elastica.solve_pose`.

    Returns
    -------
    numpy.ndarray, shape (n, 3)
        Rows (u_x/L, u_y/L, φ [rad]), in the order of ``loads``.

    Raises
    ------
    ValueError
        If ``loads`` is not a finite (n, 3) array or a load is out of range.
    elastica.ElasticaConvergenceError
        If a load cannot be reached.
    """
    arr = as_rows("loads", loads)
    flip = (arr[:, 1] < 0) | ((arr[:, 1] == 0) & (arr[:, 2] < 0))
    canon = np.where(flip[:, None], arr * [1.0, -1.0, -1.0], arr)
    poses: dict[tuple[float, float, float], np.ndarray] = {}
    for a_x, b in sorted({(r[0], r[2]) for r in canon.tolist()}):
        ays = sorted({r[1] for r in canon.tolist() if r[0] == a_x and r[2] == b})
        path = el.solve_path(
            [[a_x, a_y, b] for a_y in ays],
            axial_compliance=axial_compliance,
            load_offset=load_offset,
        )
        poses |= {(a_x, a_y, b): p for a_y, p in zip(ays, path, strict=True)}
    out = np.array([poses[tuple(r)] for r in canon.tolist()])
    return np.where(flip[:, None], out * [1.0, -1.0, -1.0], out)


def at_printed_couple(
    sweep: object, applied_poses: object, *, axial_compliance: float = pub.AXIAL_COMPLIANCE
) -> np.ndarray:
    """Elastica poses under the couple each row's B column prints (the FE's intent), given the
    poses under the couple applied (:func:`applied_loads`); only the rows where the two differ
    are solved.

    Raises
    ------
    ValueError
        If the arrays are not finite (n, 6) and (n, 3).
    """
    s, poses = as_rows("sweep", sweep, 6), as_rows("applied_poses", applied_poses)
    if len(poses) != len(s):
        raise ValueError(
            f"applied_poses must have one row per sweep row ({len(s)}), got {len(poses)}"
        )
    out = poses.copy()
    differ = applied_loads(s)[:, 2] != s[:, 2]
    if differ.any():
        out[differ] = solve_loads(s[differ, :3], axial_compliance=axial_compliance)
    return out


def compared_rows(loads: object) -> np.ndarray:
    """Which rows each component's relative difference is taken over, shape (n, 3): u_x where
    |A_y| ≥ :data:`SHORTENING_MIN_A_Y`; u_y and φ where A_y ≠ 0 or B ≠ 0 (else both are zero by
    symmetry).

    Raises
    ------
    ValueError
        If ``loads`` is not a finite (n, 3) array.
    """
    arr = as_rows("loads", loads)
    loaded = (arr[:, 1] != 0) | (arr[:, 2] != 0)
    return np.column_stack([np.abs(arr[:, 1]) >= SHORTENING_MIN_A_Y, loaded, loaded])


def relative_excess(model: object, fe: object, rows: object) -> np.ndarray:
    """model / FE − 1 per component where ``rows`` is true, NaN elsewhere, shape (n, 3).

    Raises
    ------
    ValueError
        If the arrays are not (n, 3) of one n, or a selected FE value is zero.
    """
    m, f = as_rows("model", model), as_rows("fe", fe)
    sel = np.asarray(rows, dtype=bool)
    if m.shape != f.shape or sel.shape != f.shape:
        raise ValueError(f"model, fe and rows must share one shape, got {m.shape}, {f.shape}, "
                         f"{sel.shape}")  # fmt: skip
    if np.any(f[sel] == 0):
        raise ValueError("rows must select non-zero FE values only")
    out = np.full(f.shape, np.nan)
    out[sel] = m[sel] / f[sel] - 1.0
    return out


def shares_pct(model: object, fe: object, span_of: object = None) -> np.ndarray:
    """|model − FE| per row and component in % of full scale: of the FE component's largest
    |value| over ``span_of`` (default ``fe``), shape (n, 3)
    (:func:`mechlib.metamodels.metrics.full_scale_pct`, the book's one measure).

    Raises
    ------
    ValueError
        If the arrays are not finite (n, 3) of one n.
    """
    m, f = as_rows("model", model), as_rows("fe", fe)
    if m.shape != f.shape:
        raise ValueError(f"model and fe must share one shape, got {m.shape} and {f.shape}")
    return full_scale_pct(m - f, as_rows("span_of", f if span_of is None else span_of))


class Summary(NamedTuple):
    """Differences elastica − FE per component (arrays of 3: u_x/L, u_y/L, φ).

    ``worst_abs``, ``median_abs``: largest and median |difference| (u/L, rad);
    ``worst_share_pct``, ``median_share_pct``: the same in % of full scale (of the FE
    component's largest |value| over the rows given as ``span_of``); ``worst_rel_pct``,
    ``median_rel_pct``: largest and median |model/FE − 1| [%] over the compared rows
    (:func:`compared_rows`); ``worst_row``: the row index of the largest |difference|.
    """

    worst_abs: np.ndarray
    median_abs: np.ndarray
    worst_share_pct: np.ndarray
    median_share_pct: np.ndarray
    worst_rel_pct: np.ndarray
    median_rel_pct: np.ndarray
    worst_row: np.ndarray

    def statistics(self) -> dict[str, np.ndarray]:
        """The six statistics by field name, in field order (``worst_row``, an index, left out)."""
        return {name: value for name, value in self._asdict().items() if name != "worst_row"}


def summarise(
    model: object, fe: object, loads: object, *, where: object = None, span_of: object = None
) -> Summary:
    """Worst and typical differences of ``model`` from ``fe`` per component.

    Parameters
    ----------
    model, fe, loads : array_like, shape (n, 3)
        Poses of both models and the loads applied (to select the compared rows).
    where : array_like of bool, shape (n,), optional
        The rows summarised (default all).
    span_of : array_like, shape (m, 3), optional
        FE poses whose range per component is the unit of the shares (default ``fe``).

    Returns
    -------
    Summary

    Raises
    ------
    ValueError
        For arrays of other shapes, or an empty selection.
    """
    m, f, a = as_rows("model", model), as_rows("fe", fe), as_rows("loads", loads)
    sel = np.ones(len(f), bool) if where is None else np.asarray(where, dtype=bool)
    if sel.shape != (len(f),) or not sel.any() or m.shape != f.shape or a.shape != f.shape:
        raise ValueError("model, fe, loads must be (n, 3) alike and where select some of n rows")
    spans = np.abs(as_rows("span_of", f if span_of is None else span_of)).max(axis=0)
    diff = np.abs(m - f)
    rel = np.abs(relative_excess(m, f, compared_rows(a) & sel[:, None]))
    worst_row = np.flatnonzero(sel)[np.argmax(diff[sel], axis=0)]
    rel_stats = [
        (np.nanmax(c), np.nanmedian(c)) if np.isfinite(c).any() else (np.nan, np.nan) for c in rel.T
    ]
    return Summary(
        diff[sel].max(axis=0),
        np.median(diff[sel], axis=0),
        100.0 * diff[sel].max(axis=0) / spans,
        100.0 * np.median(diff[sel], axis=0) / spans,
        100.0 * np.array([w for w, _ in rel_stats]),
        100.0 * np.array([md for _, md in rel_stats]),
        worst_row,
    )


def excess_ranges(excess: object) -> dict[str, list[float] | np.ndarray]:
    """The range of each component's relative excess (:func:`relative_excess`, NaN where not
    compared): ``ux_pct``, ``uy_pct``, ``phi_pct`` as [smallest, largest], and ``abs_max_pct``,
    the largest magnitude per component.

    Raises
    ------
    ValueError
        If ``excess`` is not an (n, 3) array.
    """
    e = np.asarray(excess, dtype=float)
    if e.ndim != 2 or e.shape[1] != len(COMPONENTS):
        raise ValueError(f"excess must be an (n, 3) array, got shape {e.shape}")
    ranges = {
        f"{name}_pct": [np.nanmin(c), np.nanmax(c)]
        for name, c in zip(("ux", "uy", "phi"), e.T, strict=True)
    }
    return ranges | {"abs_max_pct": np.nanmax(np.abs(e), axis=0)}


def worst_by(keys: object, values: object) -> tuple[np.ndarray, np.ndarray]:
    """The distinct ``keys`` (sorted) and, per key, the largest of ``values`` (NaN ignored).

    Parameters
    ----------
    keys : array_like, shape (n,)
        E.g. |A_y| or A_x of each row.
    values : array_like, shape (n,) or (n, k)

    Returns
    -------
    (levels, worst)
        Shapes (p,) and (p,) or (p, k).

    Raises
    ------
    ValueError
        If ``values`` has another number of rows than ``keys``.
    """
    k, v = np.asarray(keys, dtype=float), np.asarray(values, dtype=float)
    if k.ndim != 1 or len(v) != len(k):
        raise ValueError(f"keys (n,) and values (n, ...) must share n, got {k.shape}, {v.shape}")
    levels = np.unique(k)
    worst = np.array([np.nanmax(np.where(np.isnan(v[k == lv]), -np.inf, v[k == lv]), axis=0)
                      for lv in levels])  # fmt: skip
    return levels, np.where(np.isneginf(worst), np.nan, worst)


class SweepEvidence(NamedTuple):
    """What the kept rows show about how the file was made (counts over the transcription).

    ``couple_pairs``: computed rows (A_y ≥ 0) with B > 0 whose -B row is kept; ``identical``:
    of those, the pairs whose three responses are equal to the last printed digit (the FE applied
    one couple to both); ``with_unloaded``: the pairs whose row with B = 0 is kept too;
    ``differ_from_unloaded``: of these, the pairs whose responses differ from that row (a couple
    was applied); ``mirrored``: rows with A_y < 0 that are exact mirrors of a computed row;
    ``negative``: rows with A_y < 0.
    """

    couple_pairs: int
    identical: int
    with_unloaded: int
    differ_from_unloaded: int
    mirrored: int
    negative: int


def sweep_evidence(sweep: object) -> SweepEvidence:
    """Count the identical B/-B pairs and the mirrored rows of a sweep (columns
    :data:`.published.SWEEP_COLUMNS`, B as printed).

    Raises
    ------
    ValueError
        If ``sweep`` is not a finite (n, 6) array.
    """
    s = as_rows("sweep", sweep, 6)
    by_load = {tuple(r[:3]): r[3:] for r in s.tolist()}
    pairs = [(k, (k[0], k[1], -k[2])) for k in by_load if k[1] >= 0 and k[2] > 0]
    pairs = [(k, j) for k, j in pairs if j in by_load]
    identical = sum(by_load[k] == by_load[j] for k, j in pairs)
    unloaded = [(k, (k[0], k[1], 0.0)) for k, _ in pairs if (k[0], k[1], 0.0) in by_load]
    differ = sum(by_load[k] != by_load[z] for k, z in unloaded)
    negative = [k for k in by_load if k[1] < 0]
    mirrored = sum(
        (src := by_load.get((k[0], -k[1], -k[2]))) is not None
        and by_load[k] == [src[0], -src[1], -src[2]]
        for k in negative
    )
    return SweepEvidence(len(pairs), identical, len(unloaded), differ, mirrored, len(negative))


class MeshCase(NamedTuple):
    """The mesh study's case beside the elastica: ``meshes`` (the published table, columns
    :data:`.published.MESH_STUDY_COLUMNS`), ``elastica`` (x [mm], y [mm], φ [rad] of the load
    point), ``excess_pct`` (elastica over each mesh − 1, [%], shape (meshes, 3)) and
    ``gap_closed`` (the share of the 10 mm mesh's gap to the elastica that the 3 mm mesh closes,
    per component)."""

    meshes: np.ndarray
    elastica: np.ndarray
    excess_pct: np.ndarray
    gap_closed: np.ndarray


def mesh_case(axial_compliance: float = pub.AXIAL_COMPLIANCE) -> MeshCase:
    """The elastica at the mesh study's loads (:data:`.published.MESH_STUDY_LOADS`) beside the
    published meshes (their φ corrected for the formula as the sweep's).

    Raises
    ------
    ValueError
        If ``axial_compliance`` is out of the elastica's range.
    """
    sol = el.solve_pose(*pub.MESH_STUDY_LOADS, axial_compliance=axial_compliance)
    ours = np.array([pub.LENGTH_MM * sol.u_x, pub.LENGTH_MM * sol.u_y, sol.phi])
    meshes = pub.MESH_STUDY.copy()
    fe = np.column_stack([meshes[:, 3:5], pub.rotation_from_reported(meshes[:, 5])])
    coarse, fine = fe[0], fe[-1]
    return MeshCase(meshes, ours, 100.0 * (ours / fe - 1.0), (fine - coarse) / (ours - coarse))
