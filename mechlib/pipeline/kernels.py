"""The BLAS kernel ``make test`` executes the notebooks with: one that is neither this machine's
own nor the one the references were recorded with.

OpenBLAS picks its kernels at run time for the processor it finds (``Haswell`` on a Zen-1 EPYC,
``SkylakeX`` on an AVX-512 one), and each kernel rounds differently. A record that hinges on
round-off then passes on the machine that recorded it and fails on another. ``make test`` runs
every notebook twice under :func:`other_kernel` (``OPENBLAS_CORETYPE``): the first run's records
are compared with ``tests/references`` at their tolerances — which so hold across kernels — and the
second run's with the first's byte for byte — which checks determinism on one kernel. ``make
references`` refuses records not computed with the machine's own kernel (:func:`check_own_kernel`),
so the two never coincide by accident.

``python -m mechlib.pipeline.kernels other`` prints the kernel's name; ``own`` prints this
process's; ``spread`` lists the recorded numbers whose spread across the records of several
kernels exceeds a tenth of their tolerance (:func:`spread`); ``forget`` removes the executed
notebooks computed with another kernel (:func:`forget_other_kernels`).
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

from mechlib.blasinfo import openblas_kernel

#: kernels every x86-64 machine of ours can run, in the order they are chosen (the references'
#: tolerances were measured against the first two, and against Nehalem, which a machine whose
#: own kernel is Sandybridge runs the notebooks with when the references are Haswell's)
CANDIDATES = ("Sandybridge", "Haswell", "Nehalem")


def reference_kernels(references: Path) -> set[str]:
    """The kernels the reference files in ``references`` were recorded with (their ``blas``)."""
    found = set()
    for path in sorted(Path(references).glob("*.json")):
        kernel = json.loads(path.read_text()).get("blas")
        if kernel:
            found.add(str(kernel))
    return found


def other_kernel(own: str, recorded: set[str] | frozenset[str] = frozenset()) -> str:
    """The first of :data:`CANDIDATES` that is neither ``own`` nor in ``recorded``.

    Raises
    ------
    ValueError
        If every candidate is excluded (three kernels would have to coincide).
    """
    for kernel in CANDIDATES:
        if kernel.lower() != own.lower() and kernel.lower() not in {r.lower() for r in recorded}:
            return kernel
    raise ValueError(
        f"no kernel of {CANDIDATES} differs from the machine's own ({own}) and the references' "
        f"({sorted(recorded)})"
    )


def check_own_kernel(records: Path, own: str) -> list[str]:
    """One line per record in ``records`` computed with another kernel than ``own``."""
    problems = []
    for path in sorted(Path(records).glob("*.json")):
        kernel = json.loads(path.read_text()).get("blas")
        if kernel != own:
            problems.append(
                f"{path.stem}: computed with the {kernel} kernel, not this machine's own ({own})"
            )
    return problems


def spread(runs: dict[str, Path], references: Path, share: float = 0.1) -> list[str]:
    """Every recorded number whose spread across runs exceeds ``share`` of its tolerance.

    Parameters
    ----------
    runs : dict
        A records folder per kernel name (the same notebooks run with each kernel).
    references : Path
        ``tests/references``: the tolerances (atol + rtol · |reference|), element by element.
    share : float
        Share of the tolerance a spread may take (a tenth: a record then holds on another
        machine with ten times the round-off seen here).

    Returns
    -------
    list of str
        ``notebook key: spread s = x of its tolerance t (values …)``, largest share first.
    """
    import numpy as np

    rows = []
    for ref_path in sorted(Path(references).glob("*.json")):
        ref = json.loads(ref_path.read_text())["values"]
        got = {k: json.loads((Path(d) / ref_path.name).read_text())["values"]
               for k, d in runs.items() if (Path(d) / ref_path.name).exists()}  # fmt: skip
        for key, entry in ref.items():
            try:
                vals = np.array([g[key]["value"] for g in got.values()], dtype=float)
                base = np.asarray(entry["value"], dtype=float)
            except (KeyError, TypeError, ValueError):
                continue
            if vals.shape[1:] != base.shape or not len(vals):
                continue
            width = np.ptp(vals, axis=0)
            tol = entry["atol"] + entry["rtol"] * np.abs(base)
            ratio = np.where(
                tol > 0, width / np.where(tol > 0, tol, 1.0), np.where(width > 0, np.inf, 0.0)
            )
            worst = float(np.max(ratio)) if ratio.size else 0.0
            if worst > share:
                i = tuple(int(j) for j in np.unravel_index(int(np.argmax(ratio)), ratio.shape))
                rows.append((worst, f"{ref_path.stem} {key}{list(i) if i else ''}: spread "
                             f"{float(np.asarray(width)[i]):.3g} = {worst:.3g} of its tolerance "
                             f"{float(np.asarray(tol)[i]):.3g} (values "
                             f"{', '.join(f'{float(v[i]):.7g}' for v in vals)})"))  # fmt: skip
    return [text for _, text in sorted(rows, key=lambda r: -r[0])]


def forget_other_kernels(records: Path, executed: Path, kernel: str) -> list[str]:
    """Remove each executed notebook of ``executed`` whose record in ``records`` was computed with
    another kernel than ``kernel`` (so ``make`` executes it again); return their names.

    ``make test`` calls it before its first run: a notebook ``make book`` executed with the
    machine's own kernel is not taken for one executed with the test's.
    """
    gone = []
    for path in sorted(Path(records).glob("*.json")):
        nb = Path(executed) / f"{path.stem}.ipynb"
        if nb.exists() and json.loads(path.read_text()).get("blas") != kernel:
            nb.unlink()
            gone.append(path.stem)
    return gone


def main(argv: list[str] | None = None) -> int:
    """``own`` or ``other [references folder]``: print a kernel's name."""
    args = sys.argv[1:] if argv is None else argv
    if args and args[0] == "forget":  # forget <records> <executed> <kernel>
        gone = forget_other_kernels(Path(args[1]), Path(args[2]), args[3])
        if gone:
            print(f"executed again with the {args[3]} kernel: {', '.join(gone)}")
        return 0
    if args and args[0] == "spread":  # spread <references> <kernel>=<records folder> ...
        runs = dict(a.split("=", 1) for a in args[2:])
        for line in spread({k: Path(v) for k, v in runs.items()}, Path(args[1])):
            print(line)
        return 0
    if not args or args[0] not in ("own", "other"):
        print("usage: python -m mechlib.pipeline.kernels own | other [references folder] | "
              "spread <references> <kernel>=<records folder> ... | "
              "forget <records> <executed> <kernel>")  # fmt: skip
        return 2
    import numpy  # noqa: F401  (loads OpenBLAS, so threadpoolctl finds it)
    import scipy.linalg  # noqa: F401

    own = openblas_kernel()
    if args[0] == "own":
        print(own)
    else:
        recorded = reference_kernels(Path(args[1])) if len(args) > 1 else set()
        print(other_kernel(own, recorded))
    return 0


if __name__ == "__main__":
    sys.exit(main())
