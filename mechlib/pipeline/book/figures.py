"""Captions and alt text of the chapters' figures, given by the book build (notebooks stay plain).

Each figure a chapter draws is one code cell with one image output. The build gives that cell
myst-nb's figure options (:func:`figure_metadata`): a caption, which Sphinx numbers ("Figure 3:
…"), a target name, and an alt text for readers who cannot see the image. Captions say what is
drawn and where it comes from; they quote no result (results are glued in the text). A figure
cell without an entry here is reported by :func:`uncaptioned` (``make check-book`` fails on it).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from mechlib.plotting.calibration import MAP_PERCENTILE

#: (caption, alt text) per notebook and figure cell id.
CAPTIONS: dict[str, dict[str, tuple[str, str]]] = {
    "published_doe": {
        "cell-22": (
            "Thesis Fig 6 redrawn from Table 2: half-normal plots of the six |main effects| of "
            "each pose component, in Table 2's printed units; dashed: Lenth's margin of error.",
            "Six panels, one per pose component, plotting each factor's absolute main effect "
            "against its half-normal quantile, labelled with the factor names.",
        ),
        "cell-23": (
            "Thesis Fig 7 redrawn from Table 2: Pareto charts of the |main effects|, largest "
            "first; dashed: Lenth's margin of error.",
            "Six horizontal bar charts, one per pose component, of the factors' absolute main "
            "effects sorted by size.",
        ),
        "cell-27": (
            "The squared centred L2 discrepancy of random balanced designs with Table 4's levels "
            "(histogram) and of Table 4 itself (marked).",
            "Histogram of discrepancies of random balanced designs with a vertical line at "
            "Table 4's value.",
        ),
        "cell-31": (
            "Eq 8 entry by entry against three least-squares fits: OLS and penalized on Table 4, "
            "OLS on Table 2.",
            "Panels of 6 by 6 matrices showing each fit's difference from Eq 8 per entry.",
        ),
    },
    "hexflex_model": {
        "cell-24": (
            "Thesis Fig 2, reconstructed: the HexFlex planform of our model coloured by part, "
            "with the grounded sectors, drawn at the identified dimensions; upper right, one end "
            "of T1's beam and its radial flexure enlarged, with their quads.",
            "Top view of a triangular stage with three tabs and six L-shaped connection beams "
            "running to three grounded sectors, each part in its own colour; an enlarged inset "
            "shows a thin horizontal beam meeting a thin vertical flexure.",
        ),
        "cell-26": (
            "Thesis Fig 5 for our model: (a) the all-quad mesh of one sixth of the planform, "
            "(b) the whole mesh completed by a reflection and two rotations.",
            "Two panels: a quadrilateral mesh of a 60-degree sector of the planform, fine in the "
            "flexures and coarser in the stage and tab, and the whole mesh.",
        ),
        "cell-28": (
            "Thesis Fig 4 for our model: the positive direction of each actuator force at the "
            "tabs' external edges (D1 in the plane, D2 out of it).",
            "Planform outline with arrows at the three tabs for the in-plane directions and dots "
            "for the out-of-plane ones.",
        ),
        "cell-30": (
            "Thesis Fig 3 for our model: the six motions of the stage, each produced by the "
            "forces the inverse model gives for one pure translation or rotation.",
            "Six small plots of the planform's deformed shape, one per stage motion x, y, z, "
            "theta x, theta y, theta z.",
        ),
        "cell-32": (
            "A deformed shape in the style of thesis Fig 8, for the forces of the parameter "
            "fig8_forces: in-plane displacements magnified, colour the out-of-plane one (µm).",
            "The deformed planform coloured by its out-of-plane displacement under one set of "
            "six actuator forces.",
        ),
    },
    "nonlinear_metamodels": {
        "mm-12": (
            "Learning curves on the non-linear HexFlex: the largest error over the held-out "
            "non-linear runs at ±1 N (worst pose component, % of full scale) against the number "
            "of full non-linear FE runs each model was trained on; lines: fitted families on "
            "nested Sobol' designs; points: the thesis's fits on Table 4's runs and the "
            "reduced-order model; dashed: the error budget.",
            "Log-log plot of error in percent against training runs, one descending line per "
            "meta-model family, three single markers, and a horizontal dashed budget line.",
        ),
        "mm-15": (
            "Largest error (worst pose component, % of full scale) of each model at each force "
            "range, every fitted family trained at that range; dashed: the error budget.",
            "Log-log plot of error in percent against the force range in newtons, one line per "
            "model, with a horizontal dashed budget line.",
        ),
        "mm-20": (
            "Accuracy against speed: each model's largest error at ±1 N (% of full scale) against "
            "the time to predict one pose on the machine that built the page; dashed: the "
            "error budget; dotted: the real-time deadline.",
            "Scatter plot on logarithmic axes, one marker per model, with a horizontal dashed "
            "budget line and a vertical dotted deadline line.",
        ),
        "rt-01": (
            "Largest error at ±1 N (worst pose component, % of full scale) against the full "
            "non-linear runs used for training: the plain Gaussian process, the "
            "reduced-order model corrected by a Gaussian process of the forces fitted to its "
            "misses, and corrected by an error model on its dual-weighted residuals; the "
            "uncorrected reduced-order model as a marker; dashed: the accuracy goal.",
            "Log-log plot of error in percent against training runs, three lines and one marker, "
            "with a horizontal dashed goal line.",
        ),
    },
    "virtual_experiments": {
        "cell-09": (
            "Thesis Fig 6 on our model: half-normal plots of the main effects of Table 2's runs "
            "on our FE model (µm, µrad).",
            "Six half-normal plots of absolute main effects, one per pose component, from our "
            "model's screening runs.",
        ),
        "cell-10": (
            "Thesis Fig 6 from the published Table 2, converted to µm and µrad, for comparison "
            "with the figure above.",
            "Six half-normal plots of absolute main effects computed from the thesis's Table 2.",
        ),
        "cell-11": (
            "Thesis Fig 7 on our model: Pareto charts of the main effects of Table 2's runs on "
            "our FE model.",
            "Six horizontal bar charts of absolute main effects from our model's screening "
            "runs, largest first.",
        ),
        "cell-12": (
            "Thesis Fig 7 from the published Table 2 (µm, µrad), for comparison with the "
            "figure above.",
            "Six horizontal bar charts of absolute main effects computed from the thesis's "
            "Table 2, largest first.",
        ),
        "cell-23": (
            "Table 5(b): the errors of the linear meta-model against the geometrically "
            "non-linear FE runs, taken over the first k runs, for every k.",
            "Curves of the largest pointwise errors and errors in % of full scale per pose "
            "component against the number of non-linear runs.",
        ),
        "cell-31": (
            "Thesis Fig 8 on our model: the deformed shape of the first validation run (in-plane "
            "displacements magnified, colour the out-of-plane one in µm).",
            "The deformed planform coloured by its out-of-plane displacement under the first "
            "random validation run's forces.",
        ),
    },
    "fivebar_identification": {
        "cell-04": (
            "Thesis Fig 10: the planar 5R, its singularity curves and its maximal inscribed "
            "workspace (MIW), with the mechanism drawn at one pose.",
            "Map of the 5R's reachable region with serial and parallel singularity curves, the "
            "MIW circle and the two legs drawn to one end-effector point.",
        ),
        "cell-06": (
            "Thesis Fig 11: the loop of the left leg, P = A + l + L (Eq 22), and its active "
            "angle θ.",
            "The left leg drawn from its base A through the elbow to the end-effector P, with "
            "the active angle marked.",
        ),
        "cell-09": (
            "Thesis Fig 12: postures selected by active calibration, (a) for the traditional "
            "method, (b, c) for each leg under divide and conquer.",
            "Three panels of candidate postures in the MIW with the selected ones marked, for "
            "the traditional method and for each leg.",
        ),
        "cell-13": (
            "Thesis Fig 13: absolute parameter errors before calibration (nominal values) and "
            "after it (D&C, traditional), one seeded draw, log scale.",
            "Grouped bar chart on a log scale of the twelve parameters' errors before and after "
            "each calibration.",
        ),
        "cell-15": (
            "Thesis Fig 14: local RMS position error over the workspace before calibration (a), "
            "the ratio D&C / traditional after it (b), and the errors after D&C (c) and after "
            "the traditional method (d) on one shared colour scale.",
            "Four maps of the MIW: the error before calibration, a red-blue map of the ratio of "
            "the two methods' errors centred on 1, and the errors after each method on one colour "
            "scale.",
        ),
        "cell-19": (
            "The Monte Carlo distributions behind the means: each trial's workspace RMS error "
            "and each parameter's absolute error per strategy.",
            "A histogram of workspace errors for both strategies and box plots of each "
            "parameter's error.",
        ),
        "cell-24": (
            "Sensitivity of the comparison to the noise level and the number of postures: the "
            "ratio of the two strategies' workspace errors and D&C's share of won trials.",
            "Two panels of curves against the noise level, one per posture count.",
        ),
    },
    "beyond_hexflex": {
        "bh-08": (
            "The parallelogram flexure's stage displacement u_x/L, u_y/L and rotation φ against "
            "the transverse load A_y, per axial load A_x (columns): markers, the published 3-D FE "
            "sweep of Su and Survey per printed couple B (rotation recovered from the reported "
            "value); solid lines, our elastica under the couple the FE applied; dashed, under "
            "the couple the file prints.",
            "Nine panels in three rows (axial and transverse displacement, rotation) and three "
            "columns (A_x = -5, 0, 5), each with marker series for B = -3, 0, 3 lying on solid "
            "curves, and dashed curves that leave them.",
        ),
        "bh-21": (
            "Our elastica of the parallelogram flexure drawn to scale at the loads of the "
            "parameter drawn_loads: beams and stage (blue) over the unloaded mechanism (grey), "
            "with the load point of the elastica (dot) and of the published 3-D FE (cross).",
            "Side views of two beams clamped on the left and joined by a block on the right, "
            "bent into S-shapes, one panel per load.",
        ),
    },
    "parallelogram_fe": {
        "pfe-04": (
            "Our FE of the parallelogram flexure: the planform's quads at the page's element "
            "size (the stage, a material region, shaded), the clamped faces (black), the face "
            "the three loads act on (red) and the point the pose is reported at.",
            "Top view of two long thin beams clamped at the left end and joined at the right by "
            "a shaded block; a red line marks the block's left face between the beams.",
        ),
        "pfe-14": (
            "The parallelogram flexure's stage displacement u_x/L, u_y/L and rotation φ against "
            "the transverse load A_y on the first line of the parameter sweep_lines (by default "
            "A_x = 0, B = 0): markers, the published 3-D FE sweep of Su and Survey; solid, our "
            "non-linear FE; dashed, our stretchable elastica.",
            "Three panels of curves against A_y, each with square markers, a solid curve and a "
            "dashed curve.",
        ),
        "pfe-14b": (
            "The difference of our non-linear FE of the parallelogram flexure from the published "
            "3-D FE sweep of Su and Survey at every row solved, in % of the published full scale "
            "of u_x/L, u_y/L and φ, against A_y: a line per line of the sweep (A_x and the couple "
            "applied), the grid's corners as lone grey markers; ringed, each component's largest.",
            "Three panels of lines with dots against A_y, a few lone grey markers at the largest "
            "A_y, and one black ring per panel.",
        ),
        "pfe-20": (
            "Chapter 2's meta-model families on our FE of the parallelogram flexure: the largest "
            "error on held-out non-linear FE runs over the benchmark's load box (worst pose "
            "component, % of full scale) against the training runs; dashed, the error budget.",
            "Log-log curves of error against training runs, one per family, above a dashed "
            "horizontal budget line.",
        ),
    },
    "beyond_5r": {
        "b5r-06": (
            "Poses selected by active calibration on the 5R, the 3-RRR and the 6-UPS, per leg "
            "for D&C and shared for the traditional method (x–y projection).",
            "Panels of candidate and selected poses for each mechanism and strategy.",
        ),
        "b5r-14": (
            "Parameter errors before and after calibration on the three mechanisms, one seeded "
            "draw, in units of the disturbance.",
            "Bar charts of parameter errors per mechanism before and after each calibration.",
        ),
        "b5r-16": (
            "Position error over a regular slice of each workspace: before calibration and its "
            "RMS over the trials after each strategy. Each panel has its own colour scale, from "
            f"the {100 - MAP_PERCENTILE:g}th to the {MAP_PERCENTILE:g}th percentile of its points "
            "(the colour bar's arrows; the few points by a singular corner lie far above it): "
            "compare the levels on the colour bars.",
            "Maps of the position error over each mechanism's workspace slice.",
        ),
        "b5r-18": (
            "Workspace error of both strategies against the measurement noise and against the "
            "pose budget, per mechanism.",
            "Curves of workspace RMS error against noise level and against pose count.",
        ),
        "b5r-20": (
            "Costs against the number of legs: the size of the normal equations and measured "
            "solve times per strategy.",
            "Panels of cost measures against the number of legs for both strategies.",
        ),
    },
}


def _has_image(cell: Mapping[str, Any]) -> bool:
    return any(
        {"image/png", "image/svg+xml", "image/jpeg"} & set(out.get("data", {}))
        for out in cell.get("outputs", [])
    )


def figure_metadata(page: str, cell: Mapping[str, Any]) -> dict[str, Any] | None:
    """myst-nb's ``mystnb`` cell options for a figure cell with a caption, else None.

    Parameters
    ----------
    page : str
        The notebook's name (``fivebar_identification``).
    cell : mapping
        An executed code cell (nbformat 4).
    """
    entry = CAPTIONS.get(page, {}).get(cell.get("id", ""))
    if entry is None or not _has_image(cell):
        return None
    caption, alt = entry
    return {
        "figure": {"caption": caption, "name": f"{page}-{cell['id']}"},
        "image": {"alt": alt},
    }


def uncaptioned(page: str, nb: Mapping[str, Any]) -> list[str]:
    """Messages for figure cells of ``nb`` without a caption, and for captions of cells that do
    not exist or draw no figure (empty when every figure has one and every caption a figure)."""
    cells = {c.get("id"): c for c in nb.get("cells", []) if c.get("cell_type") == "code"}
    problems = [
        f"{page}: figure cell {cid!r} has no caption in mechlib/pipeline/book/figures.py"
        for cid, cell in cells.items()
        if _has_image(cell) and cid not in CAPTIONS.get(page, {})
    ]
    problems += [
        f"{page}: caption for cell {cid!r}, which draws no figure"
        for cid in CAPTIONS.get(page, {})
        if cid not in cells or not _has_image(cells[cid])
    ]
    return problems
