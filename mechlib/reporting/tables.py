"""Tables for the reader: the thesis's values beside ours, in its layout, with units.

Arrays in, a :class:`pandas.DataFrame` of formatted text out; nothing is computed here. Every
cell shows :data:`DIGITS` significant digits, and a value whose magnitude is at most
``rel_zero`` times the largest one of its column (round-off residue of an exact zero, below the
solver's precision) is shown as ``0``. Column headers carry the units (``"x [µm]"``).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import pandas as pd

from mechlib.params import check_float, check_int

#: significant digits of a table cell
DIGITS = 4
#: Reader names of the stage-pose conventions of :mod:`mechlib.fe.finite_pose`.
POSE_CONVENTION_LABELS: dict[str, str] = {
    "small": "small-rotation fit",
    "rotvec": "rotation vector",
    "euler_xyz": "Euler XYZ angles",
}
#: the two sources a side-by-side table sets against each other
THESIS, OURS = "thesis", "ours"


def label(name: str, unit: str = "") -> str:
    """A header with its unit: ``label("x", "µm")`` → ``"x [µm]"`` (no brackets without one)."""
    return f"{name} [{unit}]" if unit else name


def labels(names: Sequence[str], units: Sequence[str] | str = "") -> list[str]:
    """:func:`label` over names.

    Parameters
    ----------
    names : sequence of str
    units : sequence of str or str
        One unit per name ("" for none), or one unit for all.

    Returns
    -------
    list of str

    Raises
    ------
    ValueError
        When ``units`` is a sequence of another length than ``names``.
    """
    units = [units] * len(names) if isinstance(units, str) else list(units)
    if len(units) != len(names):
        raise ValueError(f"{len(names)} names need as many units, got {len(units)}")
    return [label(n, u) for n, u in zip(names, units, strict=True)]


def number(value: float, digits: int = DIGITS, zero_below: float = 0.0) -> str:
    """One cell: ``digits`` significant digits, ``"0"`` at or below ``zero_below`` in magnitude,
    a true minus sign, no exponent between 1e-4 and 1e6.

    Parameters
    ----------
    value : float
    digits : int
        Significant digits, 1 .. 17.
    zero_below : float
        Magnitudes up to this are shown as ``"0"`` (round-off of an exact zero), at least 0.

    Returns
    -------
    str
        E.g. ``"57.53"``, ``"−28.76"``, ``"39313"``, ``"1.19e−08"``.

    Raises
    ------
    ValueError
        For ``digits`` or ``zero_below`` out of range.
    """
    digits = check_int("digits", digits, low=1, high=17)
    zero_below = check_float("zero_below", zero_below, low=0.0)
    value = float(value)
    if abs(value) <= zero_below:
        return "0"
    text = f"{value:.{digits}g}"
    if "e" in text and 1e-4 <= abs(value) < 1e6:
        text = f"{value:.{max(digits - 1 - int(np.floor(np.log10(abs(value)))), 0)}f}"
    return text.replace("-", "−")


def formatted(
    values: np.ndarray,
    digits: int = DIGITS,
    rel_zero: float = 0.0,
    axis: int | None = 0,
    zero_below: object = 0.0,
) -> np.ndarray:
    """An array of cell texts: :func:`number` of each value.

    Parameters
    ----------
    values : numpy.ndarray
        One or two dimensions.
    digits : int
        Significant digits.
    rel_zero : float
        A value at most this share of the largest magnitude along ``axis`` (0: per column,
        None: of the whole array) is shown as 0, in [0, 1].
    axis : int or None
    zero_below : array_like
        Absolute magnitudes at or below which a value is shown as 0, broadcast to the values'
        shape; the larger of the two floors applies.

    Returns
    -------
    numpy.ndarray of str, two-dimensional
    """
    arr = np.atleast_2d(np.asarray(values, dtype=float))
    rel_zero = check_float("rel_zero", rel_zero, low=0.0, high=1.0)
    scale = np.abs(arr).max(axis=axis, keepdims=True) if arr.size else np.zeros((1, 1))
    floor = np.maximum(
        np.broadcast_to(rel_zero * scale, arr.shape),
        np.broadcast_to(np.asarray(zero_below, dtype=float), arr.shape),
    )
    cells = [
        number(v, digits, z) for v, z in zip(arr.ravel(), floor.ravel(), strict=True)
    ]  # fmt: skip
    return np.array(cells, dtype=object).reshape(arr.shape)


def table(
    values: np.ndarray,
    index: Sequence[str],
    columns: Sequence[str],
    *,
    digits: int = DIGITS,
    rel_zero: float = 0.0,
    axis: int | None = 0,
    index_name: str | None = None,
) -> pd.DataFrame:
    """A table of formatted values with the given headers.

    Parameters
    ----------
    values : numpy.ndarray, shape (len(index), len(columns))
    index, columns : sequence of str
        Row and column headers (with units, see :func:`labels`).
    digits, rel_zero, axis
        As in :func:`formatted`.
    index_name : str, optional
        The header of the row labels.

    Returns
    -------
    pandas.DataFrame
        Text cells.
    """
    cells = formatted(values, digits, rel_zero, axis)
    frame = pd.DataFrame(cells, index=list(index), columns=list(columns))
    frame.index.name = index_name
    return frame


#: enough significant digits to show a printed value of the thesis as printed
PRINTED = 7


def _per_source(digits: int | Mapping[str, int], sources: Mapping[str, object]) -> dict[str, int]:
    if isinstance(digits, Mapping):
        return {k: digits.get(k, DIGITS) for k in sources}
    return dict.fromkeys(sources, digits)


def side_by_side(
    sources: Mapping[str, np.ndarray],
    index: Sequence[str],
    columns: Sequence[str],
    *,
    digits: int | Mapping[str, int] = DIGITS,
    rel_zero: float | Mapping[str, float] = 0.0,
    index_name: str | None = None,
    lead: pd.DataFrame | None = None,
    zero_below: Mapping[str, object] | None = None,
) -> pd.DataFrame:
    """One column group per quantity, one sub-column per source (the thesis's, ours, …).

    Parameters
    ----------
    sources : mapping of str to numpy.ndarray
        ``{"thesis": published, "ours": ours}``, each of shape (rows, columns).
    index, columns : sequence of str
        Row labels and quantity headers (with units, see :func:`labels`).
    digits : int or mapping of str to int
        Significant digits, or per source (e.g. enough for the thesis's values as printed).
    rel_zero : float or mapping of str to float
        Per source: values at most this share of their column's largest magnitude are shown as
        0 (round-off of exact zeros; 0 for printed values, which are shown as printed).
    index_name : str, optional
        The header of the row labels.
    lead : pandas.DataFrame, optional
        Columns shown first as they are (e.g. a design's forces), same rows.
    zero_below : mapping of str to array_like, optional
        Per source, absolute magnitudes at or below which a value is shown as 0 (e.g. a
        solver's precision), broadcast to the source's shape.

    Returns
    -------
    pandas.DataFrame
        Columns ``(quantity, source)``, e.g. ``("x [µm]", "thesis")``.

    Raises
    ------
    ValueError
        For sources of different shapes or headers that do not fit them.
    """
    shapes = {k: np.shape(v) for k, v in sources.items()}
    want = (len(index), len(columns))
    if any(s != want for s in shapes.values()):
        raise ValueError(f"every source must have shape {want} (rows, columns), got {shapes}")
    zeros = rel_zero if isinstance(rel_zero, Mapping) else dict.fromkeys(sources, rel_zero)
    floors = dict(zero_below or {})
    places = _per_source(digits, sources)
    cells = {
        k: formatted(v, places[k], zeros.get(k, 0.0), zero_below=floors.get(k, 0.0))
        for k, v in sources.items()
    }
    data = {
        (col, src): cells[src][:, j] for j, col in enumerate(columns) for src in sources
    }  # fmt: skip
    frame = pd.DataFrame(data, index=list(index))
    frame.columns = pd.MultiIndex.from_tuples(frame.columns)
    if lead is not None:
        head = lead.copy()
        head.index = frame.index
        head.columns = pd.MultiIndex.from_tuples([(c, "") for c in head.columns])
        frame = pd.concat([head, frame], axis=1)
    frame.index.name = index_name
    return frame


def stacked(
    sources: Mapping[str, np.ndarray],
    index: Sequence[str],
    columns: Sequence[str],
    *,
    digits: int | Mapping[str, int] = DIGITS,
    rel_zero: float | Mapping[str, float] = 0.0,
) -> pd.DataFrame:
    """Matrices one above the other, each under its source's name (e.g. Eq 8 over our S_T).

    Parameters
    ----------
    sources : mapping of str to numpy.ndarray
        Source name → matrix of shape (len(index), len(columns)).
    index, columns : sequence of str
        Row headers (with units) and column headers.
    digits : int or mapping of str to int
        Significant digits, or per source.
    rel_zero : float or mapping of str to float
        Values at most this share of their matrix's largest magnitude are shown as 0.

    Returns
    -------
    pandas.DataFrame
        Rows ``(source, row header)``.
    """
    zeros = rel_zero if isinstance(rel_zero, Mapping) else dict.fromkeys(sources, rel_zero)
    places = _per_source(digits, sources)
    parts = {
        k: table(v, index, columns, digits=places[k], rel_zero=zeros.get(k, 0.0), axis=None)
        for k, v in sources.items()
    }
    return pd.concat(parts)


def printed_vs_ours(
    rows: Sequence[str],
    printed: Mapping[str, Sequence[str]],
    ours: Mapping[str, Sequence[str]],
) -> pd.DataFrame:
    """A table of text cells in the thesis's layout, each column as printed beside ours.

    Parameters
    ----------
    rows : sequence of str
        The thesis's row headers.
    printed, ours : mapping of str to sequence of str
        Column header → one cell per row (the thesis's text; ours for the same cells), same
        headers in both.

    Raises
    ------
    ValueError
        For different headers or a column without one cell per row.
    """
    if list(printed) != list(ours):
        raise ValueError(
            f"printed and ours need the same columns, got {list(printed)}, {list(ours)}"
        )
    for name, cells in (*printed.items(), *ours.items()):
        if len(cells) != len(rows):
            raise ValueError(f"column {name!r} needs {len(rows)} cells, got {len(cells)}")
    data = {
        (c, src): list(cells[c])
        for c in printed
        for src, cells in ((THESIS, printed), (OURS, ours))
    }
    frame = pd.DataFrame(data, index=list(rows))
    frame.columns = pd.MultiIndex.from_tuples(frame.columns)
    return frame


def latex_matrix_equation(
    lhs: str, matrix: np.ndarray, tag: str = "", digits: int = 7, rhs: str = ""
) -> str:
    """A display equation ``lhs = [matrix] rhs (tag)`` in LaTeX, each entry as :func:`number`
    gives it (with ``digits`` high enough, a printed value is shown as printed).

    Parameters
    ----------
    lhs : str
        LaTeX of the left-hand side, e.g. ``"S_T"``.
    matrix : numpy.ndarray, shape (rows, columns)
    tag : str
        The equation's number in the thesis (``"8"``), shown as ``(8)``; none if empty.
    digits : int
        Significant digits of each entry.
    rhs : str
        LaTeX after the matrix (e.g. a unit), optional.

    Returns
    -------
    str
        LaTeX for a display formula (no ``$$``), rows separated by ``\\cr``.
    """
    arr = np.atleast_2d(np.asarray(matrix, dtype=float))
    # rows end with \cr, not \\: Sphinx wraps a display formula holding \\ in a split
    # environment, where MathJax refuses the \tag
    body = r" \cr ".join(
        " & ".join(number(v, digits).replace("−", "-") for v in row) for row in arr
    )  # fmt: skip
    tagged = rf" \tag{{{tag}}}" if tag else ""
    return rf"{lhs} = \begin{{bmatrix}} {body} \end{{bmatrix}}{rhs}{tagged}"
