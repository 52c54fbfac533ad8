"""Our 3-D FE of the parallelogram beside the published one: loads, poses and rows in the
benchmark's normalised units.

Our FE (:mod:`.mechanism` through :mod:`mechlib.compliant`) takes loads in N and N·mm and
returns the stage pose [µm, µrad] about the load point; the benchmark's rows are
(A_x, A_y, B) and (u_x/L, u_y/L, φ). The published sweep's rows with A_y ≥ 0 are the computed
ones (the others are mirror images), and their couple was +|B| whatever the printed sign
(:func:`.published.applied_b`).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from mechlib.campaign import executors
from mechlib.campaign.experiments import FailedRun, run_keeping_failures
from mechlib.compliant.spec import MechanismSpec
from mechlib.parallelogram import published as pub
from mechlib.parallelogram.comparison import SMALL_A_Y, applied_loads, as_rows, fe_poses, worst_by
from mechlib.params import check_matrix


def to_newton(loads: object) -> np.ndarray:
    """Loads (n, 3) (A_x, A_y, B) as (F_x [N], F_y [N], M_z [N·mm])."""
    arr = as_rows("loads", loads)
    return np.column_stack(pub.loads_to_newton(arr[:, 0], arr[:, 1], arr[:, 2]))


def from_newton(loads: object) -> np.ndarray:
    """Loads (F_x [N], F_y [N], M_z [N·mm]), one row (3,) or rows (n, 3), as (A_x, A_y, B)."""
    arr = np.asarray(loads, dtype=float)
    rows = as_rows("loads", arr[None, :] if arr.ndim == 1 else arr)
    out = np.column_stack(pub.newton_to_loads(rows[:, 0], rows[:, 1], rows[:, 2]))
    return out[0] if arr.ndim == 1 else out


def normalised(poses: object) -> np.ndarray:
    """Stage poses (n, 6) [µm, µrad] as (u_x/L, u_y/L, φ [rad]) (n, 3)."""
    p = check_matrix("poses", poses, shape=(None, 6))
    return np.column_stack([p[:, 0] / 1e3 / pub.LENGTH_MM, p[:, 1] / 1e3 / pub.LENGTH_MM,
                            p[:, 5] / 1e6])  # fmt: skip


def in_mm(poses: object) -> np.ndarray:
    """Stage poses (n, 6) [µm, µrad] as (x [mm], y [mm], φ [rad]): the mesh study's columns."""
    p = check_matrix("poses", poses, shape=(None, 6))
    return np.column_stack([p[:, 0] / 1e3, p[:, 1] / 1e3, p[:, 5] / 1e6])


def computed_rows(lines: object, corners: bool = True) -> np.ndarray:
    """The transcribed sweep rows the published FE computed (A_y ≥ 0) on the lines (A_x, B)
    given (each of {-5, 0, 5} × {-3, 0, 3}, the printed B) and, if ``corners``, the grid's
    corners with A_y ≥ 0; sorted by (A_x, B, A_y), each load applied once (of two rows printed
    with B and -B, which the FE computed under the same couple, the first).

    Returns
    -------
    sweep : ndarray (n, 6)
        Rows in :data:`.published.SWEEP_COLUMNS` order.
    loads : ndarray (n, 3)
        The loads the FE applied (couple +|B|).
    fe : ndarray (n, 3)
        The FE's stage pose (u_x/L, u_y/L, rigid φ).
    """
    pairs = check_matrix("lines", lines, shape=(None, 2)) if np.size(lines) else np.zeros((0, 2))
    rows = [pub.sweep_line(float(ax), float(b)) for ax, b in pairs]
    if corners:
        rows.append(pub.sweep_corners())
    sweep = np.vstack(rows) if rows else np.zeros((0, 6))
    sweep = sweep[sweep[:, 1] >= 0]
    if len(sweep) == 0:
        raise ValueError("lines and corners select no computed row: give a line or corners=True")
    _, first = np.unique(applied_loads(sweep), axis=0, return_index=True)  # B, -B: one run
    sweep = sweep[np.sort(first)]
    sweep = sweep[np.lexsort((sweep[:, 1], sweep[:, 2], sweep[:, 0]))]
    return sweep, applied_loads(sweep), fe_poses(sweep)


#: the columns of :func:`sweep_table`: the loads, then (u_x/L, u_y/L, φ) of each model
SWEEP_COLUMNS = (
    "A_x [-]", "A_y [-]", "B applied [-]",
    "published u_x/L [-]", "published u_y/L [-]", "published phi rigid [rad]",
    "our FE u_x/L [-]", "our FE u_y/L [-]", "our FE phi [rad]",
    "elastica u_x/L [-]", "elastica u_y/L [-]", "elastica phi [rad]",
)  # fmt: skip


def sweep_table(loads: object, published: object, ours: object, elastica: object) -> pd.DataFrame:
    """The sweep's rows as the data bundle's table: the loads applied (A_x, A_y, B), then the
    published FE's, our FE's and the elastica's (u_x/L, u_y/L, φ [rad]) at each, columns
    :data:`SWEEP_COLUMNS`.

    Raises
    ------
    ValueError
        Any of the four not an (n, 3) array of numbers, or their row counts differing (a pose
        that is not finite is written as an empty cell).
    """
    named = {"loads": loads, "published": published, "ours": ours, "elastica": elastica}
    parts = {name: np.asarray(a, dtype=float) for name, a in named.items()}
    shapes = {name: a.shape for name, a in parts.items()}
    if any(len(s) != 2 or s[1] != 3 for s in shapes.values()) or len(set(shapes.values())) > 1:
        raise ValueError(f"loads, published, ours and elastica must be (n, 3) arrays, got {shapes}")
    return pd.DataFrame(np.hstack(list(parts.values())), columns=list(SWEEP_COLUMNS))


def largest_by_level(loads: object, shares: object) -> dict[str, np.ndarray | list[float]]:
    """How the difference of our FE from the published one grows with the loads.

    Parameters
    ----------
    loads : array_like, shape (n, 3)
        The loads (A_x, A_y, B) of the rows.
    shares : array_like, shape (n, 3)
        Each row's |our FE − published| per component, % of the published full scale
        (:func:`~.comparison.shares_pct`).

    Returns
    -------
    dict
        ``a_x_levels`` and ``by_a_x_pct``: each A_x and the largest share of each component
        there (:func:`~.comparison.worst_by`); ``a_y_levels`` and ``by_a_y_pct``: the same for
        |A_y|; ``small_and_top_pct``: the largest share of any component up to |A_y| =
        :data:`~.comparison.SMALL_A_Y`, the largest at the largest |A_y|, and that |A_y|.

    Raises
    ------
    ValueError
        Loads not an (n, 3) array, shares of other rows, or no row with |A_y| ≤ SMALL_A_Y.
    """
    rows = as_rows("loads", loads)
    ax_levels, by_ax = worst_by(rows[:, 0], shares)
    ay_levels, by_ay = worst_by(np.abs(rows[:, 1]), shares)
    small = ay_levels <= SMALL_A_Y
    if not small.any():
        raise ValueError(f"loads must hold a row with |A_y| <= {SMALL_A_Y:g}, got {ay_levels}")
    return {
        "a_x_levels": ax_levels,
        "by_a_x_pct": by_ax,
        "a_y_levels": ay_levels,
        "by_a_y_pct": by_ay,
        "small_and_top_pct": [by_ay[small].max(), by_ay[-1].max(), ay_levels[-1]],
    }


def convergence_pct(values: object) -> np.ndarray:
    """|each row − the last row| in % of the last row's magnitude, per column (the mesh study's
    measure: the last row is the finest mesh)."""
    v = np.asarray(values, dtype=float)
    return 100.0 * np.abs(v - v[-1]) / np.abs(v[-1])


def solve(
    spec: MechanismSpec,
    loads: object,
    *,
    steps: int,
    workers: int = 1,
    cache_dir: Path | None = None,
) -> np.ndarray:
    """Our non-linear FE's stage poses (u_x/L, u_y/L, φ) (n, 3) at normalised loads (n, 3):
    a campaign of ``spec``'s model (``steps`` load steps a run, ``workers`` processes, the FE
    cache ``cache_dir``), the pose the rigid registration of the stage's nodes.

    Raises
    ------
    RuntimeError
        When a run fails — does not converge, or its task raised — (:func:`solve_keeping`
        leaves such runs out instead), naming each with its loads, last relative residual and
        the reason its campaign gave.
    """
    _, poses, failures = solve_keeping(spec, loads, steps=steps, workers=workers,
                                       cache_dir=cache_dir)  # fmt: skip
    if failures:
        runs = "; ".join(
            f"row {f.index} (loads {f.forces} in N and N·mm, last relative residual "
            f"{f.residual:.3g}): {f.reason}"
            for f in failures
        )
        raise RuntimeError(f"{len(failures)} run(s) failed: {runs}")
    return poses


def solve_keeping(
    spec: MechanismSpec,
    loads: object,
    *,
    steps: int,
    workers: int = 1,
    cache_dir: Path | None = None,
) -> tuple[np.ndarray, np.ndarray, list[FailedRun]]:
    """Our non-linear FE's stage poses at normalised loads (as :func:`solve`), a run that does
    not converge left out and listed.

    Returns
    -------
    loads : ndarray (m, 3)
        The rows of ``loads`` that have a result, in order.
    poses : ndarray (m, 3)
        Their poses (u_x/L, u_y/L, φ).
    failures : list of FailedRun
        The other rows (index into ``loads``, loads in N and N·mm, last residual, error).
    """
    arr = as_rows("loads", loads)
    with executors.executor(workers) as pool:
        index, poses, failures = run_keeping_failures(
            spec, to_newton(arr), kind="nonlinear", steps=steps, pose="rotvec", executor=pool,
            cache_dir=cache_dir, progress=False,
        )  # fmt: skip
    return arr[index], normalised(poses), failures
