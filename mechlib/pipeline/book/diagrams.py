"""Flow diagrams drawn with matplotlib: numbered steps in boxes, arrows, an optional loop back.

Used for the thesis's Fig 1 (the meta-modelling method) and Fig 9 (the identification protocol)
without a Graphviz binary: the layout is computed here (:func:`box_layout`, tested) and drawn in
data coordinates, so the figure is the same on every machine.
"""

from __future__ import annotations

import textwrap
from collections.abc import Sequence
from dataclasses import dataclass
from itertools import pairwise

import matplotlib.pyplot as plt
from matplotlib.patches import FancyArrowPatch, FancyBboxPatch

BOX_WIDTH = 6.0  # drawing units; the figure is BOX_WIDTH + margins wide
BOX_HEIGHT = 1.3
GAP = 0.55  # vertical space between boxes, where the arrows run
MARGIN = 0.4
LOOP_OFFSET = 0.55  # how far right of the boxes the loop-back arrow runs
WRAP = 68  # characters per line of a step's title
NOTE_LINES = 2  # a note longer than this many lines is shortened
INCHES_PER_UNIT = 0.9
BOX_COLOR = "#e8f0fa"
EDGE_COLOR = "#1f4e79"
NOTE_COLOR = "#555555"


@dataclass(frozen=True)
class Step:
    """One box: a title (wrapped) and an optional note in smaller grey type."""

    title: str
    note: str = ""


@dataclass(frozen=True)
class Loop:
    """An arrow from the right side of box ``source`` back up to box ``target`` (0-based)."""

    source: int
    target: int
    label: str


def box_layout(n_steps: int) -> list[tuple[float, float, float, float]]:
    """Rectangles ``(x0, y0, x1, y1)`` of ``n_steps`` boxes stacked top to bottom.

    Raises
    ------
    ValueError
        If ``n_steps`` < 1.
    """
    if n_steps < 1:
        raise ValueError(f"a flow diagram needs at least one step, got {n_steps}")
    top = n_steps * (BOX_HEIGHT + GAP) - GAP
    return [
        (0.0, top - i * (BOX_HEIGHT + GAP) - BOX_HEIGHT, BOX_WIDTH, top - i * (BOX_HEIGHT + GAP))
        for i in range(n_steps)
    ]


def arrow_segments(boxes: Sequence[tuple[float, float, float, float]]) -> list[tuple[tuple, tuple]]:
    """Start and end points of the arrows from each box's bottom to the next box's top."""
    return [(((a[0] + a[2]) / 2, a[1]), ((b[0] + b[2]) / 2, b[3])) for a, b in pairwise(boxes)]


def flow_diagram(steps: Sequence[Step], loop: Loop | None = None) -> plt.Figure:
    """Draw ``steps`` as numbered boxes joined by arrows, with an optional loop back.

    Parameters
    ----------
    steps : sequence of Step
        Top to bottom.
    loop : Loop, optional
        E.g. "repeat for the next leg" from the last box back to the first.

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    ValueError
        For no steps or a loop whose boxes do not exist or that does not go back up.
    """
    boxes = box_layout(len(steps))
    if loop is not None and not 0 <= loop.target < loop.source < len(steps):
        raise ValueError(
            f"a loop goes back up between existing steps 0..{len(steps) - 1}, "
            f"got {loop.source} -> {loop.target}"
        )
    extra = LOOP_OFFSET + 1.6 if loop else 0.0
    width = BOX_WIDTH + 2 * MARGIN + extra
    height = boxes[0][3] + 2 * MARGIN
    fig, ax = plt.subplots(figsize=(width * INCHES_PER_UNIT, height * INCHES_PER_UNIT))
    ax.set_xlim(-MARGIN, BOX_WIDTH + MARGIN + extra)
    ax.set_ylim(-MARGIN, boxes[0][3] + MARGIN)
    ax.set_axis_off()
    for number, (step, (x0, y0, x1, y1)) in enumerate(zip(steps, boxes, strict=True), start=1):
        ax.add_patch(
            FancyBboxPatch(
                (x0, y0),
                x1 - x0,
                y1 - y0,
                boxstyle="round,pad=0,rounding_size=0.12",
                facecolor=BOX_COLOR,
                edgecolor=EDGE_COLOR,
                linewidth=1.2,
            )
        )
        title = textwrap.fill(f"{number}. {step.title}", WRAP)
        ax.text(x0 + 0.15, y1 - 0.12, title, va="top", ha="left", fontsize=9.5, color="black")
        if step.note:
            note = textwrap.fill(step.note, int(WRAP * 1.2), max_lines=NOTE_LINES, placeholder=" …")
            ax.text(
                x0 + 0.15,
                y0 + 0.1,
                note,
                va="bottom",
                ha="left",
                fontsize=8,
                color=NOTE_COLOR,
                style="italic",
            )
    for start, end in arrow_segments(boxes):
        ax.add_patch(
            FancyArrowPatch(start, end, arrowstyle="-|>", mutation_scale=14, color=EDGE_COLOR)
        )
    if loop is not None:
        src, dst = boxes[loop.source], boxes[loop.target]
        x = BOX_WIDTH + LOOP_OFFSET
        y_src, y_dst = (src[1] + src[3]) / 2, (dst[1] + dst[3]) / 2
        ax.plot([BOX_WIDTH, x, x], [y_src, y_src, y_dst], color=EDGE_COLOR, linewidth=1.2)
        ax.add_patch(
            FancyArrowPatch(
                (x, y_dst),
                (BOX_WIDTH, y_dst),
                arrowstyle="-|>",
                mutation_scale=14,
                color=EDGE_COLOR,
            )
        )
        ax.text(
            x + 0.1,
            (y_src + y_dst) / 2,
            textwrap.fill(loop.label, 16),
            va="center",
            ha="left",
            fontsize=8.5,
            color=EDGE_COLOR,
        )
    fig.subplots_adjust(left=0, right=1, bottom=0, top=1)
    return fig
