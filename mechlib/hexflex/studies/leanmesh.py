"""The lean FE mesh against the default one on non-linear runs, after re-identification.

A cheaper model is judged by what the book reports, not by its compliance at fixed dimensions:
the lean model (:func:`mechlib.hexflex.fe.lean.lean_model`) is first fitted to the magnitudes the
default model achieves (:func:`fit_lean`), then both solve the same non-linear runs, and
:func:`compare` states each pose component's difference as % of full scale and the difference of
the departures from linearity (each model's non-linear minus its own linear pose) as % of the
default model's largest departure of that component. The criteria (``POSE_PCT``,
``DEPARTURE_PCT``) are those a cheaper run must meet to replace the default one in the book's
non-linear campaigns.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import replace
from pathlib import Path

import numpy as np

from mechlib.hexflex import compliance as cc
from mechlib.hexflex import frame
from mechlib.hexflex import identify as ident
from mechlib.hexflex.geometry import AL7075_POISSON, AL7075_YOUNG_MPA, HexFlexGeometry
from mechlib.hexflex.spec import ModelSpec
from mechlib.params import check_float, check_int, check_matrix

#: Poses within this % of full scale, departures within this % of themselves.
POSE_PCT, DEPARTURE_PCT = 0.1, 1.0
#: The lean fit's tolerance (max |log(achieved / target)|): a tenth of the model page's 1e-3,
#: so that the comparison measures the mesh and not where two fits stopped within 0.1 %.
FIT_TOL = 1e-4
MAX_EVALUATIONS = 20
#: The dimensions the model page fits by default (its ``free_dimensions``): the lean model is
#: identified as the chapter's model was.
FREE = ("thickness", "beam_width", "beam_length", "radial_length")


def fit_lean(
    geometry: HexFlexGeometry,
    achieved: np.ndarray,
    young: float = AL7075_YOUNG_MPA,
    poisson: float = AL7075_POISSON,
    free: Sequence[str] = FREE,
    tol: float = FIT_TOL,
    max_evaluations: int = MAX_EVALUATIONS,
    pose_mesh_size: float | None = None,
    cache_dir: Path | None = None,
) -> ident.Identification:
    """The lean model's geometry that meets ``achieved``, from the default model's ``geometry``.

    Parameters
    ----------
    geometry : HexFlexGeometry
        The default model's geometry: the start, and the dimensions not in ``free``.
    achieved : array_like (4,)
        The magnitudes to meet (:data:`mechlib.hexflex.identify.TARGET_LABELS`; their sizes are
        taken), e.g. the default model's.
    young, poisson : float
        Material [MPa], [-].
    free, tol, max_evaluations
        As :func:`mechlib.hexflex.identify.identify` (which fits, with the beam model's
        sensitivities).
    pose_mesh_size : float, optional
        Flexure element size [mm] of the default mesh whose stage vertices carry the lean
        model's pose (:func:`mechlib.hexflex.fe.lean.lean_model`); default: that model's default.
    cache_dir : Path, optional
        FE cache of the lean models' compliances (:mod:`mechlib.hexflex.compliance`).

    Returns
    -------
    Identification
        The lean geometry and the magnitudes it achieves.

    Raises
    ------
    mechlib.hexflex.identify.IdentificationError
        If no lean model within ``max_evaluations`` meets ``tol``.
    """
    return ident.identify(
        geometry,
        np.abs(np.asarray(achieved, dtype=float)),
        list(free),
        cc.compliance_maker(
            cc.lean_specs(young=young, poisson=poisson, pose_mesh_size=pose_mesh_size), cache_dir
        ),
        frame.compliance_maker(young, poisson),
        max_evaluations=max_evaluations,
        tol=tol,
    )


def lean_spec(
    spec: ModelSpec, max_evaluations: int = MAX_EVALUATIONS, cache_dir: Path | None = None
) -> tuple[ModelSpec, ident.Identification]:
    """The lean stand-in of the default-mesh model ``spec``: the lean mesh, its free dimensions
    (``FREE``) fitted within ``FIT_TOL`` to the four magnitudes of ``spec``'s own FE compliance,
    its pose read at the stage vertices of ``spec``'s mesh (same material and quadrature).

    Parameters
    ----------
    spec : ModelSpec
        A default-mesh Q2 model (its compliance read from ``cache_dir`` or computed).
    max_evaluations : int
        Lean FE models the fit may build (:func:`fit_lean`).
    cache_dir : Path, optional
        FE cache of every compliance the fit reads (``spec``'s and the lean models').

    Returns
    -------
    stand_in : ModelSpec
        ``spec`` with the fitted geometry and ``mesh="lean"`` (its ``mesh_size`` stays: the
        default mesh whose stage vertices carry the pose).
    fit : Identification
        The lean fit (evaluations, achieved magnitudes).

    Raises
    ------
    ValueError
        If ``spec`` is not a default-mesh Q2 model.
    mechlib.hexflex.identify.IdentificationError
        If the fit does not meet ``FIT_TOL`` within ``max_evaluations`` (the message says to
        solve on the default mesh instead).
    """
    if spec.mesh != "default" or spec.element != "q2":
        raise ValueError(
            f"spec must be a default-mesh Q2 model, got mesh={spec.mesh!r}, "
            f"element={spec.element!r}"
        )
    own = ident.target_values(cc.compliance(spec, cache_dir))
    try:
        fit = fit_lean(
            spec.geometry,
            own,
            young=spec.young,
            poisson=spec.poisson,
            max_evaluations=max_evaluations,
            pose_mesh_size=spec.mesh_size,
            cache_dir=cache_dir,
        )
    except ident.IdentificationError as err:
        raise ident.IdentificationError(
            f"no lean stand-in of this model: {err}; solve its non-linear runs on the default "
            f"mesh instead (nonlinear_mesh='default')",
            err.result,
        ) from err
    return replace(spec, geometry=fit.geometry, mesh="lean"), fit


def sweep_design(run: object, amplitudes: Sequence[float]) -> np.ndarray:
    """Force vectors (n, 6) [N] along ``run`` (6,), scaled so that its largest |force| is each of
    ``amplitudes`` [N] (> 0): the DOE chapter's linear-range sweep.

    Raises
    ------
    ValueError
        If ``run`` is not 6 finite forces with one non-zero, or an amplitude is not positive.
    """
    f = check_matrix("run", np.atleast_2d(np.asarray(run, dtype=float)), shape=(1, 6))[0]
    top = float(np.abs(f).max())
    if top == 0.0:
        raise ValueError("run must have a non-zero force, got all zeros")
    amps = [check_float("amplitudes [N]", a, low=0.0, low_open=True) for a in amplitudes]
    return np.outer(amps, f / top)


def compare(
    default_nl: np.ndarray,
    default_linear: np.ndarray,
    lean_nl: np.ndarray,
    lean_linear: np.ndarray,
    ranges: np.ndarray,
) -> dict[str, np.ndarray]:
    """How far the lean model's non-linear poses and departures are from the default model's.

    Parameters
    ----------
    default_nl, default_linear, lean_nl, lean_linear : ndarray (n, 6)
        Non-linear and linear poses [µm, µrad] of the same runs on each model.
    ranges : ndarray (6,)
        Each component's range (> 0).

    Returns
    -------
    dict
        Per component (6,): ``pose_pct``, the largest |lean − default| non-linear pose as % of
        ``ranges``; ``departure_pct``, the largest |lean departure − default departure| as % of
        the default model's largest |departure| (a departure: non-linear minus linear pose).

    Raises
    ------
    ValueError
        If the arrays' shapes differ, a range is not positive, or the default model departs
        nowhere from linearity in a component (nothing to compare against).
    """
    arrays = [
        np.asarray(a, dtype=float) for a in (default_nl, default_linear, lean_nl, lean_linear)
    ]
    shape = arrays[0].shape
    if len(shape) != 2 or shape[1] != 6 or any(a.shape != shape for a in arrays):
        raise ValueError(
            f"poses must be four arrays of one shape (n, 6), got {[a.shape for a in arrays]}"
        )
    ranges = np.asarray(ranges, dtype=float)
    if ranges.shape != (6,) or not np.all(ranges > 0):
        raise ValueError(f"ranges must be 6 positive values, got {ranges}")
    d_nl, d_lin, l_nl, l_lin = arrays
    dep_default, dep_lean = d_nl - d_lin, l_nl - l_lin
    scale = np.abs(dep_default).max(axis=0)
    if not np.all(scale > 0):
        raise ValueError("the default model's departure from linearity is zero in a component")
    return {
        "pose_pct": 100 * np.abs(l_nl - d_nl).max(axis=0) / ranges,
        "departure_pct": 100 * np.abs(dep_lean - dep_default).max(axis=0) / scale,
    }


def compare_runs(
    default: tuple[np.ndarray, np.ndarray, np.ndarray],
    lean: tuple[np.ndarray, np.ndarray, np.ndarray],
    n_runs: int,
    ranges: np.ndarray,
) -> tuple[dict[str, dict[str, np.ndarray]], np.ndarray]:
    """:func:`compare` on the runs both models solved, the first ``n_runs`` rows of the design
    (``"runs"``) and the rest (``"sweep"``) apart.

    Parameters
    ----------
    default, lean : tuple of ndarray
        Each model's ``(ok, nl, linear)``: the design rows that converged (sorted), their
        non-linear poses (len(ok), 6) and the linear poses of every row (n, 6).
    n_runs : int
        Rows of the design that are runs; the rest is the sweep.
    ranges : ndarray (6,)
        Each component's range (> 0).

    Returns
    -------
    parts : dict
        ``{"runs": compare(...), "sweep": compare(...)}``, a part left out when no row of it
        converged on both models.
    both : ndarray
        The rows compared (converged on both).

    Raises
    ------
    RuntimeError
        If no row converged on both models.
    """
    (ok_d, nl_d, lin_d), (ok_l, nl_l, lin_l) = default, lean
    both = np.intersect1d(ok_d, ok_l)
    if not len(both):
        raise RuntimeError("no run converged on both meshes")
    nl_d, nl_l = nl_d[np.searchsorted(ok_d, both)], nl_l[np.searchsorted(ok_l, both)]
    parts = {}
    for part, rows in (("runs", both < n_runs), ("sweep", both >= n_runs)):
        if rows.any():
            parts[part] = compare(
                nl_d[rows], lin_d[both][rows], nl_l[rows], lin_l[both][rows], ranges
            )
    return parts, both


def meets_criteria(pose_pct: object, departure_pct: object, failed_on_lean_only: int = 0) -> bool:
    """Whether a lean stand-in may replace the default mesh.

    Parameters
    ----------
    pose_pct : array_like
        Pose differences, % of full scale (:func:`compare`), finite, not empty.
    departure_pct : array_like
        Departure differences, % of the departure (:func:`compare`), finite, not empty.
    failed_on_lean_only : int
        Runs that failed on the lean mesh only, ≥ 0.

    Returns
    -------
    bool
        Every pose difference within ``POSE_PCT`` %, every departure difference within
        ``DEPARTURE_PCT`` %, and no run that failed on the lean mesh only.

    Raises
    ------
    ValueError
        On an empty or non-finite difference, or a count that is not an integer ≥ 0.
    """
    for name, values in (("pose_pct", pose_pct), ("departure_pct", departure_pct)):
        arr = np.asarray(values, dtype=float)
        if arr.size == 0 or not np.all(np.isfinite(arr)):
            raise ValueError(f"{name} must be finite and not empty (in %), got {values!r}")
    failed_on_lean_only = check_int("failed_on_lean_only", failed_on_lean_only, low=0)
    return bool(
        np.max(pose_pct) <= POSE_PCT
        and np.max(departure_pct) <= DEPARTURE_PCT
        and failed_on_lean_only == 0
    )


def failed_on_lean_only(failed: Iterable[tuple[str, object]], lean: str = "lean mesh") -> list[int]:
    """The runs that failed on the lean mesh and not on the other one.

    Parameters
    ----------
    failed : iterable of (str, FailedRun)
        Each failed run (anything with an ``index``, the run's row in the design) with the name
        of the mesh it failed on.
    lean : str
        The lean mesh's name in ``failed``.

    Returns
    -------
    list of int
        Sorted design rows.
    """
    pairs = list(failed)
    on_lean = {int(f.index) for mesh, f in pairs if mesh == lean}
    return sorted(on_lean - {int(f.index) for mesh, f in pairs if mesh != lean})
