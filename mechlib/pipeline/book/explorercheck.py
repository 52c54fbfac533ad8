"""The explorer page's own JavaScript, checked in headless Chromium against Python's evaluation.

``python -m mechlib.pipeline.book.explorercheck --html book/_build/html --records build/records``
(``--out FILE``: where the measured numbers go, by default ``explorer-check.json`` beside the
HTML folder)

From ``file://`` with the network off (the flags of :mod:`mechlib.pipeline.book.browser`):

* the built page ``generated/explorer.html`` runs its script: the interactive part shows, the
  pose table is filled and the page measured its own time a pose;
* a check page, written into a temporary folder with a copy of the built ``_static/explorer.js``
  and the model literal taken from the built page, feeds :data:`N_POSES` scrambled Sobol' force
  vectors within the validated range through ``window.mechlibExplorer.pose`` and
  :data:`N_TARGETS` target poses (of random forces within :data:`TARGET_SHARE` of the range)
  through ``.inverse``, takes ``.jacobian`` at :data:`N_JACOBIANS` of the vectors, times the
  poses and writes the results into its DOM as JSON;
* the poses are compared with the plain-Python evaluator and with NumPy's
  (:func:`mechlib.metamodels.families.predict_array`) on the same model: the largest
  difference must be at most :data:`POSE_TOL` of each component's range; each inverse must
  converge, its forces give back the target within :data:`ROUND_TRIP_TOL` of each range (by
  Python) and the forces that made it within :data:`FORCE_TOL`; the Jacobian must meet central
  differences of the Python evaluation within :data:`JACOBIAN_TOL`;
* the page's literal must carry the recorded model exactly (coefficients bit for bit, the same
  validated errors);
* the files only the page brings (:data:`PAGE_FILES`) weigh at most :data:`PAGE_BUDGET` bytes.

The measured numbers (largest differences, round trip, µs a pose in the browser: a timing, not
compared) are written to a JSON file. Exit status 0 when every check passes, 1 when one fails,
2 when the built page or the record is missing, 3 when no Chromium is installed.
"""

from __future__ import annotations

import argparse
import html
import json
import re
import shutil
import sys
import tempfile
from pathlib import Path
from typing import Any

import numpy as np
from scipy.stats import qmc
from threadpoolctl import threadpool_limits

from mechlib.metamodels import evaluator, export
from mechlib.metamodels.families import predict_array
from mechlib.pipeline.book import browser, explorer

N_POSES = 2**10
"""Force vectors fed through the page's pose function (a balanced Sobol' sample)."""
N_TARGETS = 16
"""Target poses fed through the page's inverse."""
TARGET_SHARE = 0.9
"""The targets' forces lie within this share of the validated range."""
SEED = 2010
"""Seed of the Sobol' scrambling and of the targets' forces."""
POSE_TOL = 1e-12
"""Largest allowed |page − Python| pose difference, as a fraction of full scale."""
ROUND_TRIP_TOL = 1e-10
"""Largest allowed |pose(forces found) − target| (Python's pose), as a fraction of full scale."""
FORCE_TOL = 1e-9
"""Largest allowed |forces found − forces that made the target| [N]."""
N_JACOBIANS = 4
"""Force vectors (the first of the Sobol' sample) where the page's Jacobian is checked."""
FD_STEP = 1e-5
"""Step [N] of the central differences the page's Jacobian is compared with."""
JACOBIAN_TOL = 1e-7
"""Largest allowed |page Jacobian − central differences|, as a fraction of full scale per N."""
TIMING_MS = 200
"""The check page times poses for at least this long."""
PAGE_BUDGET = 100_000
"""Bytes the page may add to the built book: its HTML (with the model literal), script, style,
figure and source copy."""
PAGE = Path("generated") / f"{explorer.PAGE}.html"
SCRIPT = Path("_static") / "explorer.js"
#: the built files that only the explorer page brings
PAGE_FILES = (
    PAGE,
    SCRIPT,
    Path("_static") / "explorer.css",
    Path("_images") / explorer.FIGURE_FILE,
    Path("_sources") / "generated" / f"{explorer.PAGE}.md",
)
RESULT_ID = "mx-check"

CHECK_PAGE = """<!DOCTYPE html>
<html><head><meta charset="utf-8"><title>explorer check</title></head><body>
<script>{literal}</script>
<script src="explorer.js"></script>
<script>
var F = {forces}, T = {targets}, X = window.mechlibExplorer;
var out = {{poses: [], inverse: [], errors: []}};
try {{
  for (var i = 0; i < F.length; i++) out.poses.push(X.pose(F[i]));
  out.jacobians = [];
  for (i = 0; i < {n_jacobians}; i++) out.jacobians.push(X.jacobian(F[i]));
  var reps = 0, t0 = performance.now(), ms = 0;
  do {{
    for (i = 0; i < F.length; i++) X.pose(F[i]);
    reps++;
    ms = performance.now() - t0;
  }} while (ms < {timing_ms} && reps < 1000);
  out.us_per_pose = 1000 * ms / (reps * F.length);
  out.timed_poses = reps * F.length;
  for (i = 0; i < T.length; i++) {{
    var r = X.inverse(T[i]);
    out.inverse.push({{forces: r.forces, converged: r.converged, iterations: r.iterations}});
  }}
  try {{ X.inverse(["abc", 0, 0, 0, 0, 0]); out.bad_input = ""; }}
  catch (e) {{ out.bad_input = e.message; }}
}} catch (e) {{ out.errors.push(String(e)); }}
var pre = document.createElement("pre");
pre.id = "{result_id}";
pre.textContent = JSON.stringify(out);
document.body.appendChild(pre);
</script></body></html>
"""


def samples(amplitude: float, n_inputs: int) -> tuple[np.ndarray, np.ndarray]:
    """The :data:`N_POSES` force vectors (scrambled Sobol', within ±amplitude) and the
    :data:`N_TARGETS` forces of the inverse's targets (within ±TARGET_SHARE × amplitude)."""
    u = qmc.Sobol(d=n_inputs, scramble=True, seed=SEED).random_base2(N_POSES.bit_length() - 1)
    targets = np.random.default_rng(SEED).uniform(-1, 1, (N_TARGETS, n_inputs))
    return amplitude * (2 * u - 1), TARGET_SHARE * amplitude * targets


def _result(dom: str) -> dict[str, Any] | None:
    match = re.search(rf'<pre id="{RESULT_ID}">(.*?)</pre>', dom, re.DOTALL)
    return json.loads(html.unescape(match.group(1))) if match else None


def page_problems(dom: str) -> list[str]:
    """What the built page's dumped DOM lacks: its script ran, filled the table, timed a pose."""
    problems = []
    if not re.search(r'<html[^>]*class="[^"]*\bmx-on\b', dom):
        problems.append("the page's script did not run (no mx-on class on <html>)")
    cell = re.search(r'<td id="mx-nl-0">([^<]*)</td>', dom)
    if not cell or not cell.group(1).strip():
        problems.append("the pose table was not filled")
    timing = re.search(r'<p id="mx-timing"[^>]*>([^<]*)</p>', dom)
    if not timing or "Measuring" in timing.group(1):
        problems.append("the page did not time a pose")
    return problems


def record_problems(data: dict[str, Any], recorded: dict[str, Any]) -> list[str]:
    """Where the page's literal differs from the recorded model (empty when it carries it)."""
    model = explorer.model_of(data)
    v = recorded["validation"]
    problems = []
    if model["exponents"] != recorded["exponents"]:
        problems.append("the page's exponents differ from the record's")
    coef = np.asarray(model["coef"])
    if coef.shape != np.shape(recorded["coef"]) or not np.array_equal(coef, recorded["coef"]):
        problems.append("the page's coefficients differ from the record's")
    for key in ("worst_pct", "range", "S_T", "heldout_runs"):
        if key not in v:
            problems.append(f"the record's validation has no {key!r}")
        elif data[key] != v[key]:
            problems.append(f"the page's {key} {data[key]} differs from the record's {v[key]}")
    if data["amplitude_n"] != recorded["amplitude_n"]:
        problems.append(f"the page's amplitude {data['amplitude_n']} N differs from the record's")
    return problems


def compare(data: dict[str, Any], result: dict[str, Any], forces: np.ndarray,
            target_forces: np.ndarray) -> tuple[dict[str, Any], list[str]]:  # fmt: skip
    """The measured numbers of the check page's ``result`` and the problems found."""
    if result["errors"]:
        return {}, [f"the check page's script failed: {e}" for e in result["errors"]]
    model = explorer.model_of(data)
    ranges = np.asarray(data["range"])
    js = np.asarray(result["poses"], dtype=float)
    plain = np.array([evaluator.pose(model, f) for f in forces.tolist()])
    with threadpool_limits(limits=1, user_api="blas"):
        fast = predict_array(export.from_dict(model), forces)
        targets = predict_array(export.from_dict(model), target_forces)
    rel_plain = (np.abs(js - plain) / ranges).max(axis=0)
    rel_numpy = (np.abs(js - fast) / ranges).max(axis=0)
    found = np.array([r["forces"] for r in result["inverse"]], dtype=float)
    back = np.array([evaluator.pose(model, f) for f in found.tolist()])
    trip = (np.abs(back - targets) / ranges).max(axis=0)
    force_diff = float(np.abs(found - target_forces).max())
    jac = np.asarray(result["jacobians"], dtype=float)
    steps = FD_STEP * np.eye(forces.shape[1])
    fd = np.array(
        [
            [
                (np.array(evaluator.pose(model, list(f + e))) - evaluator.pose(model, list(f - e)))
                / (2 * FD_STEP)
                for e in steps
            ]
            for f in forces[: len(jac)]
        ]
    ).transpose(0, 2, 1)  # (vectors, outputs, inputs)
    rel_jac = float((np.abs(jac - fd) / ranges[:, None]).max())
    measured = {
        "vectors": len(forces),
        "targets": len(target_forces),
        "max_rel_diff_vs_plain_python": float(rel_plain.max()),
        "max_rel_diff_vs_numpy": float(rel_numpy.max()),
        "max_rel_diff_vs_numpy_per_component": rel_numpy.tolist(),
        "jacobian_max_rel_per_n": rel_jac,
        "round_trip_max_rel": float(trip.max()),
        "round_trip_force_max_abs_n": force_diff,
        "inverse_converged": sum(bool(r["converged"]) for r in result["inverse"]),
        "inverse_max_iterations": max(int(r["iterations"]) for r in result["inverse"]),
        "us_per_pose_js": float(result["us_per_pose"]),
        "timed_poses": int(result["timed_poses"]),
    }
    problems = []
    for name, rel in (("plain-Python", rel_plain), ("NumPy", rel_numpy)):
        if rel.max() > POSE_TOL:
            problems.append(
                f"page poses differ from the {name} evaluation by {rel.max():.3g} of a range "
                f"({data['outputs'][int(rel.argmax())]}), allowed {POSE_TOL:g}"
            )
    if not rel_jac <= JACOBIAN_TOL:
        problems.append(
            f"the page's Jacobian differs from central differences by {rel_jac:.3g} of a range "
            f"per N, allowed {JACOBIAN_TOL:g}"
        )
    if measured["inverse_converged"] != len(target_forces):
        problems.append(
            f"the inverse converged for {measured['inverse_converged']} of "
            f"{len(target_forces)} targets, allowed: all"
        )
    if trip.max() > ROUND_TRIP_TOL:
        problems.append(
            f"round trip misses by {trip.max():.3g} of a range, allowed {ROUND_TRIP_TOL:g}"
        )
    if force_diff > FORCE_TOL:
        problems.append(
            f"the inverse's forces are off by {force_diff:.3g} N, allowed {FORCE_TOL:g}"
        )
    if "must be" not in result.get("bad_input", ""):
        problems.append(f"a target typed as 'abc' gave no clear error: {result.get('bad_input')!r}")
    return measured, problems


def page_bytes(html_root: Path) -> dict[str, int]:
    """Size [bytes] of each of :data:`PAGE_FILES` in the build (0 when absent)."""
    return {
        str(f): (Path(html_root) / f).stat().st_size if (Path(html_root) / f).is_file() else 0
        for f in PAGE_FILES
    }


def check(html_root: Path, records: Path, browser_path: str) -> tuple[dict[str, Any], list[str]]:
    """Measured numbers and problems of the built explorer page under ``html_root``.

    Raises
    ------
    FileNotFoundError
        When the built page, its script or the recorded model is missing (naming the file).
    """
    page, script = Path(html_root) / PAGE, Path(html_root) / SCRIPT
    for path in (page, script, explorer.model_path(records)):
        if not path.is_file():
            raise FileNotFoundError(f"{path}: not found (build the book first)")
    page_text = page.read_text()
    data = explorer.read_script(page_text)
    problems = record_problems(data, json.loads(explorer.model_path(records).read_text()))
    forces, target_forces = samples(data["amplitude_n"], len(data["inputs"]))
    with threadpool_limits(limits=1, user_api="blas"):
        targets = predict_array(export.from_dict(explorer.model_of(data)), target_forces)
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        shutil.copy(script, folder / "explorer.js")
        (folder / "check.html").write_text(
            CHECK_PAGE.format(
                literal=explorer.script_text(data).strip(),
                forces=json.dumps(forces.tolist()),
                targets=json.dumps(targets.tolist()),
                timing_ms=TIMING_MS,
                n_jacobians=N_JACOBIANS,
                result_id=RESULT_ID,
            )
        )
        result = _result(browser.dump_dom(browser_path, folder / "check.html", folder / "p1"))
        problems += [f"built page: {p}" for p in page_problems(
            browser.dump_dom(browser_path, page, folder / "p2")
        )]  # fmt: skip
    if result is None:
        return {}, [*problems, "the check page wrote no result (its script failed or timed out)"]
    measured, found = compare(data, result, forces, target_forces)
    sizes = page_bytes(html_root)
    if sum(sizes.values()) > PAGE_BUDGET:
        found.append(
            f"the page adds {sum(sizes.values())} bytes to the book, allowed {PAGE_BUDGET}"
        )
    return {
        **measured,
        "page_bytes": sizes,
        "page_bytes_total": sum(sizes.values()),
    }, problems + found


def main(argv: list[str] | None = None) -> int:
    """Command line: check the built explorer page, write the measured numbers."""
    parser = argparse.ArgumentParser(prog="python -m mechlib.pipeline.book.explorercheck")
    parser.add_argument("--html", type=Path, required=True)
    parser.add_argument("--records", type=Path, required=True)
    parser.add_argument("--out", type=Path, default=None)
    args = parser.parse_args(argv)
    found = browser.find_browser()
    if found is None:
        print(f"no Chromium found (looked for {', '.join(browser.BROWSERS)})", file=sys.stderr)
        return 3
    try:
        measured, problems = check(args.html, args.records, found)
    except FileNotFoundError as err:
        print(err, file=sys.stderr)
        return 2
    out = args.out or args.html.parent / "explorer-check.json"
    out.write_text(json.dumps({**measured, "problems": problems}, indent=1) + "\n")
    for problem in problems:
        print(problem)
    print(f"explorer check: {len(problems)} problems; measured numbers in {out}")
    return 1 if problems else 0


if __name__ == "__main__":
    raise SystemExit(main())
