"""Values of the parallelogram-flexure benchmark, transcribed from its authors' files.

Source: H.-J. Su and B. Survey, "An Open Source Hierarchical Multi-fidelity Modeling Stack for
Design and Analysis of Compliant Mechanisms", Proc. ASME IDETC/CIE 2026, paper DETC2026-19401
(title and number as the repository's README gives them; its LaTeX source prints the title
without "An Open Source" and the number as "DETC2026-XXXXX"; the bibliography's ``su2026stack``).
Data and scripts: the public repository
github.com/haijunsu-osu/parallelogram_model_comparison, commit 20457f6 (the files used here are
unchanged up to ca92a0e). Files:

- ``fea_models/3d/parallelogram_3d.py``: the FE model (geometry, material, loads, probes);
- ``comparison/preset_data/PARALLOGRAM_FEA_3D_sweep_normalized_with_neg_Ay.csv``: the sweep
  (rows kept here: :mod:`.published_sweep`);
- ``fea_models/3d/temp/MESH_REFINEMENT_COMPARISON.md``: the mesh study (:data:`MESH_STUDY`);
- ``comparison/augment_preset_data_neg_ay.py``, ``fea_models/SYMMETRY_NOTES_NEG_FY.md``: how the
  rows with A_y < 0 were made;
- ``IDETC_2026/CM_model_stack_v2.tex`` (the paper's source, in 20457f6 only): tables "Benchmark
  Model Parameters", "FEA Simulation Setup Parameters" (C3D10, 10 mm, NLGEOM) and "Mesh
  convergence study for 3D FEA".

What the sweep's columns are (read from ``parallelogram_3d.py``):

- The model: two steel beams (x from 0 to L, centre lines at y = ±W/2, thickness T along y,
  height H along z) clamped on their faces at x = 0, and a block "stage" x ∈ [L, L + 50 mm]
  spanning both beams, E = 5000 GPa. Solid quadratic tetrahedra (gmsh, "2nd" order, i.e.
  CalculiX C3D10), target size 10 mm in beams and stage (twice the beams' 5 mm thickness, so
  the geometry, not the target, sets the elements through it), geometrically non-linear
  CalculiX, all loads applied proportionally with automatic increments. No base block, despite
  the paper's text.
- Loads (dead, global directions): F_x and F_y as point forces on ONE vertex, (L, 0, 0): the
  middle of the stage's face that joins the beam tips, on the line between the tips, NOT the
  centre of the 50 mm stage. M_z as two opposite forces normal to that face (along ∓x), spread
  over the strips 0 < y < 10 mm and -10 < y < 0, each of magnitude M_z/(10 mm) (resultants
  10 mm apart; the paper says "at y = ±10 mm"). As dead x-forces their moment falls as the stage
  turns (≈ M_z cos φ).
- The moment's SIGN IS LOST: both strip forces are set to |M_z/10 mm| with fixed directions, so
  every row with A_y ≥ 0 was computed with the same counter-clockwise couple +|B| whatever its B
  column says (the rows B and -B are identical, character for character). It is
  counter-clockwise: φ grows with |B|, and :mod:`.elastica` under +|B| matches φ at small A_y.
  The mirrored rows (A_y < 0) therefore hold -|B|. :func:`applied_b` gives the couple that was
  really applied.
- ``ux``, ``uy`` = the displacement (mm) of the node nearest (L, 0, 0) (the load point) divided
  by L, in the global x (along the beams) and y (across). u_y > 0 for A_y > 0; u_x < 0 is the
  shortening. ``phi`` [rad], counter-clockwise positive, from the x, y displacements of the two
  stage corners (L, ±(W/2 + T/2), 0): atan2(Δx_bot − Δx_top, (W + T) − (Δy_top − Δy_bot)). The
  second argument has the wrong sign (it should be +), so for a rigid stage turning by φ the
  file holds atan(sin φ / (2 − cos φ)) ≈ φ(1 − φ²): -0.1 % at 0.03 rad, -11 % at 0.35 rad.
  :func:`reported_rotation` and :func:`rotation_from_reported` convert.
- Resolution: the FE script printed x, y in mm with six significant digits (raw file
  ``fea_models/3d/PARALLOGRAM_FEA_3D_sweep.csv``); the normalised file divides them by L and
  prints the quotient in full, so ux and uy carry six significant digits; phi is printed in full.
- "with_neg_Ay": the 1547 computed rows (13 A_x × 17 A_y ≥ 0 × 7 B) followed by 1456 rows made
  by mirror symmetry about x from every row with A_y > 0: (A_y, A_x, B) → (-A_y, A_x, -B),
  (u_x, u_y, φ) → (u_x, -u_y, -φ); 3003 rows (the paper says 1,517 cases and 3,094 points). The
  mirrored rows print their loads as floats ("-5.0", and "-0.0" for B).

Checked against the benchmark as described to us: geometry, material, the three grids and the
mesh-study numbers agree with the files (the 10 mm mesh is within 1.05 %, 0.60 %, 1.72 % of the
3 mm one); the load point is not the stage centre (see above) and the sign of B is lost.
"""

from __future__ import annotations

import numpy as np

from mechlib.parallelogram.published_sweep import SWEEP_ROWS_AS_PRINTED

# --- Geometry and material (parallelogram_3d.py, PARAMETERS; paper Table "Benchmark Model
# Parameters", whose W = 75 mm is the half separation) --------------------------------------
LENGTH_MM: float = 250.0
"""L, length of each beam [mm]."""
THICKNESS_MM: float = 5.0
"""T, in-plane thickness of each beam (along y) [mm]."""
HEIGHT_MM: float = 50.0
"""H, out-of-plane height of each beam (along z) [mm]."""
SEPARATION_MM: float = 150.0
"""W, distance between the beams' centre lines [mm] (beams at y = ±75 mm)."""
STAGE_LENGTH_MM: float = 50.0
"""Length of the stage block along x, from x = L [mm]."""
MOMENT_STRIP_MM: float = 10.0
"""Width of each of the two strips the couple's forces are spread on [mm] (``MomentArm``)."""
YOUNG_MPA: float = 210e3
"""E of the beams, 210 GPa [N/mm²]."""
POISSON: float = 0.3
"""ν of beams and stage."""
YOUNG_STAGE_MPA: float = 5000e3
"""E of the quasi-rigid stage, 5000 GPa [N/mm²]."""
MESH_SIZE_MM: float = 10.0
"""Characteristic element length of the sweep's mesh [mm]."""

SECOND_MOMENT_MM4: float = HEIGHT_MM * THICKNESS_MM**3 / 12.0
"""I = H T³/12 = 520.83 mm⁴ (bending in the x-y plane)."""
BENDING_STIFFNESS_NMM2: float = YOUNG_MPA * SECOND_MOMENT_MM4
"""EI of one beam [N·mm²]."""
FORCE_UNIT_N: float = BENDING_STIFFNESS_NMM2 / LENGTH_MM**2
"""EI/L², the force of A = 1 [N] (1750 N)."""
MOMENT_UNIT_NMM: float = BENDING_STIFFNESS_NMM2 / LENGTH_MM
"""EI/L, the couple of B = 1 [N·mm]."""
HALF_WIDTH: float = SEPARATION_MM / (2.0 * LENGTH_MM)
"""w = W/(2L) = 0.3, the elastica's half width."""
AXIAL_COMPLIANCE: float = (THICKNESS_MM / LENGTH_MM) ** 2 / 12.0
"""c = EI/(EA L²) = (T/L)²/12, the elastica's axial compliance."""

# --- Load grid (parallelogram_3d.py: AxVal, AyVal, MVal) -----------------------------------
A_X_LEVELS = np.array([-10, -5, -4, -3, -2, -1, 0, 1, 2, 3, 4, 5, 10], dtype=float)
A_Y_COMPUTED_LEVELS = np.array(
    [0, 0.5, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 12, 14, 16, 18, 20], dtype=float
)
A_Y_LEVELS = np.union1d(-A_Y_COMPUTED_LEVELS, A_Y_COMPUTED_LEVELS)
"""The 33 A_y levels of the "with_neg_Ay" file (negative ones mirrored)."""
B_LEVELS = np.array([-3, -2, -1, 0, 1, 2, 3], dtype=float)
SWEEP_ROW_COUNT: int = 3003
"""Rows in the whole "with_neg_Ay" file (1547 computed + 1456 mirrored)."""


def _as_array(name: str, value: object) -> np.ndarray:
    arr = np.asarray(value, dtype=float)
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return arr


def loads_to_newton(a_x: object, a_y: object, b: object) -> tuple[np.ndarray, ...]:
    """(F_x [N], F_y [N], M_z [N·mm]) of the normalised loads (A_x, A_y, B) (scalars or arrays).

    Raises
    ------
    ValueError
        If a value is not finite.
    """
    return (
        _as_array("a_x", a_x) * FORCE_UNIT_N,
        _as_array("a_y", a_y) * FORCE_UNIT_N,
        _as_array("b", b) * MOMENT_UNIT_NMM,
    )


def newton_to_loads(f_x: object, f_y: object, m_z: object) -> tuple[np.ndarray, ...]:
    """(A_x, A_y, B) of the loads F_x [N], F_y [N], M_z [N·mm]: the inverse of
    :func:`loads_to_newton`.

    Raises
    ------
    ValueError
        If a value is not finite.
    """
    return (
        _as_array("f_x", f_x) / FORCE_UNIT_N,
        _as_array("f_y", f_y) / FORCE_UNIT_N,
        _as_array("m_z", m_z) / MOMENT_UNIT_NMM,
    )


def to_mm(u_over_l: object) -> np.ndarray:
    """Displacement [mm] of a normalised displacement u/L."""
    return _as_array("u_over_l", u_over_l) * LENGTH_MM


def from_mm(u_mm: object) -> np.ndarray:
    """Normalised displacement u/L of a displacement [mm]."""
    return _as_array("u_mm", u_mm) / LENGTH_MM


def reported_rotation(phi: object) -> np.ndarray:
    """What the FE script's formula reports for a rigid stage turned by ``phi`` [rad]:
    atan(sin φ / (2 − cos φ)) (see the module docstring)."""
    phi = _as_array("phi", phi)
    return np.arctan(np.sin(phi) / (2.0 - np.cos(phi)))


def rotation_from_reported(psi: object) -> np.ndarray:
    """The rigid rotation φ [rad] whose reported value is ``psi``: φ = asin(2 sin ψ) − ψ, the
    inverse of :func:`reported_rotation` for |ψ| < π/6 (|φ| < π/3).

    Raises
    ------
    ValueError
        If a value is not finite or |ψ| ≥ π/6 (no rigid rotation below π/3 reports it).
    """
    psi = _as_array("psi", psi)
    if np.any(np.abs(psi) >= np.pi / 6.0):
        raise ValueError(f"psi must be in (-pi/6, pi/6) rad, got {psi!r}")
    return np.arcsin(2.0 * np.sin(psi)) - psi


def applied_b(a_y: object, b: object) -> np.ndarray:
    """The couple B really applied in a sweep row: +|B| for A_y ≥ 0 (computed rows), -|B| for
    A_y < 0 (mirrored rows); the file's B column has the intended sign, which the FE lost."""
    a_y, b = _as_array("a_y", a_y), _as_array("b", b)
    return np.where(a_y < 0.0, -np.abs(b), np.abs(b))


# --- Mesh study (fea_models/3d/temp/MESH_REFINEMENT_COMPARISON.md, "Results"; the paper's
# Table "Mesh convergence study for 3D FEA" prints the sizes, elements and the y errors):
# case A_x = 0, A_y = 5, B = 0; x, y: load-point displacement [mm], phi [rad] as printed --------
MESH_STUDY_COLUMNS: tuple[str, ...] = ("mesh_mm", "nodes", "elements", "x_mm", "y_mm", "phi")
_MESH_STUDY = """
10   9450   4878  -5.7117  48.3180  0.001255
7.5  18566  10000 -5.7370  48.4389  0.001262
5    42682  24558 -5.7515  48.5085  0.001269
4    76246  45332 -5.7655  48.5761  0.001274
3    154796 95810 -5.7723  48.6102  0.001277
"""
MESH_STUDY = np.array(
    [[float(c) for c in line.split()] for line in _MESH_STUDY.split("\n") if line]
)
"""The mesh study, one row per mesh, columns :data:`MESH_STUDY_COLUMNS`."""
MESH_STUDY_LOADS: tuple[float, float, float] = (0.0, 5.0, 0.0)
"""(A_x, A_y, B) of the mesh study."""
MESH_STUDY_RESOLUTION = np.array([0.0, 0.0, 0.0, 5e-5, 5e-5, 5e-7])
"""Half a unit of the last printed digit of each column of :data:`MESH_STUDY`."""
#: the study's printed "Difference From 3 mm Reference" of the 10 mm mesh: dx, dy, dphi [%]
MESH_STUDY_10MM_PERCENT: tuple[float, float, float] = (1.05, 0.60, 1.72)

# --- Sweep subset (PARALLOGRAM_FEA_3D_sweep_normalized_with_neg_Ay.csv; rows in
# published_sweep.py) ------------------------------------------------------------------------
SWEEP_COLUMNS: tuple[str, ...] = ("A_x", "A_y", "B", "u_x/L", "u_y/L", "phi")
_FILE_ORDER = (1, 0, 2, 3, 4, 5)  # the file's columns are Ay, Ax, B, ux, uy, phi


def _parse_sweep(text: str) -> np.ndarray:
    rows = [line.split(",") for line in text.split("\n") if line.strip()]
    if any(len(r) != 6 for r in rows):
        raise ValueError("every sweep row must have six cells (Ay, Ax, B, ux, uy, phi)")
    return np.array([[float(r[k]) for k in _FILE_ORDER] for r in rows])


SWEEP_SUBSET = _parse_sweep(SWEEP_ROWS_AS_PRINTED)
"""The kept sweep rows (file order), columns :data:`SWEEP_COLUMNS`: A_x, A_y, B as the file
prints them (B: see :func:`applied_b`), u_x/L, u_y/L and φ [rad] (as reported, see
:func:`rotation_from_reported`). Rows: the 8 corners (A_x = ±10, A_y = ±20, B = ±3) and every row
with A_x ∈ {-5, 0, 5} and B ∈ {-3, 0, 3} over the 33 A_y levels (which includes the mesh-study
case A_x = 0, A_y = 5, B = 0)."""
SWEEP_RELATIVE_RESOLUTION: float = 5e-6
"""Half a unit of the sixth significant digit, relative: the printed resolution of u_x, u_y."""


def sweep_line(a_x: float, b: float) -> np.ndarray:
    """The kept rows with this A_x and printed B, sorted by A_y, columns :data:`SWEEP_COLUMNS`.

    Raises
    ------
    ValueError
        If no kept row has this (A_x, B): the lines kept are A_x ∈ {-5, 0, 5}, B ∈ {-3, 0, 3}.
    """
    sel = (SWEEP_SUBSET[:, 0] == a_x) & (SWEEP_SUBSET[:, 2] == b)
    if not np.any(sel):
        raise ValueError(f"(a_x, b) must be in {{-5, 0, 5}} x {{-3, 0, 3}}, got ({a_x!r}, {b!r})")
    rows = SWEEP_SUBSET[sel]
    return rows[np.argsort(rows[:, 1], kind="stable")]


def sweep_corners() -> np.ndarray:
    """The 8 kept corner rows (A_x = ±10, A_y = ±20, B = ±3), columns :data:`SWEEP_COLUMNS`."""
    return SWEEP_SUBSET[np.abs(SWEEP_SUBSET[:, 0]) == 10.0]
