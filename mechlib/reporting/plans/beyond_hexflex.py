"""Record plan of "Beyond the HexFlex: a parallelogram flexure against a published 3-D FE"
(``notebooks/beyond_hexflex.ipynb``): every key the notebook records, with its tolerance, glue,
texts and report rows, the published numbers and bounds the page quotes, and the description of
the data it keeps. Its claims are judged by the claims registry
(:mod:`mechlib.reporting.claimlist`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from mechlib.parallelogram import comparison as cmp
from mechlib.parallelogram import published as pub
from mechlib.reporting import report
from mechlib.reporting.recordplan import Entry
from mechlib.reporting.tolerances import (
    CLOSED_FORM,
    ELASTICA,
    ELASTICA_GAP_PCT,
    ELASTICA_PCT,
    EXACT,
    ROUNDOFF,
)

ARTEFACT = "Beyond the HexFlex (parallelogram flexure)"
#: the pose components of the report rows
COMPONENTS = ("u_x/L", "u_y/L", "φ")
#: the data the page keeps for the book's bundle: its one-line description
DATA = {
    "parallelogram_comparison": (
        "the transcribed rows of Su & Survey's 3-D FE sweep of a parallelogram flexure "
        "beside our stretchable elastica: loads F L²/EI and M L/EI (B as printed and as "
        "applied), displacements over L, rotations in rad (as reported and the rigid "
        "rotation behind it)"
    ),
}


def _levels(values: Sequence[float]) -> str:
    """A set of levels as the prose writes it: ``{−5, 0, 5}``."""
    return "{" + ", ".join(f"{v:g}" for v in values).replace("-", "−") + "}"


def _pull_push(value: Any, context: Mapping[str, Any]) -> dict[str, tuple[int, int]]:
    """The largest relative differences by A_x: along the transcribed lines in tension
    (``pull``) and compression (``push``), the rows' positions in the context, and at the grid's
    corners (the first and last A_x level)."""
    pull, push = context["pull"], context["push"]
    return {
        "ux_rel_pull": (pull, 0),
        "ux_rel_push": (push, 0),
        "uy_rel_pull": (pull, 1),
        "uy_rel_push": (push, 1),
        "phi_rel_pull": (pull, 2),
        "phi_rel_push": (push, 2),
        "ux_rel_corner_push": (0, 0),
        "ux_rel_corner_pull": (len(value) - 1, 0),
    }


def _per_component(prefix: str) -> dict[str, int]:
    """Glue of the three pose components of a value: ``<prefix>_ux``, ``_uy``, ``_phi``."""
    return {f"{prefix}_{c}": i for i, c in enumerate(("ux", "uy", "phi"))}


PLAN: dict[str, Entry] = {
    # --- the benchmark and our reference model
    "design.geometry_mm": Entry(
        tol=EXACT,
        glue={"geo_l": 0, "geo_t": 1, "geo_h": 2, "geo_w": 3, "geo_stage": 4},
        value=[
            pub.LENGTH_MM,
            pub.THICKNESS_MM,
            pub.HEIGHT_MM,
            pub.SEPARATION_MM,
            pub.STAGE_LENGTH_MM,
        ],
    ),
    "design.height_over_thickness": Entry(
        tol=CLOSED_FORM, glue="h_over_t", value=pub.HEIGHT_MM / pub.THICKNESS_MM
    ),
    # the beams' E [GPa] and ν, the stage's E [GPa]
    "design.material": Entry(
        tol=CLOSED_FORM,
        glue={"young_gpa": 0, "poisson": 1, "young_stage_gpa": 2},
        value=[pub.YOUNG_MPA / 1e3, pub.POISSON, pub.YOUNG_STAGE_MPA / 1e3],
    ),
    # A = 1 and B = 1 in N and N·m
    "design.load_units": Entry(
        tol=CLOSED_FORM,
        glue={"force_unit_n": 0, "moment_unit_nm": 1},
        value=[pub.FORCE_UNIT_N, pub.MOMENT_UNIT_NMM / 1e3],
    ),
    "design.axial_compliance": Entry(tol=CLOSED_FORM, glue="axial_c", value=pub.AXIAL_COMPLIANCE),
    "design.mesh_mm": Entry(tol=EXACT, glue="mesh_mm", value=pub.MESH_SIZE_MM),
    "sweep.rows": Entry(
        tol=EXACT,
        glue={"n_kept": 0, "n_file": 1},
        value=[len(pub.SWEEP_SUBSET), pub.SWEEP_ROW_COUNT],
    ),
    "sweep.grid_levels": Entry(
        tol=EXACT,
        glue={"n_ax": 0, "n_ay": 1, "n_b": 2, "n_ay_all": 3},
        value=[
            len(pub.A_X_LEVELS),
            len(pub.A_Y_COMPUTED_LEVELS),
            len(pub.B_LEVELS),
            len(pub.A_Y_LEVELS),
        ],
    ),
    "sweep.grid_largest": Entry(
        tol=EXACT,
        glue={"ax_max": 0, "ay_max": 1, "b_max": 2},
        value=[pub.A_X_LEVELS.max(), pub.A_Y_LEVELS.max(), pub.B_LEVELS.max()],
    ),
    # the transcribed lines: their levels of A_x and of B
    "sweep.lines": Entry(
        tol=EXACT,
        texts={"lines_ax": lambda v: _levels(v[0]), "lines_b": lambda v: _levels(v[1])},
    ),
    # the comparison's bounds, fixed before any difference is measured
    "bounds.plate_pct": Entry(tol=CLOSED_FORM, glue="plate_pct", value=100 * cmp.PLATE_BOUND),
    "bounds.shortening_pct": Entry(
        tol=CLOSED_FORM, glue="shortening_pct", value=100 * cmp.SHORTENING_BOUND
    ),
    "bounds.shortening_min_a_y": Entry(
        tol=EXACT, glue="short_min_a_y", value=cmp.SHORTENING_MIN_A_Y
    ),
    "bounds.small_a_y": Entry(tol=EXACT, glue="small_a_y", value=cmp.SMALL_A_Y),
    "bounds.stretch_share_pct": Entry(
        tol=EXACT, glue="stretch_share_pct", value=100 * cmp.STRETCH_SHARE
    ),
    "bounds.stage_centre_offset": Entry(
        tol=CLOSED_FORM, glue="centre_d", value=cmp.STAGE_CENTRE_OFFSET
    ),
    # --- what the published files show about themselves
    "data.couple_pairs": Entry(
        tol=EXACT,
        glue={"pairs": 0, "pairs_identical": 1, "pairs_unloaded": 2, "pairs_differ": 3},
        rows=report.Computed(
            ARTEFACT,
            "published 3-D FE sweep, transcribed rows: computed pairs with B and −B, those "
            "identical to the last printed digit, those whose row with B = 0 is kept, and those "
            "differing from it",
            ("pairs", "identical", "with B = 0 kept", "differing from B = 0"),
        ),
    ),
    "data.mirrored": Entry(tol=EXACT, glue={"n_mirrored": 0, "n_negative": 1}),
    "data.phi_big_loads": Entry(tol=EXACT, glue={"big_ax": 0, "big_ay": 1, "big_b": 2}),
    # the largest rotation as reported, the rigid rotation behind it [rad], their difference [%]
    "data.phi_reported_vs_rigid": Entry(
        tol=ROUNDOFF,
        glue={"phi_reported": 0, "phi_rigid": 1, "phi_reported_pct": 2},
        rows=report.Computed(
            ARTEFACT,
            "published 3-D FE sweep, largest rotation: as reported, the rigid rotation behind it "
            "[rad], and their difference [%]",
            ("reported", "rigid", "difference [%]"),
        ),
    ),
    # --- the elastica beside the 3-D FE
    "sweep.spans": Entry(tol=ROUNDOFF),
    "stretchable.worst_abs": Entry(tol=ELASTICA),
    "stretchable.median_abs": Entry(tol=ELASTICA),
    "stretchable.worst_share_pct": Entry(
        tol=ELASTICA_PCT,
        glue=_per_component("worst_share"),
        rows=report.Computed(
            ARTEFACT,
            "largest |elastica − published 3-D FE| over the transcribed rows, % of the FE's full "
            "scale",
            COMPONENTS,
        ),
    ),
    "stretchable.median_share_pct": Entry(tol=ELASTICA_PCT, glue=_per_component("med_share")),
    "stretchable.worst_rel_pct": Entry(tol=ELASTICA_PCT),
    "stretchable.median_rel_pct": Entry(
        tol=ELASTICA_PCT,
        glue=_per_component("med_rel"),
        rows=report.Computed(
            ARTEFACT,
            "median |elastica / published 3-D FE − 1| over the transcribed rows [%]",
            COMPONENTS,
        ),
    ),
    "stretchable.worst_loads": Entry(tol=EXACT),
    "excess.ux_pct": Entry(tol=ELASTICA_PCT, glue={"ux_ex_min": 0, "ux_ex_max": 1}),
    "excess.uy_pct": Entry(tol=ELASTICA_PCT, glue={"uy_ex_min": 0, "uy_ex_max": 1}),
    "excess.phi_pct": Entry(tol=ELASTICA_PCT, glue={"phi_ex_min": 0, "phi_ex_max": 1}),
    "excess.abs_max_pct": Entry(tol=ELASTICA_PCT),
    # --- where the differences grow
    "growth.a_y_levels": Entry(tol=EXACT),
    "growth.by_a_y_share_pct": Entry(tol=ELASTICA_PCT),
    "growth.by_a_y_rel_pct": Entry(tol=ELASTICA_PCT),  # u_y and φ: every level
    "growth.small_share_pct": Entry(tol=ELASTICA_PCT, glue="small_share"),
    "growth.top_share_pct": Entry(tol=ELASTICA_PCT, glue=_per_component("top_share")),
    "growth.phi_rel_pct_small_top": Entry(
        tol=ELASTICA_PCT, glue={"phi_rel_small": 0, "phi_rel_top": 1}
    ),
    "growth.a_x_levels": Entry(tol=EXACT),
    "growth.by_a_x_rel_pct": Entry(tol=ELASTICA_PCT, glue=_pull_push),
    "growth.a_x_levels_quoted": Entry(
        tol=EXACT, glue={"ax_pull": 0, "ax_push": 1, "ax_low": 2, "ax_high": 3}
    ),
    # --- small loads, and what turns the stage under a couple
    "small.phi_worst_rad": Entry(tol=ELASTICA, glue="phi_small_worst"),
    "small.phi_fe_max_rad": Entry(tol=ROUNDOFF, glue="phi_small_fe_max"),
    "small.phi_worst_share_pct": Entry(tol=ELASTICA_PCT, glue="phi_small_share"),
    "couple.median_rel_pct": Entry(
        tol=ELASTICA_PCT,
        glue={"couple_rel_stretch": 0, "couple_rel_inext": 1},
        rows=report.Computed(
            ARTEFACT,
            "rotation under a couple at small loads: median |elastica / published 3-D FE − 1| [%]",
            ("stretchable", "inextensible"),
        ),
    ),
    "couple.overall_median_rel_pct": Entry(tol=ELASTICA_PCT),
    # --- where the FE's loads act
    "load_point.median_miss_rad": Entry(tol=ELASTICA, glue={"lp_tip": 0, "lp_centre": 1}),
    "load_point.median_fe_phi_rad": Entry(tol=ROUNDOFF, glue="lp_fe_phi"),
    # --- the mesh study's case
    # the published mesh study: its load (A_x, A_y, B) and its element sizes [mm]
    "mesh.loads": Entry(
        tol=EXACT, glue={"mesh_ax": 0, "mesh_ay": 1, "mesh_b": 2}, value=list(pub.MESH_STUDY_LOADS)
    ),
    "mesh.sizes_mm": Entry(
        tol=EXACT,
        glue=lambda v: {"mesh_coarse": 0, "mesh_fine": len(v) - 1},
        value=pub.MESH_STUDY[:, 0],
    ),
    "mesh.elastica": Entry(
        tol=ELASTICA,
        glue={"mesh_el_x": 0, "mesh_el_y": 1, "mesh_el_phi": 2},
        rows=report.Computed(
            ARTEFACT,
            "elastica at the published mesh study's load: load point x, y [mm] and rotation [rad]",
            ("x [mm]", "y [mm]", "φ [rad]"),
        ),
    ),
    # the elastica over each published mesh − 1, [%]: y at the coarsest and the finest mesh
    "mesh.excess_pct": Entry(
        tol=ELASTICA_GAP_PCT,
        glue=lambda v: {"mesh_ex_y_coarse": (0, 1), "mesh_ex_y_fine": (len(v) - 1, 1)},
    ),
    "mesh.gap_closed_pct": Entry(
        tol=ELASTICA_GAP_PCT, glue={"gap_closed_x": 0, "gap_closed_y": 1, "gap_closed_phi": 2}
    ),
    # --- the deformed parallelogram
    "shapes.poses": Entry(tol=ELASTICA),
}
