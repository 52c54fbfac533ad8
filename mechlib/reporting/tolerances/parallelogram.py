"""Named tolerances of the parallelogram flexure: our FE, the elastica, and the meta-models
fitted to our FE.
"""

from __future__ import annotations

from mechlib.reporting.tolerance import Tolerance

# --- the parallelogram flexure: our FE, the elastica, and the meta-models fitted to our FE ------

LINEAR_FE_RATIO = Tolerance(
    rtol=1e-7,
    why="a linear FE compliance (one sparse direct solve) over a closed form: solves on another "
    "processor's BLAS kernels were measured within 1.4e-8 of the largest component "
    "(mechlib.campaign.cachecheck), inside 1e-7",
)
LINEAR_FE_CHANGE_PCT = Tolerance(
    rtol=1e-5,
    why="a change, in percent, between two linear FE compliances (a few % apart): each solve "
    "agrees to ~1e-8 between kernels, which the difference magnifies to ~1e-6 of the change",
)
CACHED_FE_POSE = Tolerance(
    rtol=1e-6,
    atol=1e-12,
    why="the pose of a non-linear FE run read from the FE cache: a re-run reads the same stored "
    "bits, so the pose repeats exactly (relative 1e-6, a floor of 1e-12 for a rotation near 0); "
    "a cold recomputation is checked only to 1e-7 of the run's largest component "
    "(mechlib.campaign.cachecheck), which for a small component can exceed 1e-6 of itself",
)
FE_EFFECTS = Tolerance(
    rtol=1e-5,
    atol=1e-9,
    why="main effects of FE poses read from the FE cache (signed sums over a design's runs): a "
    "re-run reads the same stored bits, so only the sums' round-off can differ (relative 1e-5, "
    "a floor of 1e-9 for effects that vanish by symmetry); a cold recomputation is checked only "
    "to 1e-7 of each run's largest component (mechlib.campaign.cachecheck)",
)
FE_FIT_ERROR_PCT = Tolerance(
    rtol=1e-4,
    atol=1e-9,
    why="the largest held-out error, in % of full scale, of a least-squares fit to FE runs: "
    "the runs agree to 1e-7 (mechlib.campaign.cachecheck) and the fit's round-off is far "
    "smaller; the error is a difference of such values, so relative 1e-4, a floor of 1e-9",
)
META_FIT_PCT = Tolerance(
    rtol=1e-3,
    atol=1e-6,
    why="held-out errors, in % of full scale, of meta-model families fitted to FE runs, some "
    "by iterative optimisers (a Gaussian process's likelihood, a cross-validated penalty) "
    "that another kernel can stop one iterate apart: relative 1e-3, a floor of 1e-6 points",
)
META_CURVE_PCT = Tolerance(
    rtol=0.1,
    atol=1e-6,
    why="held-out errors, in % of full scale, along the learning curves, which hold a Gaussian "
    "process fitted at every size: its likelihood has several optima and the seeded optimiser's "
    "landing moves with the BLAS kernel's round-off (at 128 runs the largest error was 14.61 % "
    "under OpenBLAS's Haswell and Sandybridge kernels, 14.20 % under Nehalem, and the error "
    "over the other held-out runs 4.60 % against 4.40 %: 4.2 % apart); 10 %, a floor of 1e-6 "
    "points",
)
META_CURVE_PCT_REL = Tolerance(
    rtol=0.1,
    why="as META_CURVE_PCT, for the best family's error at the largest size (never near 0)",
)
DISTILLED_PCT = Tolerance(
    rtol=1e-3,
    atol=1e-9,
    why="as META_FIT_PCT, for a distilled polynomial's held-out error, fitted by least squares "
    "to a family's predictions: a floor of 1e-9 points",
)
DESIGN_POINT = Tolerance(
    rtol=1e-9,
    atol=1e-12,
    why="a point of a seeded design in the loads' units: drawn by the same generator on every "
    "machine and scaled to the load box, round-off of the scaling only; a floor of 1e-12 for "
    "a coordinate at 0",
)
ELASTICA = Tolerance(
    rtol=1e-6,
    atol=1e-12,
    why="the elastica (mechlib.parallelogram.elastica): shooting with an adaptive integrator "
    "(relative 1e-10) and Newton to a residual of 1e-9, continued over load steps; another "
    "kernel's round-off moves a pose by far less than 1e-6; a floor of 1e-12 near 0",
)
ELASTICA_PCT = Tolerance(
    rtol=1e-6,
    atol=1e-9,
    why="as ELASTICA, for a difference from the published FE in percent (of full scale or of "
    "the FE's value): a floor of 1e-9 points for differences near 0",
)
ELASTICA_GAP_PCT = Tolerance(
    rtol=1e-5,
    atol=1e-9,
    why="as ELASTICA_PCT, for the elastica against the published meshes and the share of their "
    "gap that refining closes (a difference over a difference): the cancellation costs a "
    "digit, so relative 1e-5",
)
