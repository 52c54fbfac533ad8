"""The pages that show the thesis's Fig 1 (meta-modelling method) and Fig 9 (identification
protocol), each step linked to the section of the book that carries it out.

The steps paraphrase the thesis (sec. 2.5 for Fig 1, sec. 3.6 for Fig 9). Where each step is
implemented is given as ``(page, artefact or heading text)``, resolved against the chapter pages'
headings when the book is built (:func:`~mechlib.reporting.artefacts.find_section`), and as
the mechlib functions that do the work (tested to exist).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import matplotlib.pyplot as plt

from mechlib.metamodels.metrics import FULL_SCALE, FULL_SCALE_DEFINITION
from mechlib.metamodels.realtime import DEADLINE_US
from mechlib.pipeline.book.diagrams import Loop, Step, flow_diagram

#: the measures every page of the book uses, defined once here (on the method page of Fig 1)
MEASURES = f"""\
## Measures used throughout this book

**{FULL_SCALE}.** {FULL_SCALE_DEFINITION} MAXABS (Eq 10) and RMSE (Eq 11) are absolute errors, in
the pose component's units; "% of full scale" divides MAXABS by the full scale. Where two sets of
runs give two numbers for one quantity, the sentence names the set of runs.

**Real time.** A model is real-time when one pose, one call at a time, takes at most
{DEADLINE_US:g} µs: the period of a {1e3 / DEADLINE_US:g} kHz control loop. The thesis names no
rate; this one is our choice of a feedback rate for a nano-positioner, not a figure of the thesis
or of the HexFlex's controller. Every timing judgement of the book uses this one deadline.
"""


@dataclass(frozen=True)
class MethodStep:
    """A step of a method figure, where the book shows it and which functions do it."""

    title: str
    shown_in: tuple[tuple[str, str], ...]
    functions: tuple[str, ...]


@dataclass(frozen=True)
class MethodFigure:
    """A method figure of the thesis and the page that shows it."""

    page: str  # page name under book/generated/
    heading: str
    figure: str  # "Fig 1"
    caption: str
    steps: tuple[MethodStep, ...]
    loop: Loop | None = None
    notes: str = ""  # Markdown after the table: definitions the whole book uses


FIG1 = MethodFigure(
    page="method_doe",
    heading="The meta-modelling method (Fig 1)",
    figure="Fig 1",
    caption=(
        "Methodology for force–displacement meta-modelling of compliant mechanisms (thesis sec. "
        "2.5): six steps from the mechanism's topology to a verified meta-model, redrawn by code. "
        "The grey line in each box and the table below name the sections of this book that carry "
        "the step out."
    ),
    steps=(
        MethodStep(
            "Define the mechanism's topology; the factors are its input forces τ",
            (("published_doe", "Table 1"), ("hexflex_model", "layout")),
            ("mechlib.published", "mechlib.hexflex.geometry.actuator_directions"),
        ),
        MethodStep(
            "Build a virtual (finite-element) model of the mechanism",
            (("hexflex_model", "identification"), ("hexflex_model", "Figures 2–5")),
            ("mechlib.hexflex.fe.model.HexFlexModel", "mechlib.hexflex.identify.identify"),
        ),
        MethodStep(
            "Screen the factors with a factorial design (Plackett–Burman)",
            (("published_doe", "Tables 2–3"), ("virtual_experiments", "Table 2")),
            (
                "mechlib.doe.plackett_burman",
                "mechlib.screening.main_effects",
                "mechlib.screening.lenth",
            ),
        ),
        MethodStep(
            "Fine-tune with a space-filling design (uniform design)",
            (("published_doe", "Table 4"), ("virtual_experiments", "Table 4")),
            (
                "mechlib.doe.centered_l2_discrepancy_squared",
                "mechlib.campaign.experiments.run_experiments",
            ),
        ),
        MethodStep(
            "Construct the surrogate (meta-)model of the kinematics",
            (("published_doe", "Eq 8"), ("virtual_experiments", "Eqs 6–9")),
            (
                "mechlib.metamodels.linear.fit_linear",
                "mechlib.metamodels.quadratic.fit_quadratic",
                "mechlib.metamodels.linear.inverse",
            ),
        ),
        MethodStep(
            "Verify the meta-model's accuracy with extra experiments",
            (("virtual_experiments", "Table 5"),),
            (
                "mechlib.metamodels.metrics.error_metrics",
                "mechlib.hexflex.studies.linearity.linearity_sweep",
            ),
        ),
    ),
    notes=MEASURES,
)

FIG9 = MethodFigure(
    page="protocol_5r",
    heading="The identification protocol (Fig 9)",
    figure="Fig 9",
    caption=(
        "Kinematic identification protocol of parallel symmetrical mechanisms (thesis sec. 3.6), "
        "redrawn by code: each leg κ is identified on its own, with postures chosen for that leg, "
        "and the protocol repeats until every leg is identified. The grey line in each box and the "
        "table below name the sections of this book that carry the step out on the planar 5R."
    ),
    steps=(
        MethodStep(
            "From the nominal parameters φκ and the inverse kinematics gκ (Eqs 12–13), "
            "compute the identification Jacobian Cκ = ∂gκ/∂φκᵀ over candidate postures "
            "(Eq 17)",
            (("fivebar_identification", "Fig 12"),),
            ("mechlib.dyad.jacobian",),
        ),
        MethodStep(
            "Select the postures Rκ that maximise the observability O₁(Cκ) by active "
            "calibration (Eq 18)",
            (("fivebar_identification", "Fig 12"),),
            (
                "mechlib.calibration.selection.select_active",
                "mechlib.calibration.selection.observability_o1",
            ),
        ),
        MethodStep(
            "Measure the end-effector poses R̂κ and joint readings Q̂κ there, and solve "
            "Eq 16 (least squares on the inverse kinematics)",
            (("fivebar_identification", "Table 7"),),
            (
                "mechlib.calibration.mechanism.simulate",
                "mechlib.calibration.identify.identify_leg",
            ),
        ),
        MethodStep(
            "Update the mechanism's kinematic model with the identified φκ",
            (("fivebar_identification", "Fig 14"),),
            (
                "mechlib.calibration.mechanism.pose_errors",
                "mechlib.calibration.statistics.local_rms",
            ),
        ),
    ),
    loop=Loop(source=3, target=0, label="next leg κ + 1, until all legs are identified"),
)

METHOD_FIGURES = (FIG1, FIG9)


def _note(step: MethodStep) -> str:
    return "in this book: " + "; ".join(
        f"{page.replace('_', ' ')} · {what}" for page, what in step.shown_in
    )


def draw(method: MethodFigure) -> plt.Figure:
    """The method's flow diagram (the boxes carry where the book implements each step)."""
    return flow_diagram([Step(s.title, _note(s)) for s in method.steps], method.loop)


def alt_text(method: MethodFigure) -> str:
    """The figure's alt text: a flow diagram and its steps in order, in words."""
    steps = "; ".join(f"{i}. {step.title}" for i, step in enumerate(method.steps, 1))
    return f"Flow diagram of {len(method.steps)} steps: {steps}".replace("\n", " ")


def page_markdown(method: MethodFigure, image: str, link: Callable[[str, str], str]) -> str:
    """The MyST page showing ``image`` with its caption and the step-by-step table of links.

    Parameters
    ----------
    method : MethodFigure
    image : str
        Path of the drawn figure relative to the page.
    link : callable
        ``link(page, what)`` returns the MyST link to the section of ``page`` showing ``what``.
    """
    lines = [
        f"# {method.heading}",
        "",
        # a numbered figure ("Figure N", the book's numbering); the caption names the thesis's
        f"```{{figure}} {image}",
        f":alt: {alt_text(method)}",
        ":align: center",
        f":name: {method.page}-figure",
        "",
        f"Thesis {method.figure}, redrawn. {method.caption}",
        "```",
        "",
        "```{list-table}",
        ":header-rows: 1",
        ":widths: 40 32 28",
        "",
        "* - step",
        "  - where this book carries it out",
        "  - mechlib functions",
    ]
    for number, step in enumerate(method.steps, start=1):
        where = "; ".join(link(page, what) for page, what in step.shown_in)
        funcs = ", ".join(f"`{f}`" for f in step.functions)
        lines += [f"* - {number}. {step.title}", f"  - {where}", f"  - {funcs}"]
    lines.append("```")
    if method.loop is not None:
        lines += [
            "",
            f"After step {method.loop.source + 1}: {method.loop.label} "
            f"(back to step {method.loop.target + 1}).",
        ]
    if method.notes:
        lines += ["", method.notes.rstrip("\n")]
    return "\n".join(lines) + "\n"


def write_pages(folder: Path, link: Callable[[str, str], str]) -> list[Path]:
    """Draw every method figure as SVG into ``folder`` and write its page; return the pages."""
    folder.mkdir(parents=True, exist_ok=True)
    pages = []
    for method in METHOD_FIGURES:
        image = f"{method.page}.svg"
        with plt.rc_context({"svg.hashsalt": "mechlib"}):  # the same SVG on every build
            fig = draw(method)
            fig.savefig(folder / image, format="svg", metadata={"Date": None})
        plt.close(fig)
        page = folder / f"{method.page}.md"
        text = page_markdown(method, image, link)
        if not page.exists() or page.read_text() != text:
            page.write_text(text)
        pages.append(page)
    return pages
