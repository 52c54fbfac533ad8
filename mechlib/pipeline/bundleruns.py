"""The FE runs of the book, from the results store, as tables of the data bundle.

The results store (``store/``, :mod:`mechlib.campaign.store`) holds every FE task the
book's notebooks read: the runs behind the tables and figures of chapter 2 and of the pages
beyond it, the HexFlex's and the compliant layouts' (the parallelogram flexure).
:func:`store_tables` lays them out as CSV texts:

* ``runs/models.csv``: one row per HexFlex FE model (model id, mesh, element size, element,
  material, every geometry dimension in mm, the free DOF count where a run measured it): the
  identified HexFlex on its default and lean meshes, the mesh-convergence and family geometries;
* ``runs/linear_runs.csv``: every linear run of the HexFlex (model id, forces [N], pose [µm, µrad]);
* ``runs/nonlinear_runs.csv``: every non-linear run of the HexFlex (model id, load steps, forces,
  the pose in the three conventions of :mod:`mechlib.fe.finite_pose`, the solve statistics);
* ``runs/layout_models.csv`` and ``runs/layout_nonlinear_runs.csv``: the same for the compliant
  layouts of :mod:`mechlib.compliant` (one row per model with its full specification as JSON;
  loads in each port's unit).

The tables hold as many runs of each kind as the store's manifest counts (the landing page
quotes that count), or :func:`store_tables` refuses; :func:`readme` says how many each file holds.
A run that did not converge has no result, so it is not in the store; the records list those.
"""

from __future__ import annotations

import csv
import io
import json
import textwrap
from pathlib import Path

import numpy as np

from mechlib import published as pub
from mechlib.campaign.experiments import POSE_CONVENTIONS, SOLVE_STATS
from mechlib.campaign.store import Entry, StoreError, family, read_store
from mechlib.fespecs import HEXFLEX, MECHANISM
from mechlib.pipeline.bundle import csv_text

_FORCES = [f"{f} [N]" for f in pub.FACTORS]
_POSES = [f"{r} [{u}]" for r, u in zip(pub.RESPONSES, pub.RESPONSE_UNITS, strict=True)]
_STATS_UNITS = {"residual": "relative"}
#: the bundle's files of runs, by kind of run (the manifest's ``runs`` counts them)
RUN_FILES: dict[str, tuple[str, ...]] = {
    "linear": ("runs/linear_runs.csv", "runs/layout_linear_runs.csv"),
    "nonlinear": ("runs/nonlinear_runs.csv", "runs/layout_nonlinear_runs.csv"),
}

README = """\
runs/     every FE run the book reads from its results store (the runs behind chapter 2's
          tables and figures and the pages beyond it), computed by the commit the landing names:
{counts}
          models.csv          one row per HexFlex FE model: model id, mesh ("default" or "lean"),
                              element size [mm] (of a lean model: the default mesh's size on whose
                              stage vertices its pose is fitted), element, Young's modulus [MPa],
                              Poisson's ratio, quadrature order, coarsening (the default mesh's
                              growth away from the flexures; empty: its default), geometry [mm],
                              free DOFs (where a run counted them)
          linear_runs.csv     the HexFlex's linear runs: model id, forces T1D1..T3D2 [N], pose
                              x y z [um], thx thy thz [urad] (small-rotation fit of the stage
                              nodes)
          nonlinear_runs.csv  the HexFlex's non-linear runs: model id, load steps, forces [N],
                              the pose in three conventions (small: small-rotation fit;
                              rotvec: exact rigid registration as translation + rotation
                              vector; euler_xyz: the same as intrinsic Euler XYZ angles)
                              [um, urad], and the solve statistics (Newton corrections,
                              factorisations, restarts, final relative residual)
          layout_models.csv   one row per FE model of a compliant layout (the parallelogram
                              flexure): model id, element size [mm], layers through the
                              thickness, thickness [mm], Young's modulus [MPa], Poisson's ratio,
                              and the model's full specification (JSON: parts, clamp, stage, load
                              ports, material regions)
          layout_nonlinear_runs.csv   as nonlinear_runs.csv, the loads in each port's unit
          A run that did not converge has no result and is not listed; the records name them.
"""


def run_counts(tables: dict[str, str]) -> dict[str, int]:
    """The number of runs (data rows) of each CSV table of runs in ``tables``, by file name."""
    return {
        name: sum(1 for _ in csv.reader(io.StringIO(text))) - 1
        for name, text in tables.items()
        if name.endswith("_runs.csv")
    }


def readme(tables: dict[str, str]) -> str:
    """The bundle README's paragraph on ``tables`` (:func:`store_tables`), with how many runs
    each file holds."""
    counts = run_counts(tables)
    totals = {kind: sum(counts.get(n, 0) for n in files) for kind, files in RUN_FILES.items()}
    listed = "; ".join(f"{n.removeprefix('runs/')}: {c}" for n, c in counts.items())
    text = f"{totals['nonlinear']} non-linear and {totals['linear']} linear runs in all ({listed})"
    return README.format(
        counts=textwrap.fill(text, width=96, initial_indent=" " * 10, subsequent_indent=" " * 10)
    )


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
        :func:`~mechlib.campaign.store.read_store` says; or tables that do not hold as
        many linear and non-linear runs as the manifest counts.
    """
    manifest, entries = read_store(Path(store))
    tables = _hexflex_tables([e for e in entries if family(e.spec) == HEXFLEX.name])
    layouts = [e for e in entries if family(e.spec) == MECHANISM.name]
    if layouts:
        tables.update(_layout_tables(layouts))
    counts = run_counts(tables)
    for kind, files in RUN_FILES.items():
        held = sum(counts.get(name, 0) for name in files)
        if held != manifest["runs"].get(kind, 0):
            raise StoreError(
                f"the bundle's tables hold {held} {kind} runs, the store's manifest counts "
                f"{manifest['runs'].get(kind, 0)}"
            )
    return tables


def _ordered(entries: list[Entry], key) -> tuple[list[str], list[Entry]]:
    """The entries' specifications in ``key`` order, and the entries by model, kind and key."""
    order = sorted({e.spec for e in entries}, key=key)
    rank = {s: i for i, s in enumerate(order)}
    return order, sorted(entries, key=lambda e: (rank[e.spec], e.kind, e.key))


def _run_rows(entries: list[Entry], model: dict[str, str]) -> tuple[list, list]:
    """The linear and non-linear rows: model id (and load steps), loads, results."""
    linear, nonlinear = [], []
    for e in entries:
        if e.kind == "linear":
            linear += [[model[e.spec], *f, *r] for f, r in zip(e.forces, e.results, strict=True)]
        elif e.kind == "nonlinear":
            nonlinear += [
                [model[e.spec], e.steps, *f, *r] for f, r in zip(e.forces, e.results, strict=True)
            ]
    return linear, nonlinear


def _nonlinear_columns() -> list[str]:
    poses = [f"{c} {p}" for c in POSE_CONVENTIONS for p in _POSES]
    return [*poses, *(f"{s} [{_STATS_UNITS.get(s, 'count')}]" for s in SOLVE_STATS)]


def _hexflex_tables(entries: list[Entry]) -> dict[str, str]:
    """The HexFlex's models, linear and non-linear runs."""
    order, entries = _ordered(entries, lambda s: (json.loads(s).get("mesh", ""), s))
    model = {s: f"M{i + 1}" for i, s in enumerate(order)}
    sizes = {e.spec: int(e.results[0, 0]) for e in entries if e.kind == "size"}
    linear, nonlinear = _run_rows(entries, model)
    header, rows = _model_rows(order, sizes)
    return {
        "runs/models.csv": csv_text(header, rows),
        "runs/linear_runs.csv": csv_text(["model", *_FORCES, *_POSES], _floats(linear)),
        "runs/nonlinear_runs.csv": csv_text(
            ["model", "load steps", *_FORCES, *_nonlinear_columns()], _floats(nonlinear)
        ),
    }


def _layout_tables(entries: list[Entry]) -> dict[str, str]:
    """The compliant layouts' models and runs (a layout's loads: its ports, in their units)."""
    order, entries = _ordered(entries, lambda s: s)
    parsed = [json.loads(s)["mechanism"] for s in order]
    ports = [[f"{ld['name']} [{ld['unit']}]" for ld in p["layout"]["loads"]] for p in parsed]
    if any(p != ports[0] for p in ports):
        raise StoreError(f"the compliant layouts' runs have different load ports: {ports}")
    model = {s: f"L{i + 1}" for i, s in enumerate(order)}
    models = [
        [model[s], float(p["mesh_size"]), p["layers"], float(p["layout"]["thickness"]),
         float(p["layout"]["young"]), float(p["layout"]["poisson"]), s]
        for s, p in zip(order, parsed, strict=True)
    ]  # fmt: skip
    head = ["model", "element size [mm]", "layers", "thickness [mm]", "Young's modulus [MPa]",
            "Poisson's ratio", "specification (JSON)"]  # fmt: skip
    linear, nonlinear = _run_rows(entries, model)
    out = {
        "runs/layout_models.csv": csv_text(head, models),
        "runs/layout_nonlinear_runs.csv": csv_text(
            ["model", "load steps", *ports[0], *_nonlinear_columns()], _floats(nonlinear)
        ),
    }
    if linear:
        out["runs/layout_linear_runs.csv"] = csv_text(
            ["model", *ports[0], *_POSES], _floats(linear)
        )
    return out


def _floats(rows: list[list[object]]) -> list[list[object]]:
    """Rows with numpy numbers as Python floats (CSV writes them as their shortest decimal)."""
    return [[float(v) if isinstance(v, np.floating) else v for v in row] for row in rows]
