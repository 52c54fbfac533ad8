"""Anderson mixing: acceleration of a fixed-point iteration by its last few differences.

The non-linear solver (:mod:`.nonlinear`) keeps one factorised tangent over several corrections
(a chord iteration); mixing each correction with the last ones (Anderson 1965; Walker & Ni 2011,
SIAM J. Numer. Anal. 49(4) 1715–1735) makes that iteration converge like GMRES on the secant
information instead of linearly.
"""

from __future__ import annotations

import numpy as np

from mechlib.blas import one_thread


class Anderson:
    """Anderson mixing of the corrections of one factorised tangent (depth 0: plain steps).

    Parameters
    ----------
    depth : int
        How many of the last iterate and correction differences the mixing fits (0: none).

    For iterates x_k with corrections f_k (``-K⁻¹ r(x_k)``) the step is
    ``f_k − (ΔX + ΔF) γ`` with γ the least-squares fit of f_k by the last ``depth`` differences
    ΔF of corrections (ΔX of iterates) — GMRES-like acceleration of the chord iteration.
    """

    def __init__(self, depth: int) -> None:
        self.depth = depth
        self.reset()

    def reset(self) -> None:
        self._x: np.ndarray | None = None
        self._f: np.ndarray | None = None
        self._dx: list[np.ndarray] = []
        self._df: list[np.ndarray] = []

    def step(self, x: np.ndarray, f: np.ndarray) -> np.ndarray:
        """The step from ``x`` given its correction ``f``."""
        if self.depth == 0:
            return f
        if self._x is not None:
            self._dx.append(x - self._x)
            self._df.append(f - self._f)
            del self._dx[: -self.depth], self._df[: -self.depth]
        self._x, self._f = x, f
        if not self._df:
            return f
        df = np.stack(self._df, axis=1)
        with one_thread():  # bit-identical in any process
            gamma = np.linalg.lstsq(df, f, rcond=None)[0]
            return f - (np.stack(self._dx, axis=1) + df) @ gamma
