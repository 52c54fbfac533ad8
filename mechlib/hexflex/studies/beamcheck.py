"""One flexure against beam theory: a clamped rectangular beam meshed and solved like the HexFlex.

The beam is meshed with the same elements as :class:`mechlib.hexflex.fe.model.HexFlexModel` (one
layer of Q2 hexahedra through the thickness, ``n_width`` elements across) and loaded by a force
spread over its last ``tip_length`` mm; the mean deflection of the loaded end face is compared
with the Timoshenko cantilever (:func:`timoshenko_tip`, κ = 5/6) loaded at the load's centre and
read at the free end.
"""

from __future__ import annotations

import numpy as np

from mechlib.hexflex.fe import mesh as ms
from mechlib.hexflex.frame_solver import SHEAR_FACTOR
from mechlib.params import check_choice, check_float, check_int


def timoshenko_tip(
    length: float,
    width: float,
    thickness: float,
    young: float,
    poisson: float,
    direction: str,
    at: float | None = None,
) -> float:
    """Deflection per unit force [mm/N] at ``at`` (default: the load point) of a cantilever
    loaded at ``length`` from the clamp, bent in-plane (across ``width``) or out-of-plane.

    ``P a² (3 b − a) / (6 E I) + P a / (κ G A)`` with load position ``a`` and measuring point
    ``b >= a`` (the beam beyond the load stays straight).
    """
    direction = check_choice("direction", direction, ("in_plane", "out_of_plane"))
    b = length if at is None else check_float("at [mm]", at, low=length)
    depth, breadth = (width, thickness) if direction == "in_plane" else (thickness, width)
    inertia = breadth * depth**3 / 12.0
    shear = young / (2 * (1 + poisson))
    bend = length**2 * (3 * b - length) / (6 * young * inertia)
    return bend + length / (SHEAR_FACTOR * shear * breadth * depth)


def rectangle_mesh(length: float, width: float, nx: int, ny: int) -> ms.PlanarMesh:
    """Structured quad mesh of ``[0, length] × [-width/2, width/2]``."""
    x, y = np.meshgrid(np.linspace(0, length, nx + 1), np.linspace(-width / 2, width / 2, ny + 1))
    nodes = np.c_[x.ravel(), y.ravel()]
    i, j = np.meshgrid(np.arange(nx), np.arange(ny))
    n0 = (j * (nx + 1) + i).ravel()
    quads = np.c_[n0, n0 + 1, n0 + nx + 2, n0 + nx + 1]
    return ms.PlanarMesh(nodes, quads)


def fe_tip(
    length: float,
    width: float,
    thickness: float,
    young: float,
    poisson: float,
    direction: str,
    n_width: int = 1,
    tip_length: float | None = None,
) -> float:
    """Mean tip deflection per unit force [mm/N] of the Q2 one-layer model of the beam."""
    from mechlib.fe.sfepy_base import QUAD_ORDER, integral, quiet_sfepy

    quiet_sfepy()  # before the first SfePy import prints its notices
    from sfepy.discrete import Equation, Equations, FieldVariable, Material, Problem
    from sfepy.discrete.conditions import Conditions, EssentialBC
    from sfepy.discrete.fem import FEDomain, Field, Mesh
    from sfepy.mechanics.matcoefs import stiffness_from_youngpoisson
    from sfepy.terms import Term

    direction = check_choice("direction", direction, ("in_plane", "out_of_plane"))
    n_width = check_int("n_width", n_width, low=1, high=64)
    for name, v in (("length", length), ("width", width), ("thickness", thickness)):
        check_float(f"{name} [mm]", v, low=0.0, low_open=True)
    h = width / n_width
    nx = max(1, round(length / h))
    tip = h if tip_length is None else tip_length
    planar = rectangle_mesh(length, width, nx, n_width)
    coors, hexes = ms.extrude(planar, thickness)
    cx = planar.nodes[planar.quads].mean(axis=1)[:, 0]
    groups = np.where(cx > length - tip, 2, 1).astype(np.int32)
    mesh = Mesh.from_data(
        "beam",
        coors,
        np.zeros(len(coors), dtype=np.int32),
        [hexes.astype(np.int32)],
        [groups],
        ["3_8"],
    )
    domain = FEDomain("beam", mesh)
    omega = domain.create_region("Omega", "all")
    clamp = domain.create_region("Clamp", f"vertices in (x < {1e-9 * length})", "facet")
    load = domain.create_region("Load", "cells of group 2")
    end = domain.create_region("End", f"vertices in (x > {length * (1 - 1e-9)})", "vertex")
    fld = Field.from_args("fu", np.float64, "vector", omega, approx_order=2)
    u = FieldVariable("u", "unknown", fld)
    v = FieldVariable("v", "test", fld, primary_var_name="u")
    comp = 1 if direction == "in_plane" else 2
    vol = width * thickness * min(tip, length)
    f = np.zeros((3, 1))
    f[comp] = 1.0 / vol
    quad = integral(QUAD_ORDER)
    m = Material("m", D=stiffness_from_youngpoisson(3, young, poisson))
    fm = Material("f", val=f)
    eq = Equation(
        "balance",
        Term.new("dw_lin_elastic(m.D, v, u)", quad, omega, m=m, v=v, u=u)
        - Term.new("dw_volume_lvf(f.val, v)", quad, load, f=fm, v=v),
    )
    pb = Problem("beam", equations=Equations([eq]))
    pb.set_bcs(ebcs=Conditions([EssentialBC("clamp", clamp, {"u.all": 0.0})]))
    from sfepy.base.base import IndexedStruct
    from sfepy.solvers.ls import ScipyDirect
    from sfepy.solvers.nls import Newton

    pb.set_solver(
        Newton({"i_max": 1, "eps_a": 1e-12}, lin_solver=ScipyDirect({}), status=IndexedStruct())
    )
    state = pb.solve(save_results=False)
    disp = state()
    nodes = fld.get_dofs_in_region(end)
    return float(np.mean(np.asarray(disp).reshape(-1, 3)[nodes, comp]))


def compare(
    length: float,
    width: float,
    thickness: float,
    young: float,
    poisson: float,
    n_widths: tuple[int, ...] = (1, 2, 4),
) -> list[dict[str, object]]:
    """FE against Timoshenko for both bending directions and several elements across.

    The load is spread over the last ``width`` mm and the deflection read at the free end.

    Returns
    -------
    list of dict
        ``direction``, ``n_width``, ``fe_um_per_n``, ``theory_um_per_n``, ``ratio``.
    """
    rows = []
    for n_width in n_widths:
        for direction in ("in_plane", "out_of_plane"):
            fe = fe_tip(length, width, thickness, young, poisson, direction, n_width, width)
            th = timoshenko_tip(
                length - width / 2, width, thickness, young, poisson, direction, at=length
            )
            rows.append(
                {
                    "direction": direction,
                    "n_width": n_width,
                    "fe_um_per_n": 1e3 * fe,
                    "theory_um_per_n": 1e3 * th,
                    "ratio": fe / th,
                }
            )
    return rows
