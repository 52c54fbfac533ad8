"""The book's page "Try the model": the meta-model chapter's real-time model, in the browser.

:func:`write_explorer` reads the model the meta-model notebook recorded
(``records/data/nonlinear_metamodels/realtime_model.json``, written by
:func:`mechlib.metamodels.export.to_dict`) and writes into ``book/generated/``:

* ``explorer_model.js``, a classic script ``window.MECHLIB_EXPLORER = {...};``: the model as a
  JavaScript literal (:func:`literal`), exact and compact — the coefficients as their IEEE
  doubles (little-endian, base64; half the bytes of their shortest decimal repr), the exponents
  one digit each;
* ``explorer_widget.html``, the page's interactive part (:mod:`explorerpage`) with that script
  inline, which ``book/_static/explorer.js`` drives (no file is fetched: it reads from
  ``file://``);
* ``explorer_preset.svg``, the static figure of a preset pose that the printed page shows (the
  same views as the interactive part's, :mod:`explorerdraw`);
* ``explorer.md``, the page, every number on it read from the model's record.

When the model changes, all of them change with it; when its record is missing, nothing stale is
left behind and the problem names the file.
"""

from __future__ import annotations

import base64
import json
import math
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from mechlib.metamodels import evaluator, export
from mechlib.pipeline.book import explorerdraw, explorerpage
from mechlib.reporting.records import DATA_DIR

MODEL_NOTEBOOK = "nonlinear_metamodels"
"""The notebook whose record holds the model."""
MODEL_FILE = "realtime_model.json"
PAGE = "explorer"
"""The page's name under ``book/generated/`` (its ``_toc.yml`` entry: ``generated/explorer``)."""
SCRIPT_FILE = "explorer_model.js"
WIDGET_FILE = "explorer_widget.html"
FIGURE_FILE = "explorer_preset.svg"
GLOBAL = "MECHLIB_EXPLORER"
"""The literal's name on the page (``window.MECHLIB_EXPLORER``)."""
PRESET = (0.6, -0.4, 0.3, 0.8, -0.5, -0.7)
"""The preset forces of the printed figure, as shares of the validated force range: every
force non-zero, so that all six pose components move."""
DISPLAY_RESOLUTION = 1e-4
"""Pose values are shown to this fraction of full scale (decimals per component)."""
CHECK_TOLERANCE = 1e-12
"""The model's own check poses must be met to this fraction of full scale."""
VALIDATION_KEYS = ("worst_pct", "range", "S_T", "heldout_runs", "teacher", "degree")
"""What the model's ``validation`` must hold for the page."""


def model_path(records: Path) -> Path:
    """Where the meta-model notebook records the real-time model."""
    return Path(records) / DATA_DIR / MODEL_NOTEBOOK / MODEL_FILE


def check_model(model: Mapping[str, Any]) -> None:
    """Raise ValueError naming what the page cannot use in an exported model dict."""
    if model.get("format") != export.FORMAT:
        raise ValueError(f"format must be {export.FORMAT!r}, got {model.get('format')!r}")
    n_in, n_out = len(model["inputs"]), len(model["outputs"])
    if n_in != n_out or len(model["units"]) != n_out:
        raise ValueError(
            f"inputs, outputs and units must have one entry per force and pose component "
            f"(a square model, for the inverse), got {n_in}, {n_out} and {len(model['units'])}"
        )
    missing = [k for k in VALIDATION_KEYS if k not in model["validation"]]
    if missing:
        raise ValueError(f"validation must hold {list(VALIDATION_KEYS)}, missing {missing}")
    v = model["validation"]
    for key in ("worst_pct", "range"):
        if len(v[key]) != n_out:
            raise ValueError(f"validation[{key!r}] must have {n_out} entries, got {len(v[key])}")
    if not all(math.isfinite(r) and r > 0 for r in v["range"]):
        raise ValueError(f"validation['range'] must be finite and > 0, got {v['range']}")
    if np.shape(v["S_T"]) != (n_out, n_in):
        raise ValueError(f"validation['S_T'] must be {n_out} × {n_in}, got {np.shape(v['S_T'])}")
    exps = np.asarray(model["exponents"])
    if exps.ndim != 2 or exps.shape[1] != n_in or exps.min() < 0 or exps.max() > 9:
        raise ValueError(
            f"exponents must be (terms, {n_in}) integers in 0 .. 9 (one digit each), "
            f"got shape {exps.shape}, range {exps.min()} .. {exps.max()}"
        )


def load_model(records: Path) -> dict[str, Any]:
    """The recorded real-time model, checked (:func:`check_model`) and checked against its own
    check poses by the plain-Python evaluator (within :data:`CHECK_TOLERANCE` of each range).

    Raises
    ------
    FileNotFoundError
        When the meta-model notebook recorded no model (naming the file looked for).
    ValueError
        When the model is malformed or misses its check poses.
    """
    path = model_path(records)
    if not path.is_file():
        raise FileNotFoundError(
            f"{path}: no real-time model recorded (the {MODEL_NOTEBOOK} notebook writes it); "
            f"the page {PAGE} needs it"
        )
    model = json.loads(path.read_text())
    check_model(model)
    ranges = model["validation"]["range"]
    for forces, expected in zip(model["check"]["forces_n"], model["check"]["poses"], strict=True):
        got = evaluator.pose(model, forces)
        worst = max(abs(g - e) / r for g, e, r in zip(got, expected, ranges, strict=True))
        if worst > CHECK_TOLERANCE:
            raise ValueError(
                f"the model misses its check pose at forces {forces} by {worst:.3g} of a range, "
                f"allowed {CHECK_TOLERANCE:g}"
            )
    return model


def pack_doubles(values: np.ndarray) -> str:
    """Base64 of the little-endian IEEE doubles of ``values`` (row-major): exact, 10.7 characters
    a number."""
    return base64.b64encode(np.ascontiguousarray(values, dtype="<f8").tobytes()).decode("ascii")


def unpack_doubles(text: str) -> np.ndarray:
    """The doubles :func:`pack_doubles` wrote (flat)."""
    return np.frombuffer(base64.b64decode(text), dtype="<f8").copy()


def pack_exponents(exponents: Sequence[Sequence[int]]) -> str:
    """The exponents, row-major, one decimal digit each (all in 0 .. 9)."""
    return "".join(str(int(k)) for row in exponents for k in row)


def unpack_exponents(text: str, n_inputs: int) -> list[list[int]]:
    """The exponents :func:`pack_exponents` wrote, ``n_inputs`` a row."""
    return [[int(c) for c in text[i : i + n_inputs]] for i in range(0, len(text), n_inputs)]


def decimals(ranges: Sequence[float]) -> list[int]:
    """Decimals that show each component to :data:`DISPLAY_RESOLUTION` of its range."""
    return [max(0, math.ceil(-math.log10(r * DISPLAY_RESOLUTION))) for r in ranges]


def literal(model: Mapping[str, Any]) -> dict[str, Any]:
    """What the page's script needs, JSON-ready: the model (exact), its validation, the drawing.

    Keys: ``amplitude_n``, ``inputs``, ``outputs``, ``units``, ``degree``, ``terms``,
    ``exponents`` (:func:`pack_exponents`), ``coef_b64`` (:func:`pack_doubles`, terms ×
    outputs), ``S_T``, ``range``, ``worst_pct``, ``heldout_runs``, ``decimals``, ``drawing``
    (outline and actuators [mm], directions, magnifications, views and their limits, arrow scale).
    """
    v = model["validation"]
    shape = explorerdraw.outline()
    reach = float(np.hypot(*shape.T).max())
    at, dirs = explorerdraw.actuators()
    return {
        "amplitude_n": float(model["amplitude_n"]),
        "inputs": list(model["inputs"]),
        "outputs": list(model["outputs"]),
        "units": list(model["units"]),
        "degree": int(np.max(model["exponents"])),
        "terms": len(model["exponents"]),
        "exponents": pack_exponents(model["exponents"]),
        "coef_b64": pack_doubles(np.asarray(model["coef"], dtype=float)),
        "S_T": [[float(s) for s in row] for row in v["S_T"]],
        "range": [float(r) for r in v["range"]],
        "worst_pct": [float(w) for w in v["worst_pct"]],
        "heldout_runs": int(v["heldout_runs"]),
        "decimals": decimals(v["range"]),
        "drawing": {
            "outline_mm": np.round(shape, 4).tolist(),
            "actuators_mm": np.round(at, 4).tolist(),
            "directions": np.round(dirs, 12).tolist(),
            "magnification": explorerdraw.magnifications(v["range"], reach),
            "views": [
                {
                    "name": n,
                    "h": h,
                    "v": w,
                    "magnification": m,
                    "limits": lim,
                    "forces": explorerdraw.shown_forces(dirs, w),
                }
                for (n, h, w, m), lim in zip(
                    explorerdraw.VIEWS, explorerdraw.extents(reach), strict=True
                )
            ],
            "arrow_mm_per_n": explorerdraw.ARROW_MM_PER_N,
        },
    }


def script_text(data: Mapping[str, Any]) -> str:
    """The classic script defining ``window.MECHLIB_EXPLORER`` (safe inside ``<script>``)."""
    text = json.dumps(data, ensure_ascii=False, separators=(",", ":")).replace("</", "<\\/")
    return f"window.{GLOBAL} = {text};\n"


def read_script(text: str) -> dict[str, Any]:
    """The literal of a script :func:`script_text` wrote, or of a page that carries it inline."""
    start = text.index(f"window.{GLOBAL} = ") + len(f"window.{GLOBAL} = ")
    data, _ = json.JSONDecoder().raw_decode(text, start)  # JSON reads "<\\/" as "</"
    return data


def model_of(data: Mapping[str, Any]) -> dict[str, Any]:
    """The model dict (as :func:`mechlib.metamodels.export.to_dict` writes it, without its check
    values) that a literal carries: what the page evaluates."""
    n_in, n_out = len(data["inputs"]), len(data["outputs"])
    return {
        "format": export.FORMAT,
        "amplitude_n": data["amplitude_n"],
        "inputs": data["inputs"],
        "outputs": data["outputs"],
        "units": data["units"],
        "exponents": unpack_exponents(data["exponents"], n_in),
        "coef": unpack_doubles(data["coef_b64"]).reshape(-1, n_out).tolist(),
        "validation": {"S_T": data["S_T"], "range": data["range"], "teacher": ""},
    }


def preset(model: Mapping[str, Any]) -> tuple[list[float], list[float], list[float]]:
    """The preset forces [N] and their poses by the model and by S_T."""
    forces = [share * float(model["amplitude_n"]) for share in PRESET]
    linear = (np.asarray(model["validation"]["S_T"]) @ forces).tolist()
    return forces, evaluator.pose(model, forces), linear


def figure_text(model: Mapping[str, Any], data: Mapping[str, Any]) -> str:
    """The static figure of the preset pose (:func:`explorerdraw.figure_svg`), as SVG."""
    forces, pose, _ = preset(model)
    return explorerdraw.figure_svg(data["drawing"], pose, forces)


def outputs(book: Path) -> list[Path]:
    """The files :func:`write_explorer` writes."""
    folder = Path(book) / "generated"
    return [folder / name for name in (f"{PAGE}.md", SCRIPT_FILE, WIDGET_FILE, FIGURE_FILE)]


def _write(path: Path, text: str) -> None:
    if not path.exists() or path.read_text() != text:
        path.write_text(text)


def write_explorer(records: Path, book: Path, footer: str = "") -> list[str]:
    """Write the page ``generated/explorer.md`` and its files from the recorded model.

    Parameters
    ----------
    records : Path
        The build's records folder (``build/records``).
    book : Path
        The book's source folder.
    footer : str
        Markdown appended to the page (the build's provenance block).

    Returns
    -------
    list of str
        Problems (empty when the page was written): the missing or malformed model, named; its
        files are then removed, so that no stale page is built.
    """
    try:
        model = load_model(records)
    except (FileNotFoundError, ValueError, KeyError) as err:
        for path in outputs(book):
            path.unlink(missing_ok=True)
        where = "" if isinstance(err, FileNotFoundError) else f"{model_path(records)}: "
        return [f"explorer page not written: {where}{err}"]
    page, script, widget, figure = outputs(book)
    page.parent.mkdir(parents=True, exist_ok=True)
    data = literal(model)
    js = script_text(data)
    _write(script, js)
    _write(widget, explorerpage.widget_html(data, js))
    _write(figure, figure_text(model, data))
    text = explorerpage.page_markdown(model, data, preset(model), WIDGET_FILE, FIGURE_FILE)
    _write(page, text + footer)
    return []
