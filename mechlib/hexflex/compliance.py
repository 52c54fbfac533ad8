"""Compliances of FE models as cached campaign tasks.

An identification builds one FE model per step only to read its 6 × 6 compliance — the poses
under the six unit actuator forces. Computed here as one linear task of
:func:`~mechlib.campaign.experiments.run_experiments` (the forces ``np.eye(6)``), a
compliance is cached under its task key like any FE result, logged for the results store, and
read back on the next build instead of meshing and factorising the model again. In one process
the numbers are bit for bit those of :meth:`HexFlexModel.compliance` (the same back-substitution
of the same six unit loads).
"""

from __future__ import annotations

from collections.abc import Callable
from functools import partial
from pathlib import Path

import numpy as np

from mechlib.campaign.experiments import release_models, run_experiments
from mechlib.hexflex.fe.model import check_settings
from mechlib.hexflex.geometry import HexFlexGeometry
from mechlib.hexflex.spec import ModelSpec
from mechlib.params import check_float

SpecMaker = Callable[[HexFlexGeometry], ModelSpec]


def compliance(spec: ModelSpec, cache_dir: Path | None = None) -> np.ndarray:
    """The compliance (6, 6) of ``spec``'s linear model: rows x y z θx θy θz [µm/N, µrad/N],
    columns T1D1 … T3D2 — read from ``cache_dir`` when a build computed it before (``None``:
    no cache)."""
    return run_experiments(spec, np.eye(6), cache_dir=cache_dir, progress=False).T


def default_specs(*, young: float, poisson: float, element: str, mesh_fraction: float) -> SpecMaker:
    """Geometry → :class:`ModelSpec` of the default mesh with flexure elements ``mesh_fraction``
    of its narrowest flexure width (:func:`mechlib.hexflex.fe.model.model_maker`'s recipe); the
    settings are checked here, before any model is built."""
    young, poisson, element, mesh_fraction = check_settings(young, poisson, element, mesh_fraction)
    return partial(
        _default_spec, young=young, poisson=poisson, element=element, mesh_fraction=mesh_fraction
    )


def lean_specs(*, young: float, poisson: float, pose_mesh_size: float | None) -> SpecMaker:
    """Geometry → :class:`ModelSpec` of the lean mesh (:func:`mechlib.hexflex.fe.lean.lean_model`),
    its pose read at the stage vertices of the default mesh of flexure elements
    ``pose_mesh_size`` [mm] (``None``: that model's default)."""
    if pose_mesh_size is not None:
        pose_mesh_size = check_float("pose_mesh_size [mm]", pose_mesh_size, low=0.0, low_open=True)
    young, poisson, _, _ = check_settings(young, poisson, "q2")
    return partial(_lean_spec, young=young, poisson=poisson, pose_mesh_size=pose_mesh_size)


def compliance_maker(specs: SpecMaker, cache_dir: Path | None = None) -> Callable[..., np.ndarray]:
    """Geometry → :func:`compliance` of the model ``specs`` makes of it: the FE side of
    :func:`mechlib.hexflex.identify.identify` and ``log_sensitivity``, cached in ``cache_dir``
    (after each call this process keeps no model: :func:`release_models`)."""
    return partial(_compliance_of, specs, cache_dir)


def _default_spec(
    g: HexFlexGeometry, *, young: float, poisson: float, element: str, mesh_fraction: float
) -> ModelSpec:
    return ModelSpec(
        g, young=young, poisson=poisson, mesh_size=mesh_fraction * g.narrowest, element=element
    )


def _lean_spec(
    g: HexFlexGeometry, *, young: float, poisson: float, pose_mesh_size: float | None
) -> ModelSpec:
    return ModelSpec(g, young=young, poisson=poisson, mesh_size=pose_mesh_size, mesh="lean")


def _compliance_of(specs: SpecMaker, cache_dir: Path | None, g: HexFlexGeometry) -> np.ndarray:
    out = compliance(specs(g), cache_dir)
    release_models()  # an identification builds a new model at every step: keep none of them
    return out
