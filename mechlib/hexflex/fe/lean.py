"""The lean HexFlex FE model: a coarser mesh with the default model's pose definition.

The stage pose of :class:`~mechlib.hexflex.fe.model.HexFlexModel` is an unweighted least-squares
rigid fit over the stage's mesh vertices (:func:`mechlib.fe.pose.fit_operator`). The
stage is nearly rigid but not rigid (it bends under the out-of-plane loads), so the fitted pose
is a vertex-density-weighted average of its motion: coarsening the stage's mesh changes the
quantity of interest itself (z←T1D2 and θx←T1D2 by 1–5 % at fixed dimensions), not only its
discretisation error.

:class:`StageFitModel` keeps that definition whatever its own mesh: its pose is the same rigid
fit over the stage vertices of a *default* mesh of the same geometry (meshed, not solved; its
flexure element size ``pose_mesh_size``), with the displacements there interpolated from the
model's own Q2 field by a sparse matrix built once. On that default mesh itself it reproduces
the default model's poses to the precision of the interpolation points' reference coordinates
(≈ 1e-8 of an element).

:func:`lean_model` is the recipe the cheaper non-linear runs use (``LEAN``): flexure elements
0.6 of the narrowest flexure width (two across the narrowest), growing to ``LEAN["mid_widths"]``
widths mid-way along each flexure, stage and tabs graded from the flexures' corners up to 30
narrowest widths, the pose fitted as by the default model. A lean model stands for the default
model it was fitted to (:func:`mechlib.hexflex.studies.leanmesh.fit_lean`: the same magnitudes
of the compliance); on the identified HexFlex it gives the same non-linear poses within a small
fraction of their range at a fraction of the cost (``make bench``, section ``lean``).
"""

from __future__ import annotations

from dataclasses import dataclass
from types import MappingProxyType

import numpy as np
import scipy.sparse as sp

from mechlib.blas import one_thread
from mechlib.fe.pose import fit_operator
from mechlib.hexflex import geometry as geo
from mechlib.hexflex.fe import mesh as ms
from mechlib.hexflex.fe.model import (
    COARSE_WIDTHS,
    DEFAULT_MESH_FRACTION,
    HexFlexModel,
    coarsening_for,
)
from mechlib.params import check_float

#: The lean mesh: flexure element size (fraction of the narrowest flexure width), largest
#: stage and tab element (narrowest widths), their size gradient (``mesh.sector_mesh``'s
#: ``body_grading``) and the flexure elements' length mid-way (widths).
LEAN = MappingProxyType(
    {"mesh_fraction": 0.6, "coarse_widths": 30.0, "body_grading": 1.0, "mid_widths": 4.0}
)
#: Largest excursion of a stage vertex's reference coordinates outside [0, 1] that is taken as
#: round-off (the vertices lie on element faces) and clipped; more is an error.
REF_TOL = 1e-6


def default_stage_points(g: geo.HexFlexGeometry, size: float | None = None) -> np.ndarray:
    """The stage vertices (n, 3) [mm] the default model of ``g`` with flexure elements ``size``
    [mm] (default ``DEFAULT_MESH_FRACTION`` of the narrowest flexure width) fits its pose on."""
    size = DEFAULT_MESH_FRACTION * g.narrowest if size is None else size
    sector = ms.sector_mesh(g, size, coarsening_for(COARSE_WIDTHS, size / g.narrowest))
    coors, _ = ms.extrude(ms.full_mesh(sector, size), g.thickness)
    return coors[geo.in_stage(coors, g)]


def interpolation_matrix(model: HexFlexModel, points: np.ndarray) -> sp.csr_array:
    """Sparse (3 n, n_dofs): the model's reduced displacement vector → displacements at
    ``points`` (n, 3) [mm] inside its mesh, x y z per point, by its Q2 interpolation.

    A point on an element's face or edge gets reference coordinates outside [0, 1] by round-off;
    excursions up to ``REF_TOL`` are clipped to the element, larger ones are refused.

    Raises
    ------
    ValueError
        If points lie outside the mesh, or in elements with clamped nodes (how many).
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
    clamped = np.any(eq[econn] < 0, axis=(1, 2))
    if np.any(clamped):
        raise ValueError(
            f"points must lie in elements without clamped nodes: {int(clamped.sum())} of "
            f"{len(pts)} do not"
        )
    for c in range(3):
        dofs = eq[econn, c]
        rows.append(np.repeat(3 * np.arange(len(pts)) + c, econn.shape[1]))
        cols.append(dofs.ravel())
        vals.append(basis.ravel())
    shape = (3 * len(pts), model.n_dofs)
    return sp.csr_array((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape)


@dataclass
class StageFitModel(HexFlexModel):
    """:class:`HexFlexModel` whose pose is fitted at a default mesh's stage vertices
    (interpolated from its own field), whatever its own stage mesh.

    Parameters
    ----------
    (those of :class:`HexFlexModel`), and
    pose_mesh_size : float, optional
        Flexure element size [mm] of the default mesh whose stage vertices define the pose
        (default: ``DEFAULT_MESH_FRACTION`` of the narrowest flexure width), in (0, the
        narrowest flexure width].
    """

    pose_mesh_size: float | None = None

    def __post_init__(self) -> None:
        g = self.geometry
        if self.pose_mesh_size is not None:
            self.pose_mesh_size = check_float(
                "pose_mesh_size [mm]", self.pose_mesh_size, low=0.0, high=g.narrowest,
                low_open=True,
            )  # fmt: skip
        super().__post_init__()
        self._points = default_stage_points(g, self.pose_mesh_size)
        self._interp = interpolation_matrix(self, self._points)
        self._fit = fit_operator(self._points)

    def pose_of(self, reduced: np.ndarray) -> np.ndarray:
        """Stage pose(s) [µm, µrad] of reduced displacement vector(s): (6,) or (6, n)."""
        with one_thread():  # as HexFlexModel.pose_of
            return self._fit @ (self._interp @ reduced)

    def stage_motion(self, reduced: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The default mesh's stage vertices (m, 3) [mm] and their displacements (m, 3) [mm],
        interpolated: what :meth:`pose_of` fits."""
        return self._points, (self._interp @ np.asarray(reduced)).reshape(-1, 3)

    def poses_plain_sfepy(self, forces: object) -> np.ndarray:
        """Not available: SfePy's plain path fits the pose on the model's own stage nodes."""
        raise NotImplementedError(
            "poses_plain_sfepy fits the pose on the model's own stage nodes; a StageFitModel "
            "fits it elsewhere: use poses()"
        )


def lean_model(
    geometry: geo.HexFlexGeometry,
    young: float | None = None,
    poisson: float | None = None,
    pose_mesh_size: float | None = None,
) -> StageFitModel:
    """The lean model (``LEAN``) of ``geometry``, its pose fitted at the stage vertices of the
    default mesh with flexure elements ``pose_mesh_size`` [mm] (:class:`StageFitModel`);
    material as :class:`HexFlexModel`'s defaults unless given."""
    fraction = LEAN["mesh_fraction"]
    material = {k: v for k, v in (("young", young), ("poisson", poisson)) if v is not None}
    return StageFitModel(
        geometry,
        mesh_size=fraction * geometry.narrowest,
        coarsening=coarsening_for(LEAN["coarse_widths"], fraction),
        body_grading=LEAN["body_grading"],
        mid_widths=LEAN["mid_widths"],
        pose_mesh_size=pose_mesh_size,
        **material,
    )
