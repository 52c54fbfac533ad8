"""A structured box of 8-node hexahedra, optionally graded towards one end (the cantilever
benchmark's mesh, :mod:`mechlib.hexflex.studies.cantilever`). Units: mm.
"""

from __future__ import annotations

import math

import numpy as np

from mechlib.params import check_float, check_int


def box_hexahedra(
    size: tuple[float, float, float], cells: tuple[int, int, int], clamp_size: float | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """A structured grid of 8-node hexahedra on [0, a] × [−b/2, b/2] × [−c/2, c/2] [mm].

    ``size`` = (a, b, c) > 0, ``cells`` = (nx, ny, nz) ≥ 1 elements along each side. With
    ``clamp_size`` [mm] the first of the nx equal elements along x is halved towards x = 0 until
    its piece there is at most that long. Returns the node coordinates (n_nodes, 3) and the
    hexahedra (n_el, 8) in SfePy's ``3_8`` order (face z⁻ counter-clockwise seen from +z, then
    face z⁺).
    """
    a, b, c = (
        check_float(f"size[{i}] [mm]", s, low=0.0, low_open=True) for i, s in enumerate(size)
    )
    nx, ny, nz = (check_int(f"cells[{i}]", n, low=1) for i, n in enumerate(cells))
    xs = np.linspace(0.0, a, nx + 1)
    if clamp_size is not None:
        first = a / nx
        clamp_size = check_float("clamp_size [mm]", clamp_size, low=0.0, high=first, low_open=True)
        halvings = math.ceil(math.log2(first / clamp_size) - 1e-12)
        xs = np.concatenate([[0.0], first / 2.0 ** np.arange(halvings, 0, -1), xs[1:]])
        nx = len(xs) - 1
    axes = (xs, np.linspace(-b / 2, b / 2, ny + 1), np.linspace(-c / 2, c / 2, nz + 1))
    grid = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
    index = np.arange(len(grid)).reshape(nx + 1, ny + 1, nz + 1)
    i, j, k = (g.ravel() for g in np.meshgrid(np.arange(nx), np.arange(ny), np.arange(nz),
                                             indexing="ij"))  # fmt: skip
    corners = [(0, 0), (1, 0), (1, 1), (0, 1)]  # (Δi, Δj) counter-clockwise from +z
    hexes = [index[i + di, j + dj, k + dk] for dk in (0, 1) for di, dj in corners]
    return np.ascontiguousarray(grid), np.stack(hexes, axis=1).astype(np.int32)
