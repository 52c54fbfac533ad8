"""The 5R chapter and "Beyond the 5R" run one calibration engine: through either page's entry
point, the same 5R study, seed and settings give the same numbers, and the two pages' default
parameters are the same settings."""

import json

import pytest

from mechlib import mechanism_catalog as catalog
from mechlib.calibration import montecarlo as mcarlo
from mechlib.calibration import statistics as cs
from mechlib.calibration import study as st
from mechlib.fivebar import mechanism as fivebar
from mechlib.fivebar.kinematics import N_LEG_PARAMS
from mechlib.paths import REPO_ROOT

#: coarse lattices, few trials: the tie does not depend on the sizes
SPACING, GRID, SEED, SIGMA, TRIALS, N_PER_LEG = 0.06, 0.15, 2010, 1e-4, 12, 18


def _parameters(notebook: str) -> dict[str, object]:
    """The defaults of a notebook's ``parameters`` cell."""
    cells = json.loads((REPO_ROOT / "notebooks" / f"{notebook}.ipynb").read_text())["cells"]
    cell = next(c for c in cells if "parameters" in c["metadata"].get("tags", []))
    values: dict[str, object] = {}
    exec("".join(cell["source"]), {}, values)  # the repository's own notebook
    return values


def test_both_entry_points_give_the_same_5r_numbers() -> None:
    # the 5R chapter: its study, its three budgets in one Monte Carlo
    study = fivebar.study(fivebar.FRACTION, SPACING, GRID, fivebar.DISTURBANCE, fivebar.SOLVER)
    shared = st.budgets(study.mech, N_PER_LEG, list(fivebar.BUDGETS.values()))
    dc = st.select_dc(study, N_PER_LEG)
    trad = {key: st.select_traditional(study, n) for key, n in shared.items()}
    chapter = mcarlo.monte_carlo(study, dc, trad, SIGMA, TRIALS, SEED)
    # Beyond the 5R: the catalog's 5R and its two budgets
    built = catalog.build(
        "5R",
        seed=SEED,
        disturbance=fivebar.DISTURBANCE,
        n_candidates=400,
        n_random_grid=40,
        slice_points=9,
        fivebar_spacing=SPACING,
        fivebar_grid_spacing=GRID,
    )
    beyond = mcarlo.run(built.study, N_PER_LEG, SIGMA, TRIALS, SEED)
    assert beyond.shared == {"thesis": 36, "matched": 27}
    for name, key in (("item10", "thesis"), ("equal", "matched")):
        a, b = cs.compare(chapter, fivebar.BUDGETS[name]), cs.compare(beyond.mc, key)
        assert a == b  # identical: pos RMS, medians, shares, p-values, parameter RMS
        assert a["pos_rms_dc"] > 0 and 0 < a["p_value"] < 1
    assert st.conditioning(study, dc, trad)["thesis"] == pytest.approx(
        st.conditioning(built.study, beyond.dc_sets, beyond.trad_sets)["thesis"], rel=0
    )


def test_the_two_pages_default_to_the_same_5r_settings() -> None:
    fb, b5r = _parameters("fivebar_identification"), _parameters("beyond_5r")
    same = (b5r["seed"], b5r["sigma"], b5r["n_trials_5r"])
    assert (fb["seed"], fb["sigma"], fb["n_trials"]) == same
    assert fb["n_per_leg"] == b5r["poses_per_parameter"] * N_LEG_PARAMS
    assert fb["disturbance"] == b5r["disturbance"] == fivebar.DISTURBANCE
    # Beyond the 5R builds its 5R with the library's defaults: the chapter's must be the same
    assert fb["workspace_fraction"] == fivebar.FRACTION == catalog.FIVEBAR_FRACTION
    assert fb["candidate_spacing"] == fivebar.CANDIDATE_SPACING
    assert fb["grid_spacing"] == fivebar.GRID_SPACING
    assert fb["solver"] == fivebar.SOLVER
