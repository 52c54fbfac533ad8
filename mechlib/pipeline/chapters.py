"""The chapters: their order, and the inputs one takes from another's record — declared once.

Every notebook of ``notebooks/`` is a chapter. :data:`CHAPTERS` is the order they execute in
(each after the chapters whose records it reads); :data:`CHAPTER_INPUTS` says which of a
chapter's parameters are filled from which record. The Makefile reads both from here (this file
runs with the standard library alone, before the environment exists)::

    python3 mechlib/pipeline/chapters.py order   # the chapters, in execution order
    python3 mechlib/pipeline/chapters.py edges   # chapter:upstream pairs, one per input record
    python3 mechlib/pipeline/chapters.py makefile  # the Makefile's rules (build/chapters.mk)
"""

from __future__ import annotations

import sys
from collections.abc import Iterable
from pathlib import Path

#: Execution order: a chapter comes after every chapter it takes an input from; the longest chain
#: (the model page, the DOE chapter, the meta-model page) first, the chapters that feed no other
#: after it (a build with fewer workers than ready chapters starts them in this order).
CHAPTERS: tuple[str, ...] = (
    "hexflex_model",
    "virtual_experiments",
    "nonlinear_metamodels",
    "nonlinear_family",
    "published_doe",
    "fivebar_identification",
    "beyond_5r",
    "beyond_hexflex",
    "parallelogram_fe",
)
#: Scheduling only (no input passes): chapter -> the chapter it starts after when make has fewer
#: job slots than ready chapters. make starts the ready chapter that comes first in its list, so
#: the quick chapters that feed no other would otherwise take a free slot while the longest chain
#: (the model page, the DOE chapter, the meta-model page) waits.
DEFERRED: dict[str, str] = {
    "published_doe": "virtual_experiments",
    "fivebar_identification": "virtual_experiments",
    "beyond_5r": "virtual_experiments",
    "beyond_hexflex": "virtual_experiments",
    "parallelogram_fe": "virtual_experiments",
}
#: The parameters a reader changes first, per chapter (each box "How this page was built" names
#: them; every name is a parameter of the chapter's parameters cell: a test checks it).
MAIN_PARAMETERS: dict[str, tuple[str, ...]] = {
    "hexflex_model": ("thickness", "mesh_fraction", "free_dimensions", "fit_tol"),
    "virtual_experiments": ("seed", "nonlinear_runs", "nonlinear_mesh", "workers"),
    "nonlinear_metamodels": ("training_runs", "families", "goal_pct", "workers"),
    "nonlinear_family": ("thicknesses", "family_runs", "nonlinear_mesh", "workers"),
    "published_doe": ("seed", "n_random_designs", "lenth_alpha", "penalty"),
    "fivebar_identification": ("seed", "sigma", "n_per_leg", "n_trials", "solver"),
    "beyond_5r": ("seed", "sigma", "n_trials", "n_trials_5r"),
    "beyond_hexflex": ("drawn_loads",),
    "parallelogram_fe": ("mesh_size", "layers", "sweep_lines", "curve_sizes", "budget_scales"),
}
#: Chapter inputs: chapter -> {parameter: (upstream chapter, record key)}. Whoever executes the
#: chapter passes each parameter the upstream chapter's recorded value (unless the run gives it
#: itself); a key ending in ``.*`` passes every value under that prefix, as a mapping by the rest
#: of its key (``geometry.thickness`` -> ``{"thickness": ...}``).
CHAPTER_INPUTS: dict[str, dict[str, tuple[str, str]]] = {
    "virtual_experiments": {
        "geometry": ("hexflex_model", "geometry.*"),
        "mesh_fraction": ("hexflex_model", "model.mesh_fraction"),
    },
    # the family page solves the DOE chapter's validation draw (its seed and size) on the
    # members of the Eq 8 family, so it runs after that chapter
    "nonlinear_family": {
        "geometry": ("hexflex_model", "geometry.*"),
        "mesh_fraction": ("hexflex_model", "model.mesh_fraction"),
        "seed": ("virtual_experiments", "parameters.seed"),
        "n_validation": ("virtual_experiments", "parameters.n_validation"),
    },
    # the meta-model page holds out the first runs of the DOE chapter's validation draw
    "nonlinear_metamodels": {
        "geometry": ("hexflex_model", "geometry.*"),
        "mesh_fraction": ("hexflex_model", "model.mesh_fraction"),
        "seed": ("virtual_experiments", "parameters.seed"),
        "n_validation": ("virtual_experiments", "parameters.n_validation"),
    },
}


def upstream(chapter: str) -> list[str]:
    """The chapters whose records ``chapter`` reads, in :data:`CHAPTERS` order."""
    names = {up for up, _ in CHAPTER_INPUTS.get(chapter, {}).values()}
    return [c for c in CHAPTERS if c in names]


def in_order(notebooks: Iterable[Path]) -> list[Path]:
    """Notebook paths in :data:`CHAPTERS` order (any other notebook after them, by name)."""
    rank = {name: i for i, name in enumerate(CHAPTERS)}
    return sorted(notebooks, key=lambda p: (rank.get(Path(p).stem, len(rank)), Path(p).stem))


def check_order() -> None:
    """Raise ``ValueError`` unless every input comes from a chapter that executes earlier (and
    every deferred chapter waits for an earlier one)."""
    for chapter, after in DEFERRED.items():
        if after not in CHAPTERS or chapter not in CHAPTERS[CHAPTERS.index(after) + 1 :]:
            raise ValueError(
                f"deferred chapter {chapter!r} must come after {after!r} in CHAPTERS: "
                f"{list(CHAPTERS)}"
            )
    for chapter, inputs in CHAPTER_INPUTS.items():
        for name, (up, _) in inputs.items():
            if chapter not in CHAPTERS or up not in CHAPTERS[: CHAPTERS.index(chapter)]:
                raise ValueError(
                    f"input {name!r} of {chapter!r} comes from {up!r}, which is not a chapter "
                    f"executed before it; CHAPTERS: {list(CHAPTERS)}"
                )


def make_rules(executed: str = "$(BUILD)/executed") -> list[str]:
    """The Makefile's lines for the chapters: ``NB_NAMES`` (the chapters in order), a
    prerequisite per input (a chapter executes after those whose records fill its inputs) and an
    order-only one per :data:`DEFERRED` pair (make starts the ready chapter that comes first in
    its list, so the quick chapters that feed no other wait for the longest chain)."""
    lines = [f"NB_NAMES := {' '.join(CHAPTERS)}"]
    lines += [f"{executed}/{c}.ipynb: {executed}/{u}.ipynb" for c in CHAPTERS for u in upstream(c)]
    lines += [f"{executed}/{c}.ipynb: | {executed}/{a}.ipynb" for c, a in DEFERRED.items()]
    return lines


def main(argv: list[str]) -> int:
    """``order``: the chapters one per word; ``edges``: ``chapter:upstream`` words;
    ``deferred``: ``chapter:after`` words of :data:`DEFERRED`; ``makefile``: :func:`make_rules`."""
    check_order()
    if argv == ["order"]:
        print(" ".join(CHAPTERS))
    elif argv == ["edges"]:
        print(" ".join(f"{c}:{u}" for c in CHAPTERS for u in upstream(c)))
    elif argv == ["deferred"]:
        print(" ".join(f"{c}:{a}" for c, a in DEFERRED.items()))
    elif argv == ["makefile"]:
        print("\n".join(make_rules()))
    else:
        print("usage: chapters.py order|edges|deferred|makefile", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
