"""Mesh and element convergence of the HexFlex compliance.

:func:`study` solves one geometry over flexure element sizes (and optionally another size of the
free region, and the shell element); :func:`changes` reduces its rows to the largest relative
changes of the four Eq 8 magnitudes the identification matches.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from mechlib.campaign.experiments import model_size, release_models
from mechlib.hexflex import geometry as geo
from mechlib.hexflex.compliance import compliance
from mechlib.hexflex.fe.model import (
    COARSE_WIDTHS,
    ELEMENTS,
    coarsening_for,
)
from mechlib.hexflex.geometry import AL7075_POISSON, AL7075_YOUNG_MPA
from mechlib.hexflex.identify import target_values
from mechlib.hexflex.spec import ModelSpec
from mechlib.params import check_float


def study(
    geometry: geo.HexFlexGeometry,
    fractions: list[float],
    young: float = AL7075_YOUNG_MPA,
    poisson: float = AL7075_POISSON,
    elements: tuple[str, ...] = ELEMENTS,
    coarse_widths: float = COARSE_WIDTHS,
    cache_dir: Path | None = None,
) -> list[dict[str, object]]:
    """Compliance of one geometry over mesh sizes (fractions of the narrowest flexure) and elements.

    The largest element (stage, tabs) stays ``coarse_widths`` narrowest flexure widths, so the
    fractions refine the flexures; call again with a smaller ``coarse_widths`` to refine the rest.

    Parameters
    ----------
    geometry : HexFlexGeometry
    fractions : list of float
        Flexure element sizes as fractions of the narrowest flexure width, each in (0, 1].
    young, poisson : float
        Material constants [MPa, -].
    elements : tuple of str
        Element kinds to solve at every fraction (``model.ELEMENTS``).
    coarse_widths : float
        Largest element of the stage and tabs, in narrowest flexure widths, in [1, 64].
    cache_dir : Path, optional
        FE cache: each model's compliance and DOF count are read from it when a build computed
        them before (:mod:`mechlib.hexflex.compliance`), so no model is built then.

    Returns
    -------
    list of dict
        ``element``, ``fraction``, ``coarse_widths``, ``mesh_size`` [mm], ``n_dofs`` and
        ``compliance`` (6, 6) per model.
    """
    coarse_widths = check_float("coarse_widths", coarse_widths, low=1.0, high=64.0)
    rows = []
    for fraction in fractions:
        fraction = check_float("fractions", fraction, low=0.0, high=1.0, low_open=True)
        size = geometry.narrowest * fraction
        for kind in elements:
            spec = ModelSpec(
                geometry,
                young=young,
                poisson=poisson,
                element=kind,
                mesh_size=size,
                coarsening=coarsening_for(coarse_widths, fraction),
            )
            rows.append(
                {
                    "element": kind,
                    "fraction": fraction,
                    "coarse_widths": coarse_widths,
                    "mesh_size": size,
                    "n_dofs": model_size(spec, cache_dir),
                    "compliance": compliance(spec, cache_dir),
                }
            )
            release_models()  # the next, finer model replaces this one
    return rows


def changes(
    rows: list[dict[str, object]], chosen_fraction: float, coarse_widths: float
) -> dict[str, object]:
    """Largest relative changes of the four target magnitudes in a mesh-convergence study.

    Parameters
    ----------
    rows : list of dict
        Output of :func:`study` (Q2 rows over flexure fractions at ``coarse_widths``; optionally
        Q2 rows with another ``coarse_widths`` and shell rows).
    chosen_fraction : float
        The flexure fraction of the model in use; must be one of the Q2 fractions.
    coarse_widths : float
        Largest element of the flexure-refinement series, in narrowest flexure widths.

    Returns
    -------
    dict
        ``fractions`` (coarse to fine), ``steps`` (change at each refinement), ``next`` (chosen →
        next finer; NaN if the chosen mesh is the finest), ``finest`` (chosen → finest),
        ``coarse_region`` (chosen → same flexures with another free-region size; NaN if absent),
        ``shell_vs_q2`` (on the finest flexure mesh; NaN if no shell row).

    Raises
    ------
    ValueError
        If the chosen fraction is not in the Q2 series.
    """

    def mags(r: dict[str, object]) -> np.ndarray:
        return target_values(np.asarray(r["compliance"]))

    def change(a: np.ndarray, b: np.ndarray) -> float:
        return float(np.max(np.abs(a / b - 1.0)))

    series = sorted(
        (r for r in rows if r["element"] == "q2" and r["coarse_widths"] == coarse_widths),
        key=lambda r: -float(r["fraction"]),
    )
    fractions = [float(r["fraction"]) for r in series]
    match = [i for i, f in enumerate(fractions) if np.isclose(f, chosen_fraction, rtol=1e-9)]
    if not match:
        raise ValueError(
            f"chosen_fraction must be one of the Q2 fractions {fractions}, got {chosen_fraction}"
        )
    k = match[0]
    values = [mags(r) for r in series]
    steps = [change(values[i + 1], values[i]) for i in range(len(values) - 1)]
    others = [
        r
        for r in rows
        if r["element"] == "q2"
        and r["coarse_widths"] != coarse_widths
        and np.isclose(float(r["fraction"]), chosen_fraction, rtol=1e-9)
    ]
    shells = [
        r
        for r in rows
        if r["element"] == "shell"
        and r["coarse_widths"] == coarse_widths
        and np.isclose(float(r["fraction"]), fractions[-1], rtol=1e-9)
    ]
    nan = float("nan")
    return {
        "fractions": fractions,
        "steps": steps,
        "next": steps[k] if k < len(steps) else nan,
        "finest": change(values[k], values[-1]),
        "coarse_region": change(mags(others[0]), values[k]) if others else nan,
        "shell_vs_q2": change(mags(shells[0]), values[-1]) if shells else nan,
    }
