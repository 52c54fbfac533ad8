"""Observability indices and optimal posture selection (thesis Eq 18; Sun & Hollerbach 2008).

Mechanism-independent: used by every instance of the core (:mod:`mechlib.fivebar.mechanism`,
:mod:`mechlib.mechanisms`).

A candidate posture contributes a block ``G_j`` (p × n) of rows to the identification matrix:
one row per leg reading (p = 1 for one leg, p = 2 for the traditional 12-parameter matrix,
whose block is ``diag(C1_j, C2_j)``). Selection maximises ``det(CᵀC)`` — equivalently the
observability index O1 of Eq 18 for a fixed number of parameters — by the active calibration
algorithm: greedy additions with the rank-p determinant update
``det(M + GᵀG) = det(M) · det(I + G M⁻¹ Gᵀ)`` and a Woodbury update of ``M⁻¹``, followed by
exchange passes (remove one, add the best) until no exchange increases the determinant.
"""

from __future__ import annotations

import numpy as np

from mechlib.params import check_int

START_REGULARISATION = 1e-8
"""Greedy selection starts from M = ε·mean(diag GᵀG)·I so that M⁻¹ exists (Sun & Hollerbach)."""
IMPROVEMENT_TOL = 1e-12
"""An exchange must raise log det by more than this to be made (stops cycling on ties)."""


def observability_o1(c: object) -> float:
    """Thesis Eq 18: ``O1 = (s1 s2 … sn)^(1/n) / n`` over the singular values of ``C``."""
    s = np.linalg.svd(np.asarray(c, dtype=float), compute_uv=False)
    n = s.size
    return float(np.exp(np.mean(np.log(s))) / n)


def observability_borm_menq(c: object) -> float:
    """Borm & Menq's O1: ``(s1 … sn)^(1/n) / sqrt(m)``, ``m`` the number of measurements."""
    c = np.asarray(c, dtype=float)
    s = np.linalg.svd(c, compute_uv=False)
    return float(np.exp(np.mean(np.log(s))) / np.sqrt(c.shape[0]))


def observability_o3(c: object) -> float:
    """O3, the inverse condition number ``s_min / s_max`` of ``C`` (columns scaled to unit norm,
    so that parameters of different units compare)."""
    c = np.asarray(c, dtype=float)
    scale = np.linalg.norm(c, axis=0)
    s = np.linalg.svd(c / np.where(scale > 0, scale, 1.0), compute_uv=False)
    return float(s[-1] / s[0])


def d_optimality(c: object) -> float:
    """D-optimality ``det(CᵀC)^(1/n)``, from the singular values (no overflow)."""
    s = np.linalg.svd(np.asarray(c, dtype=float), compute_uv=False)
    return float(np.exp(2 * np.mean(np.log(s))))


def _blocks(candidates: object) -> np.ndarray:
    g = np.asarray(candidates, dtype=float)
    if g.ndim == 2:
        g = g[:, None, :]
    if g.ndim != 3 or not np.all(np.isfinite(g)):
        raise ValueError(f"candidates must be finite blocks of shape (N, p, n), got {g.shape}")
    return g


def _check_count(n_select: int, g: np.ndarray) -> int:
    n_select = check_int("n_select", n_select, low=1)
    if n_select > g.shape[0]:
        raise ValueError(
            f"n_select must be <= the number of candidates ({g.shape[0]}), got {n_select}"
        )
    return n_select


def _start(g: np.ndarray) -> np.ndarray:
    scale = np.mean(np.einsum("jpn,jpn->n", g, g)) / g.shape[0]
    return np.eye(g.shape[2]) * START_REGULARISATION * scale


def _gains(g: np.ndarray, m_inv: np.ndarray, sign: float = 1.0) -> np.ndarray:
    """log det(I ± G_j M⁻¹ G_jᵀ) for every candidate block (vectorised)."""
    s = np.einsum("jpn,nm,jqm->jpq", g, m_inv, g)
    eye = np.eye(g.shape[1])
    sgn, logdet = np.linalg.slogdet(eye + sign * s)
    return np.where(sgn > 0, logdet, -np.inf)


def _woodbury(m_inv: np.ndarray, gj: np.ndarray, sign: float) -> np.ndarray:
    """(M ± GᵀG)⁻¹ from M⁻¹."""
    mg = m_inv @ gj.T
    inner = np.eye(gj.shape[0]) + sign * gj @ mg
    return m_inv - sign * mg @ np.linalg.solve(inner, mg.T)


def select_active(candidates: object, n_select: int, max_passes: int = 20) -> np.ndarray:
    """Indices of ``n_select`` candidate postures maximising det(CᵀC) (active calibration).

    Parameters
    ----------
    candidates : array_like, shape (N, p, n) or (N, n)
        Identification-matrix block of every candidate posture.
    n_select : int
        Postures to select, at most N.
    max_passes : int
        Cap on exchange passes.

    Returns
    -------
    numpy.ndarray of int, shape (n_select,)
    """
    g = _blocks(candidates)
    n_select = _check_count(n_select, g)
    m_inv = np.linalg.inv(_start(g))
    chosen: list[int] = []
    free = np.ones(g.shape[0], dtype=bool)
    for _ in range(n_select):
        gain = np.where(free, _gains(g, m_inv), -np.inf)
        j = int(np.argmax(gain))
        chosen.append(j)
        free[j] = False
        m_inv = _woodbury(m_inv, g[j], +1.0)
    for _ in range(check_int("max_passes", max_passes, low=0)):
        improved = False
        for pos in range(n_select):
            s = chosen[pos]
            loss = _gains(g[s : s + 1], m_inv, -1.0)[0]
            m_minus = _woodbury(m_inv, g[s], -1.0)
            gain = np.where(free, _gains(g, m_minus), -np.inf)
            j = int(np.argmax(gain))
            if j != s and gain[j] + loss > IMPROVEMENT_TOL:
                chosen[pos] = j
                free[s], free[j] = True, False
                m_inv = _woodbury(m_minus, g[j], +1.0)
                improved = True
        if not improved:
            break
    return np.array(chosen)


def _logdet_svd(g: np.ndarray, idx: list[int], m0: np.ndarray) -> float:
    rows = [np.linalg.cholesky(m0).T] + [g[i] for i in idx]
    s = np.linalg.svd(np.vstack(rows), compute_uv=False)
    return float(2 * np.sum(np.log(s)))


def select_reference_svd(candidates: object, n_select: int, max_passes: int = 20) -> np.ndarray:
    """The same greedy + exchange search, scoring each candidate by an SVD of the full matrix.

    The plain implementation that :func:`select_active` is checked and benchmarked against.
    """
    g = _blocks(candidates)
    n_select = _check_count(n_select, g)
    m0 = _start(g)
    chosen: list[int] = []
    for _ in range(n_select):
        scores = [
            (-np.inf if j in chosen else _logdet_svd(g, [*chosen, j], m0)) for j in range(len(g))
        ]
        chosen.append(int(np.argmax(scores)))
    for _ in range(check_int("max_passes", max_passes, low=0)):
        improved = False
        for pos in range(n_select):
            base = _logdet_svd(g, chosen, m0)
            rest = chosen[:pos] + chosen[pos + 1 :]
            scores = [
                (-np.inf if j in rest or j == chosen[pos] else _logdet_svd(g, [*rest, j], m0))
                for j in range(len(g))
            ]
            j = int(np.argmax(scores))
            if scores[j] - base > IMPROVEMENT_TOL:
                chosen[pos] = j
                improved = True
        if not improved:
            break
    return np.array(chosen)


def _leg_gains(legs: list[np.ndarray], m_invs: list[np.ndarray], sign: float = 1.0) -> np.ndarray:
    """Σκ log(1 ± cκj Mκ⁻¹ cκjᵀ) for every candidate j (block-diagonal total matrix)."""
    total = np.zeros(legs[0].shape[0])
    for c, m_inv in zip(legs, m_invs, strict=True):
        arg = 1.0 + sign * np.einsum("jn,nm,jm->j", c, m_inv, c)
        total += np.where(arg > 0, np.log(np.where(arg > 0, arg, 1.0)), -np.inf)
    return total


def select_shared(legs: object, n_select: int, max_passes: int = 20) -> np.ndarray:
    """:func:`select_active` on the traditional (block-diagonal) total matrix, leg by leg.

    Leg κ's reading depends only on φκ, so a shared posture adds the block ``diag(c1j, …, cnj)``
    and ``det(CᵀC) = Πκ det(CκᵀCκ)``: the determinant update is a sum of rank-one updates of
    each leg's matrix. The selection equals :func:`select_active` on the stacked blocks (tested)
    at a cost linear, not cubic, in the number of legs.

    Parameters
    ----------
    legs : sequence of array_like, each shape (N, nκ)
        Identification matrix of every leg over the same N candidate postures.
    n_select : int
        Postures to select, at most N.
    max_passes : int
        Cap on exchange passes.

    Returns
    -------
    numpy.ndarray of int, shape (n_select,)
    """
    cs = [np.asarray(c, dtype=float) for c in legs]  # type: ignore[attr-defined]
    if not cs or any(c.ndim != 2 or c.shape[0] != cs[0].shape[0] for c in cs):
        raise ValueError(
            f"legs must be (N, nκ) matrices over the same N candidates, got {[c.shape for c in cs]}"
        )
    n_select = _check_count(n_select, cs[0][:, None, :])
    n_total = sum(c.shape[1] for c in cs)
    scale = sum(float(np.sum(c**2)) for c in cs) / n_total / cs[0].shape[0]
    m_invs = [np.eye(c.shape[1]) / (START_REGULARISATION * scale) for c in cs]
    chosen: list[int] = []
    free = np.ones(cs[0].shape[0], dtype=bool)

    def update(m: list[np.ndarray], j: int, sign: float) -> list[np.ndarray]:
        return [_woodbury(mi, c[j : j + 1], sign) for mi, c in zip(m, cs, strict=True)]

    for _ in range(n_select):
        j = int(np.argmax(np.where(free, _leg_gains(cs, m_invs), -np.inf)))
        chosen.append(j)
        free[j] = False
        m_invs = update(m_invs, j, +1.0)
    for _ in range(check_int("max_passes", max_passes, low=0)):
        improved = False
        for pos in range(n_select):
            s = chosen[pos]
            loss = _leg_gains([c[s : s + 1] for c in cs], m_invs, -1.0)[0]
            m_minus = update(m_invs, s, -1.0)
            gain = np.where(free, _leg_gains(cs, m_minus), -np.inf)
            j = int(np.argmax(gain))
            if j != s and gain[j] + loss > IMPROVEMENT_TOL:
                chosen[pos] = j
                free[s], free[j] = True, False
                m_invs = update(m_minus, j, +1.0)
                improved = True
        if not improved:
            break
    return np.array(chosen)


#: Observability indices a selection can maximise (:func:`select_greedy`), by name.
INDICES = {
    "O1 (thesis, Eq 18)": observability_o1,
    "O1 (Borm & Menq)": observability_borm_menq,
    "O3 (inverse condition number)": observability_o3,
    "D-optimality": d_optimality,
}


def _stacked_index(stack: np.ndarray, index: str) -> np.ndarray:
    """:data:`INDICES` ``index`` of every matrix of ``stack`` (k, m, n) at once."""
    if index.startswith("O3"):
        norm = np.linalg.norm(stack, axis=1, keepdims=True)
        s = np.linalg.svd(stack / np.where(norm > 0, norm, 1.0), compute_uv=False)
        return s[:, -1] / s[:, 0]
    s = np.linalg.svd(stack, compute_uv=False)
    with np.errstate(divide="ignore"):
        geo = np.exp(np.mean(np.log(s), axis=1))
    m, n = stack.shape[1:]
    return {"O1 (thesis, Eq 18)": geo / n, "O1 (Borm & Menq)": geo / np.sqrt(m)}.get(index, geo**2)


def select_greedy(candidates: object, n_select: int, index: str) -> np.ndarray:
    """Greedy selection of ``n_select`` rows of ``candidates`` (N, n) maximising ``index`` (a key
    of :data:`INDICES`), each step scoring every free candidate by the index of the set with it
    (one batched SVD a step).

    The first ``n`` picks maximise D-optimality (an index of fewer rows than columns is not
    defined). Slower than :func:`select_active`, but valid for indices without a determinant
    update (O3); for a fixed set size the three O1/D-optimality indices are monotone functions of
    ``det(CᵀC)`` and select alike.
    """
    c = np.asarray(candidates, dtype=float)
    if index not in INDICES:
        raise ValueError(f"index must be one of {sorted(INDICES)}, got {index!r}")
    n_select = _check_count(n_select, c[:, None, :])
    chosen = list(select_active(c, min(n_select, c.shape[1]), max_passes=0))
    free = np.ones(len(c), dtype=bool)
    free[chosen] = False
    while len(chosen) < n_select:
        rest = np.flatnonzero(free)
        stack = np.concatenate(
            [np.broadcast_to(c[chosen], (len(rest), len(chosen), c.shape[1])), c[rest, None, :]],
            axis=1,
        )
        j = int(rest[int(np.argmax(_stacked_index(stack, index)))])
        chosen.append(j)
        free[j] = False
    return np.array(chosen)
