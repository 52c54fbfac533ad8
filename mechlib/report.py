"""Rows of the reproduction report: published value, ours, difference, verdict.

Each notebook adds rows through :func:`compare_row` (numbers) or :func:`claim_row` (statements
checked by a computed test); :mod:`mechlib.bookbuild` gathers the rows of every record into the
book's report page. A verdict is never typed: it follows from the numbers and tolerances given.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mechlib.params import check_float

REPRODUCED = "reproduced"
WITHIN = "within tolerance"
DIVERGES = "diverges"
SUPPORTED = "claim supported"
NOT_SUPPORTED = "claim not supported"
COMPUTED = "computed (no published value)"


def _fmt(values: np.ndarray, digits: int = 6) -> str:
    flat = values.ravel()
    text = ", ".join(f"{v:.{digits}g}" for v in flat[:6])
    return text + (f", … ({flat.size} values)" if flat.size > 6 else "")


def compare_row(
    artefact: str,
    quantity: str,
    published: object,
    ours: object,
    *,
    resolution: object = 0.0,
    rtol: float = 0.0,
    atol: object = 0.0,
    tolerance: str = "",
    cause: str = "",
) -> dict[str, Any]:
    """Compare our value(s) with the published ones and classify the agreement.

    Parameters
    ----------
    artefact : str
        Thesis artefact, e.g. ``"Table 3"``.
    quantity : str
        What is compared, e.g. ``"|effects| (36 cells)"``.
    published, ours : array_like
        Same shape.
    resolution : array_like
        Half a unit of the last printed digit (see ``published.printed_resolution``): a
        difference within it is "reproduced".
    rtol : float
        Relative tolerance beyond printing for "within tolerance".
    atol : array_like
        Absolute tolerance added to ``rtol`` (e.g. a fraction of a row's scale, so that entries
        printed as exact zeros can be judged).
    tolerance : str
        How the tolerance reads in the verdict; default ``"<rtol> %"``.
    cause : str
        Why the values diverge, shown when they do. Required in that case.

    Returns
    -------
    dict
        A row with the published and our values (shortened), the largest absolute and relative
        difference and the verdict.
    """
    pub = np.asarray(published, dtype=float)
    our = np.asarray(ours, dtype=float)
    if pub.shape != our.shape:
        raise ValueError(f"published shape {pub.shape} differs from ours {our.shape}")
    rtol = check_float("rtol", rtol, low=0.0)
    res = np.broadcast_to(np.asarray(resolution, dtype=float), pub.shape)
    abs_tol = np.broadcast_to(np.asarray(atol, dtype=float), pub.shape)
    if np.any(abs_tol < 0) or np.any(res < 0):
        raise ValueError("atol and resolution must be >= 0")
    diff = np.abs(our - pub)
    rel = np.divide(diff, np.abs(pub), out=np.zeros_like(diff), where=pub != 0)
    # a tiny allowance for binary floating point on top of the printed half-digit
    slack = 1e-9 * np.maximum(np.abs(pub), 1.0)
    if np.all(diff <= res + slack):
        verdict = REPRODUCED
    elif np.all(diff <= res + rtol * np.abs(pub) + abs_tol + slack):
        verdict = f"{WITHIN} ({tolerance or f'{100 * rtol:g} %'})"
    else:
        if not cause:
            raise ValueError(f"{artefact} {quantity}: values diverge, a cause must be given")
        verdict = f"{DIVERGES}: {cause}"
    return {
        "artefact": artefact,
        "quantity": quantity,
        "published": _fmt(pub),
        "ours": _fmt(our),
        "max_abs_diff": float(diff.max()),
        "max_rel_diff": float(rel.max()),
        "verdict": verdict,
    }


def claim_row(artefact: str, claim: str, evidence: str, holds: bool) -> dict[str, Any]:
    """A row for a statement of the thesis checked by a computed test (``holds``)."""
    return {
        "artefact": artefact,
        "quantity": claim,
        "published": "(claim)",
        "ours": evidence,
        "max_abs_diff": None,
        "max_rel_diff": None,
        "verdict": SUPPORTED if bool(holds) else NOT_SUPPORTED,
    }


def computed_row(artefact: str, quantity: str, ours: object) -> dict[str, Any]:
    """A row for a number the thesis does not publish (ours only)."""
    return {
        "artefact": artefact,
        "quantity": quantity,
        "published": "—",
        "ours": _fmt(np.asarray(ours, dtype=float)),
        "max_abs_diff": None,
        "max_rel_diff": None,
        "verdict": COMPUTED,
    }
