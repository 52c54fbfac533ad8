"""The FE runs of the book, from the results store, as tables of the data bundle.

The results store (``store/``, :mod:`mechlib.hexflex.campaign.store`) holds every FE task the
book's notebooks read: the runs behind the tables and figures of chapter 2 and of the pages
beyond it. :func:`store_tables` lays them out as CSV texts:

* ``runs/models.csv``: one row per FE model (model id, mesh, element size, element, material,
  every geometry dimension in mm, the free DOF count where a run measured it): the identified
  HexFlex on its default and lean meshes, the mesh-convergence and family geometries;
* ``runs/linear_runs.csv``: every linear run (model id, forces [N], pose [µm, µrad]);
* ``runs/nonlinear_runs.csv``: every non-linear run (model id, load steps, forces, the pose in
  the three conventions of :mod:`mechlib.fe.finite_pose`, the solve statistics).

A run that did not converge has no result, so it is not in the store; the records list those.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from mechlib import published as pub
from mechlib.hexflex.campaign.experiments import POSE_CONVENTIONS, SOLVE_STATS
from mechlib.hexflex.campaign.store import family, read_store
from mechlib.pipeline.bundle import csv_text

_FORCES = [f"{f} [N]" for f in pub.FACTORS]
_POSES = [f"{r} [{u}]" for r, u in zip(pub.RESPONSES, pub.RESPONSE_UNITS, strict=True)]
_STATS_UNITS = {"residual": "relative"}

README = """\
runs/     every FE run the book reads from its results store (the runs behind chapter 2's
          tables and figures and the pages beyond it), computed by the commit the landing names:
          models.csv          one row per FE model: model id, mesh ("default" or "lean"),
                              element size [mm] (of a lean model: the default mesh's size on whose
                              stage vertices its pose is fitted), element, Young's modulus [MPa],
                              Poisson's ratio, quadrature order, coarsening (the default mesh's
                              growth away from the flexures; empty: its default), geometry [mm],
                              free DOFs (where a run counted them)
          linear_runs.csv     model id, forces T1D1..T3D2 [N], pose x y z [um], thx thy thz
                              [urad] (small-rotation fit of the stage nodes)
          nonlinear_runs.csv  model id, load steps, forces [N], the pose in three conventions
                              (small: small-rotation fit; rotvec: exact rigid registration as
                              translation + rotation vector; euler_xyz: the same as intrinsic
                              Euler XYZ angles) [um, urad], and the solve statistics (Newton
                              corrections, factorisations, restarts, final relative residual)
          A run that did not converge has no result and is not listed; the records name them.
"""


def _model_rows(specs: list[str], sizes: dict[str, int]) -> tuple[list[str], list[list[object]]]:
    parsed = [json.loads(s) for s in specs]
    dims = sorted({k for p in parsed for k in p.get("geometry", {})})
    header = [
        "model",
        "mesh",
        "element size [mm]",
        "element",
        "Young's modulus [MPa]",
        "Poisson's ratio",
        "quadrature order",
        "coarsening",
        *(f"{d} [mm]" for d in dims),
        "free DOFs",
    ]
    rows = []
    for i, (s, p) in enumerate(zip(specs, parsed, strict=True)):
        geo = p.get("geometry", {})
        rows.append(
            [
                f"M{i + 1}",
                p.get("mesh", ""),
                float(p["mesh_size"]) if p.get("mesh_size") is not None else "",
                p.get("element", ""),
                float(p["young"]),
                float(p["poisson"]),
                p.get("quad_order", ""),
                float(p["coarsening"]) if "coarsening" in p else "",
                *(float(geo[d]) if d in geo else "" for d in dims),
                sizes.get(s, ""),
            ]
        )
    return header, rows


def store_tables(store: Path) -> dict[str, str]:
    """The store's runs as CSV texts by file name in the bundle (see the module's docstring).

    Raises
    ------
    StoreError
        A store that cannot be read as it is (checksum, keys), as
        :func:`~mechlib.hexflex.campaign.store.read_store` says.
    """
    _, entries = read_store(Path(store))
    # the HexFlex's runs (the parallelogram's are in its page's data: its sweep table)
    entries = [e for e in entries if family(e.spec) == "hexflex"]
    order = sorted({e.spec for e in entries}, key=lambda s: (json.loads(s).get("mesh", ""), s))
    model = {s: f"M{i + 1}" for i, s in enumerate(order)}
    sizes = {e.spec: int(e.results[0, 0]) for e in entries if e.kind == "size"}
    linear, nonlinear = [], []
    for e in sorted(entries, key=lambda e: (order.index(e.spec), e.kind, e.key)):
        if e.kind == "linear":
            linear += [[model[e.spec], *f, *r] for f, r in zip(e.forces, e.results, strict=True)]
        elif e.kind == "nonlinear":
            nonlinear += [
                [model[e.spec], e.steps, *f, *r] for f, r in zip(e.forces, e.results, strict=True)
            ]
    poses = [f"{c} {p}" for c in POSE_CONVENTIONS for p in _POSES]
    stats = [f"{s} [{_STATS_UNITS.get(s, 'count')}]" for s in SOLVE_STATS]
    header, rows = _model_rows(order, sizes)
    return {
        "runs/models.csv": csv_text(header, rows),
        "runs/linear_runs.csv": csv_text(["model", *_FORCES, *_POSES], _floats(linear)),
        "runs/nonlinear_runs.csv": csv_text(
            ["model", "load steps", *_FORCES, *poses, *stats], _floats(nonlinear)
        ),
    }


def _floats(rows: list[list[object]]) -> list[list[object]]:
    """Rows with numpy numbers as Python floats (CSV writes them as their shortest decimal)."""
    return [[float(v) if isinstance(v, np.floating) else v for v in row] for row in rows]
