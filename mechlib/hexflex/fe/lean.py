"""The lean HexFlex FE model: a coarser mesh with the default model's pose definition.

The stage pose of :class:`~mechlib.hexflex.fe.model.HexFlexModel` is an unweighted least-squares
rigid fit over the stage's mesh vertices (:func:`mechlib.hexflex.fe.pose.fit_operator`). The
stage is nearly rigid but not rigid (it bends under the out-of-plane loads), so the fitted pose
is a vertex-density-weighted average of its motion: coarsening the stage's mesh changes the
quantity of interest itself (z←T1D2 and θx←T1D2 by 1–5 % at fixed dimensions), not only its
discretisation error.

:class:`StageFitModel` keeps that definition whatever its own mesh: its pose is the same rigid
fit over the stage vertices of the *default* mesh of the same geometry (meshed, not solved),
with the displacements there interpolated from the model's own Q2 field by a sparse matrix built
once. With the default mesh it reproduces the default model's poses exactly.

:func:`lean_model` is the recipe the cheaper non-linear runs use (``LEAN``): two Q2 elements
across every flexure (``mesh_size`` 0.6 of the narrowest width), flexure elements growing to
``LEAN["mid_widths"]`` widths mid-way, stage and tabs graded from the flexures' corners to 30
narrowest widths, the pose fitted as by the default model. Identified to Eq 8 like the default
model, it gives the same non-linear poses within a small fraction of their range at a fraction
of the cost (``make bench``, section ``lean``).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from threadpoolctl import threadpool_limits

from mechlib.hexflex import geometry as geo
from mechlib.hexflex.fe import mesh as ms
from mechlib.hexflex.fe.model import (
    COARSE_WIDTHS,
    DEFAULT_MESH_FRACTION,
    HexFlexModel,
    coarsening_for,
)
from mechlib.hexflex.fe.pose import fit_operator

#: The lean mesh: flexure element size (fraction of the narrowest flexure width), largest
#: stage and tab element (narrowest widths), their size gradient (``mesh.sector_mesh``'s
#: ``body_grading``) and the flexure elements' length mid-way (widths).
LEAN: dict[str, float] = {
    "mesh_fraction": 0.6,
    "coarse_widths": 30.0,
    "body_grading": 1.0,
    "mid_widths": 4.0,
}
#: Largest excursion of a stage vertex's reference coordinates outside [0, 1] that is taken as
#: round-off (the vertices lie on element faces) and clipped; more is an error.
REF_TOL = 1e-6


def default_stage_points(g: geo.HexFlexGeometry) -> np.ndarray:
    """The stage vertices (n, 3) [mm] the default model of ``g`` fits its pose on."""
    size = DEFAULT_MESH_FRACTION * g.narrowest
    sector = ms.sector_mesh(g, size, coarsening_for(COARSE_WIDTHS, DEFAULT_MESH_FRACTION))
    coors, _ = ms.extrude(ms.full_mesh(sector, size), g.thickness)
    return coors[geo.in_stage(coors, g)]


def interpolation_matrix(model: HexFlexModel, points: np.ndarray) -> sp.csr_array:
    """Sparse (3 n, n_dofs): the model's reduced displacement vector → displacements at
    ``points`` (n, 3) [mm] inside its mesh, x y z per point, by its Q2 interpolation.

    Raises
    ------
    ValueError
        If a point lies outside the mesh, or in an element with clamped nodes.
    """
    from sfepy.discrete.common.global_interp import get_ref_coors

    fld = model.fe.field
    pts = np.ascontiguousarray(points, dtype=float)
    ref, cells, status = get_ref_coors(fld, pts, close_limit=0.1)
    outside = np.abs(np.clip(ref, 0.0, 1.0) - ref).max(axis=1) > REF_TOL
    if np.any(status > 1) or np.any(outside):
        raise ValueError(
            f"points must lie inside the model's mesh: {int(np.sum((status > 1) | outside))} "
            f"of {len(pts)} do not"
        )
    basis = fld.poly_space.eval_basis(np.clip(ref, 0.0, 1.0)).reshape(len(pts), -1)
    econn = fld.get_econn(("cell", fld.region.tdim), fld.region)[cells]  # (n, nodes/element)
    eq = model.fe.eq.reshape(-1, model.fe.n_comp)
    rows, cols, vals = [], [], []
    for c in range(3):
        dofs = eq[econn, c]
        if np.any(dofs < 0):
            raise ValueError("points must lie in elements without clamped nodes")
        rows.append(np.repeat(3 * np.arange(len(pts)) + c, econn.shape[1]))
        cols.append(dofs.ravel())
        vals.append(basis.ravel())
    shape = (3 * len(pts), model.n_dofs)
    return sp.csr_array((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape)


class StageFitModel(HexFlexModel):
    """:class:`HexFlexModel` whose pose is fitted at the default mesh's stage vertices
    (interpolated from its own field), whatever its own stage mesh. Same parameters."""

    def __post_init__(self) -> None:
        super().__post_init__()
        self._points = default_stage_points(self.geometry)
        self._interp = interpolation_matrix(self, self._points)
        self._fit = fit_operator(self._points)

    def pose_of(self, reduced: np.ndarray) -> np.ndarray:
        """Stage pose(s) [µm, µrad] of reduced displacement vector(s): (6,) or (6, n)."""
        with threadpool_limits(limits=1, user_api="blas"):  # as HexFlexModel.pose_of
            return self._fit @ (self._interp @ reduced)

    def stage_motion(self, reduced: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The default mesh's stage vertices (m, 3) [mm] and their displacements (m, 3) [mm],
        interpolated: what :meth:`pose_of` fits."""
        return self._points, (self._interp @ np.asarray(reduced)).reshape(-1, 3)


def lean_model(
    geometry: geo.HexFlexGeometry, young: float | None = None, poisson: float | None = None
) -> StageFitModel:
    """The lean model (``LEAN``) of ``geometry``; material as :class:`HexFlexModel`'s
    defaults unless given."""
    fraction = LEAN["mesh_fraction"]
    material = {k: v for k, v in (("young", young), ("poisson", poisson)) if v is not None}
    return StageFitModel(
        geometry,
        mesh_size=fraction * geometry.narrowest,
        coarsening=coarsening_for(LEAN["coarse_widths"], fraction),
        body_grading=LEAN["body_grading"],
        mid_widths=LEAN["mid_widths"],
        **material,
    )
