"""The text of the explorer page ("Try the model"): its Markdown and its interactive part's HTML.

Everything shown is read from the literal :func:`mechlib.pipeline.book.explorer.literal` makes
of the recorded model (names, units, force range, magnifications, worst errors); the values
that move are filled in by ``book/_static/explorer.js``, which finds its elements by the ``mx-``
ids written here. Native ``<input type="range">`` sliders with ``<label>`` s and a ``<form>``
keep the page usable from the keyboard.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from html import escape
from typing import Any

import numpy as np

from mechlib.pipeline.book import explorerdraw

SLIDER_STEPS = 100
"""Slider positions per force range (a step of amplitude / 100)."""
ROOT_ID = "mx"
#: the printed page's link to the live page (mechlib/pipeline/pdf.py points it at the page of the
#: HTML build beside the PDF's folder): its class, the page, and the sentence before it
LIVE_PAGE_CLASS = "live-page"
LIVE_PAGE = "generated/explorer.html"
LIVE_PAGE_TEXT = (
    "On paper this page shows the preset pose below; the sliders and the inverse run in the HTML "
    "book, page"
)
"""The id of the interactive part's element (``explorer.js`` looks for it)."""


def _fmt(value: float, places: int) -> str:
    text = f"{value:.{places}f}"
    return text[1:] if text.startswith("-") and float(text) == 0 else text.replace("-", "−")


def _view(index: int, view: Mapping[str, Any], data: Mapping[str, Any]) -> str:
    """One view of the interactive part, titled, drawn at zero force (the script redraws it)."""
    mag = data["drawing"]["magnification"][view["magnification"]]
    zeros = [0.0] * len(data["inputs"])
    return (
        f'<div class="mx-view"><p class="mx-view-title" id="mx-view-{index}">{view["name"]}: '
        f"displacements ×{mag:g}</p>"
        + explorerdraw.view_svg(view, data["drawing"], zeros, zeros, index=index)
        + "</div>"
    )


def widget_html(data: Mapping[str, Any], script: str) -> str:
    """The interactive part: force sliders and reset, the pose table, the three views, the
    timing line, the inverse form; then the model literal ``script`` inline."""
    amp, n = data["amplitude_n"], len(data["inputs"])
    step = amp / SLIDER_STEPS
    places = max(0, -int(np.floor(np.log10(step))))
    sliders = [
        f'<div class="mx-slider"><label for="mx-f{i}">{escape(name)}</label>'
        f'<input type="range" id="mx-f{i}" min="{-amp:g}" max="{amp:g}" step="{step:g}" '
        f'value="0"><output id="mx-f{i}-out" for="mx-f{i}">{_fmt(0, places)} N</output></div>'
        for i, name in enumerate(data["inputs"])
    ]
    heldout = data["heldout_runs"]
    rows = [
        f'<tr><th scope="row">{escape(o)}</th><td>{escape(u)}</td><td id="mx-nl-{i}"></td>'
        f'<td id="mx-lin-{i}"></td><td id="mx-diff-{i}"></td>'
        f"<td>±{_fmt(w / 100 * r, d)}</td></tr>"
        for i, (o, u, w, r, d) in enumerate(
            zip(
                data["outputs"],
                data["units"],
                data["worst_pct"],
                data["range"],
                data["decimals"],
                strict=True,
            )
        )
    ]
    targets = [
        f'<div class="mx-target"><label for="mx-t{i}">{escape(o)} [{escape(u)}]</label>'
        f'<input type="text" inputmode="decimal" id="mx-t{i}" value="0" size="10"></div>'
        for i, (o, u) in enumerate(zip(data["outputs"], data["units"], strict=True))
    ]
    views = [_view(i, v, data) for i, v in enumerate(data["drawing"]["views"])]
    return "\n".join(
        [
            f'<div id="{ROOT_ID}" class="mx-explorer">',
            '<p class="mx-nojs">The interactive part of this page runs in your browser and needs '
            "JavaScript; the figure below shows the stage for preset forces.</p>",
            '<div class="mx-live">',
            '<div class="mx-top">',
            f'<fieldset class="mx-forces"><legend>Actuator forces [N], each within '
            f"±{amp:g} N</legend>",
            *sliders,
            f'<p><button type="button" id="mx-reset">Set all {n} forces to 0 N</button></p>',
            f'<p class="mx-hint">A focused slider moves by {step:g} N with the arrow keys; Home '
            "and End move it to its ends; Tab goes to the next one.</p>",
            "</fieldset>",
            '<div class="mx-table"><table id="mx-pose" class="table">',
            "<caption>The stage's pose for these forces</caption>",
            "<thead><tr><th>pose component</th><th>unit</th><th>real-time model</th>"
            "<th>linear S<sub>T</sub> (Eq 8)</th><th>model − S<sub>T</sub></th>"
            f"<th>model's worst error against our FE on {heldout} held-out runs</th></tr></thead>",
            "<tbody>",
            *rows,
            "</tbody></table></div>",
            "</div>",
            '<div class="mx-views">',
            *views,
            "</div>",
            f'<p class="mx-legend">Grey, dashed: the stage at rest; blue: moved by the real-time '
            f"model's pose; red arrows: the forces ({data['drawing']['arrow_mm_per_n']:g} mm of "
            "the drawing a newton) where they act.</p>",
            '<p id="mx-timing" class="mx-timing">Measuring how long a pose takes in your '
            "browser…</p>",
            '<form id="mx-inverse" class="mx-inverse" novalidate>',
            "<fieldset><legend>The inverse: type a target pose, get the forces</legend>",
            *targets,
            '<p><button type="submit" id="mx-solve">Find the forces</button> '
            '<button type="button" id="mx-copy">Start from the pose shown above</button></p>',
            "</fieldset>",
            '<div id="mx-inverse-out" aria-live="polite"></div>',
            "</form>",
            "</div>",
            f"<script>{script.strip()}</script>",
            "</div>",
        ]
    )


def _list_table(header: Sequence[str], rows: Sequence[Sequence[str]]) -> list[str]:
    lines = ["```{list-table}", ":header-rows: 1", ":class: mx-preset", ""]
    for row in [header, *rows]:
        lines += [f"* - {row[0]}", *(f"  - {cell}" for cell in row[1:])]
    return [*lines, "```"]


def page_markdown(
    model: Mapping[str, Any],
    data: Mapping[str, Any],
    preset: tuple[Sequence[float], Sequence[float], Sequence[float]],
    widget: str,
    figure: str,
) -> str:
    """The page: what the model is, the interactive part (``widget``, raw HTML), the preset
    pose's figure (``figure``, numbered) and table, and how the page computes."""
    v = model["validation"]
    amp, heldout = data["amplitude_n"], data["heldout_runs"]
    worst = float(v.get("worst_pct_max", max(data["worst_pct"])))
    forces, pose, linear = preset
    mags = data["drawing"]["magnification"]
    names = ", ".join(
        f"{name} {_fmt(f, 2)} N" for name, f in zip(data["inputs"], forces, strict=True)
    )
    table = _list_table(
        [
            "pose component",
            "unit",
            "real-time model",
            "linear S_T (Eq 8)",
            "model − S_T",
            f"model's worst error against our FE on {heldout} held-out runs",
        ],
        [
            [o, u, _fmt(p, d), _fmt(q, d), _fmt(p - q, d), f"±{_fmt(w / 100 * r, d)}"]
            for o, u, p, q, w, r, d in zip(
                data["outputs"],
                data["units"],
                pose,
                linear,
                data["worst_pct"],
                data["range"],
                data["decimals"],
                strict=True,
            )
        ],
    )
    return "\n".join(
        [
            "---",
            "html_theme.sidebar_secondary.remove: true",
            "---",
            "",
            "# Try the model",
            "",
            "The {doc}`meta-model chapter </chapters/nonlinear_metamodels>` distils a real-time "
            f"model of the non-linear HexFlex: a Legendre polynomial of total degree "
            f"{data['degree']} ({data['terms']} terms a pose component) fitted to the "
            f"{v['teacher']}. On {heldout} held-out non-linear finite-element runs with forces "
            f"within ±{amp:g} N it misses by at most {worst:.3g} % of full scale. That error is "
            "against our finite-element model — one member of the family of parts with Eq 8's "
            "compliance, on its lean mesh, under dead loads — not against a device: the "
            "{doc}`family page </chapters/nonlinear_family>` shows members with the same S_T "
            "departing from one another by far more, and forces that turn with the tabs "
            "(follower loads) would move the poses too. "
            "This page evaluates that model in your browser. Set the six actuator forces (the "
            "thesis's names: tab T1 to T3, direction D1 in the plate's plane, D2 out of it) and "
            "it shows the stage's pose by the model beside the pose by the linear S_T of Eq 8, "
            "their difference and the model's worst error on those runs, and draws the moved "
            "stage. Below, type a target pose: Newton's method on the same polynomial finds the "
            "forces that reach it. The page computes all of it itself and loads nothing.",
            "",
            "```{raw} html",
            f":file: {widget}",
            "```",
            "",
            "```{raw} html",
            f'<p class="print-only">{LIVE_PAGE_TEXT} <a class="{LIVE_PAGE_CLASS}" '
            f'data-page="{LIVE_PAGE}" href="#">{LIVE_PAGE}</a>.</p>',
            "```",
            "",
            "## A preset pose",
            "",
            "For the preset forces below, {numref}`explorer-preset` draws the stage and the table "
            "gives its pose (the printed page shows these instead of the interactive part).",
            "",
            f"```{{figure}} {figure}",
            ":name: explorer-preset",
            ":align: center",
            ":alt: Three views of the HexFlex's triangular stage with its three tabs, at rest "
            "(dashed) and moved (filled), with arrows for the six forces",
            "",
            f"The HexFlex's stage and tabs moved by the real-time model's pose for the forces "
            f"{names}: top view (x, y and θz; displacements magnified ×{mags['in_plane']:g}) and "
            f"side views on the x–z and y–z planes (z, θx and θy; ×{mags['out_of_plane']:g}). "
            "Dashed grey: at rest; arrows: the forces "
            f"({data['drawing']['arrow_mm_per_n']:g} mm of the drawing a newton). The stage is "
            "drawn as a rigid plate moved by the pose (small rotations).",
            "```",
            "",
            *table,
            "",
            "## How the page computes",
            "",
            "The model's coefficients are written into this page when the book is built, from "
            "the meta-model chapter's record: the exact doubles of its "
            f"{data['terms']} × {len(data['outputs'])} coefficients. When that model changes, "
            "this page changes with it. A pose is the sum over the terms of products of scaled "
            f"Legendre polynomials √(2k+1) P_k(u), u = force / {amp:g} N, evaluated by their "
            "three-term recurrence in the same operations and order as the plain-Python "
            "evaluator of the data bundle, so that the browser's pose equals it to round-off. "
            "The inverse starts at zero force (its first step inverts the model's tangent "
            "there) and takes Newton steps "
            "with the polynomial's exact Jacobian (the derivative of the same recurrence), "
            "halving a step that does not reduce the largest error, until the target is met to "
            f"round-off; forces beyond ±{amp:g} N, where the model was not validated, are shown "
            "with a warning. The book's checks run this page in a headless browser: a Sobol' "
            "sample of force vectors goes through its own functions and the poses are compared "
            "with the Python evaluation of the same model, and the inverse's round trip is "
            "checked.",
            "",
        ]
    )
