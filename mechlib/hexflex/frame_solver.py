"""A small 3-D frame solver: 2-node beams, 6 DOF per node, rectangular sections.

Euler–Bernoulli or Timoshenko beams (:data:`SHEAR_FACTOR`), Saint-Venant torsion with Roark's
constant of a rectangle, rigid-body constraints by a transformation matrix (a *master* node
carries its *slaves*), clamped nodes; :func:`solve_frame` gives the master and free nodes'
displacements and rotations for load cases. Nothing here knows the HexFlex:
:mod:`mechlib.hexflex.frame` builds the HexFlex as such a frame. Units are the caller's (the
HexFlex uses mm, N, MPa).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg as sl

from mechlib.hexflex.geometry import MAX_POISSON
from mechlib.params import check_float

#: Timoshenko shear correction factor of a rectangle (Cowper's ν-free value, 5/6).
SHEAR_FACTOR = 5.0 / 6.0
#: Roark's torsion constant of a rectangle: J = a b³ [1/3 − 0.21 (b/a)(1 − b⁴/(12 a⁴))].
ROARK_THIRD, ROARK_C1, ROARK_C2 = 1.0 / 3.0, 0.21, 1.0 / 12.0
#: An element is "along z" (no local y axis) if |z × axis| ≤ PARALLEL_TOL · length.
PARALLEL_TOL = 1e-12
NDOF, _UP = 6, np.array([0.0, 0.0, 1.0])  # DOF per node; the planar frames' normal (local z)
_PAIR = np.array([[1.0, -1.0], [-1.0, 1.0]])
_AXIAL, _TWIST = np.ix_([0, 6], [0, 6]), np.ix_([3, 9], [3, 9])
_BEND_Y, _BEND_Z = np.ix_([1, 5, 7, 11], [1, 5, 7, 11]), np.ix_([2, 4, 8, 10], [2, 4, 8, 10])


@dataclass(frozen=True)
class Frame:
    """A frame of 2-node beams with rectangular sections.

    Attributes
    ----------
    nodes : ndarray (n, 3)
        Node coordinates [mm].
    elements : ndarray (m, 2) of int
        Node indices of each beam.
    widths, depths : ndarray (m,)
        Section sides [mm]: ``width`` along the local y axis (``up × axis``, in the plane for a
        planar frame), ``depth`` along the local z axis (``up`` for a planar frame).
    clamped : tuple of int
        Nodes with all six DOF fixed.
    rigid : mapping int -> tuple of int
        Rigid bodies: master node → slave nodes, ``u_s = u_m + θ_m × (x_s − x_m)``, ``θ_s = θ_m``.
    """

    nodes: np.ndarray
    elements: np.ndarray
    widths: np.ndarray
    depths: np.ndarray
    clamped: tuple[int, ...] = ()
    rigid: Mapping[int, tuple[int, ...]] = field(default_factory=dict)


def torsion_constant(width: float, depth: float) -> float:
    """Saint-Venant torsion constant [mm⁴] of a ``width × depth`` rectangle.

    Roark's Formulas for Stress and Strain (7th ed., Table 10.7, case 4), written with the full
    long side ``a`` and short side ``b``: ``J = a b³ [1/3 − 0.21 (b/a)(1 − b⁴/(12 a⁴))]``.
    """
    a, b = max(width, depth), min(width, depth)
    return a * b**3 * (ROARK_THIRD - ROARK_C1 * (b / a) * (1 - ROARK_C2 * (b / a) ** 4))


def element_stiffness(
    p0: np.ndarray,
    p1: np.ndarray,
    width: float,
    depth: float,
    young: float,
    poisson: float,
    shear: bool = True,
) -> np.ndarray:
    """Global 12 × 12 stiffness of a straight beam (Przemieniecki's exact Timoshenko element).

    DOF order ``(u, v, w, θx, θy, θz)`` of node 0 then node 1. With ``shear=False`` it is the
    Euler–Bernoulli element. Both are exact for loads applied at the nodes.
    """
    axis = np.asarray(p1, float) - np.asarray(p0, float)
    length = float(np.linalg.norm(axis))
    side = np.cross(_UP, axis)
    if length <= 0 or np.linalg.norm(side) <= PARALLEL_TOL * length:
        raise ValueError(f"element from {p0} to {p1} must have length > 0 and not be along z")
    e1, e2 = axis / length, side / np.linalg.norm(side)
    rot = np.array([e1, e2, np.cross(e1, e2)])
    shear_mod, area, L = young / (2 * (1 + poisson)), width * depth, length
    k = np.zeros((12, 12))
    k[_AXIAL] = young * area / L * _PAIR
    k[_TWIST] = shear_mod * torsion_constant(width, depth) / L * _PAIR
    # (v, θz): bending about local z, I = depth·width³/12; (w, θy): θy = −w' flips the signs
    for idx, inertia, signs in (
        (_BEND_Y, depth * width**3 / 12, np.array([1.0, 1, 1, 1])),
        (_BEND_Z, width * depth**3 / 12, np.array([1.0, -1, 1, -1])),
    ):
        phi = 12 * young * inertia / (SHEAR_FACTOR * shear_mod * area * L**2) if shear else 0.0
        m = np.array([
            [12, 6 * L, -12, 6 * L],
            [6 * L, (4 + phi) * L**2, -6 * L, (2 - phi) * L**2],
            [-12, -6 * L, 12, -6 * L],
            [6 * L, (2 - phi) * L**2, -6 * L, (4 + phi) * L**2],
        ])  # fmt: skip
        k[idx] = young * inertia / ((1 + phi) * L**3) * np.outer(signs, signs) * m
    big = np.kron(np.eye(4), rot)
    return big.T @ k @ big


def node_reduction(frame: Frame) -> tuple[np.ndarray, np.ndarray, int]:
    """How each node's 6 DOF follow the free unknowns: ``u_node = block @ u_free[col : col + 6]``.

    Returns ``col`` (n,) (−1 for a clamped node), ``block`` (n, 6, 6) (identity, or for a slave
    the rigid map ``[[I, −[d]×], [0, I]]`` of its master's DOF, ``d = x_s − x_m``) and the number
    of free unknowns. This is the transformation ``u_full = T u_free`` stored node by node.
    """
    n = len(frame.nodes)
    clamped = set(frame.clamped)
    slave_of = {s: m for m, slaves in frame.rigid.items() for s in slaves}
    for m in frame.rigid:
        if m in slave_of or m in clamped:
            raise ValueError(f"rigid master node {m} must be neither a slave nor clamped")
    if clamped & set(slave_of):
        raise ValueError(f"nodes {sorted(clamped & set(slave_of))} cannot be clamped and slaves")
    own = [i for i in range(n) if i not in clamped and i not in slave_of]
    col = np.full(n, -1)
    col[own] = NDOF * np.arange(len(own))
    block = np.tile(np.eye(NDOF), (n, 1, 1))
    for s, m in slave_of.items():  # u_s = u_m + θ_m × d = u_m − [d]× θ_m
        d = frame.nodes[s] - frame.nodes[m]
        block[s, :3, 3:] = -np.array([[0, -d[2], d[1]], [d[2], 0, -d[0]], [-d[1], d[0], 0]])
        col[s] = col[m]
    return col, block, NDOF * len(own)


def solve_frame(
    frame: Frame, young: float, poisson: float, loads: np.ndarray, shear: bool = True
) -> np.ndarray:
    """Nodal displacements and rotations of a linear frame.

    Parameters
    ----------
    frame : Frame
    young, poisson : float
        Young's modulus [MPa], > 0, and Poisson's ratio, in (−1, 0.5).
    loads : ndarray (..., n, 6)
        Nodal forces [N] and moments [N·mm]; leading axes are load cases.
    shear : bool
        Timoshenko shear deformation (κ = 5/6) if true, Euler–Bernoulli if false.

    Returns
    -------
    ndarray, the shape of ``loads``
        ``(u, v, w, θx, θy, θz)`` per node [mm, rad].

    Raises
    ------
    ValueError
        For bad material constants or loads, or a frame that is a mechanism.
    """
    young, poisson = check_material(young, poisson)
    f = np.asarray(loads, dtype=float)
    n = len(frame.nodes)
    if f.shape[-2:] != (n, NDOF) or not np.all(np.isfinite(f)):
        raise ValueError(f"loads must be finite with shape (..., {n}, 6), got {f.shape}")
    col, block, m = node_reduction(frame)
    k = np.zeros((m, m))
    for (a, b), w, d in zip(frame.elements, frame.widths, frame.depths, strict=True):
        ke = element_stiffness(frame.nodes[a], frame.nodes[b], w, d, young, poisson, shear)
        for i, p in ((0, a), (1, b)):
            for j, q in ((0, a), (1, b)):
                if col[p] >= 0 and col[q] >= 0:
                    kij = ke[NDOF * i : NDOF * i + NDOF, NDOF * j : NDOF * j + NDOF]
                    k[col[p] : col[p] + NDOF, col[q] : col[q] + NDOF] += block[p].T @ kij @ block[q]
    cases = f.reshape(-1, n, NDOF)
    rhs = np.zeros((m, len(cases)))
    for p in np.flatnonzero(col >= 0):
        rhs[col[p] : col[p] + NDOF] += block[p].T @ cases[:, p, :].T
    try:
        u = sl.solve(k, rhs, assume_a="pos")
    except np.linalg.LinAlgError as err:
        raise ValueError("the frame is a mechanism (singular reduced stiffness)") from err
    out = np.zeros_like(cases)
    for p in np.flatnonzero(col >= 0):
        out[:, p, :] = (block[p] @ u[col[p] : col[p] + NDOF]).T
    return out.reshape(f.shape)


def check_material(young: float, poisson: float) -> tuple[float, float]:
    """Young's modulus [MPa] > 0 and Poisson's ratio in (−1, ``MAX_POISSON``], checked."""
    young = check_float("young [MPa]", young, low=0.0, low_open=True)
    poisson = check_float("poisson", poisson, low=-1.0, high=MAX_POISSON, low_open=True)
    return young, poisson
