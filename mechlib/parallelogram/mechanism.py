"""The parallelogram flexure of the benchmark as a :class:`~mechlib.compliant.layout.Layout`.

Axes as in :mod:`.published`, shifted so that the origin is the benchmark's load and probe point
(the middle of the stage's face at the beam tips): the beams run from the clamp at x = -L to
x = 0 at y = ±W/2, the stage block spans x ∈ [0, 50 mm] across both beams, and the extrusion is
the beams' height H along z. The three load ports act on the stage's face between the beam tips
(x = 0, |y| ≤ W/2 - T/2, the face that holds the benchmark's load point): F_x and F_y [N] as
uniform tractions of that resultant, M_z [N·mm] as a normal traction varying linearly across
the face (the benchmark puts F_x and F_y on one vertex of that face and M_z on two 10 mm strips
beside its middle; we take it that on a stage this stiff only the resultants matter). The
stage is of the beams' steel unless ``stage_young`` gives it its own modulus (a material region:
the benchmark's is 5000 GPa).
"""

from __future__ import annotations

import math

from mechlib.compliant.layout import Layout, Load
from mechlib.parallelogram import published as pub

#: Largest |A_x|, |A_y| and |B| a model accepts (normalised): the elastica's bounds.
MAX_A, MAX_B = 40.0, 10.0
LOAD_NAMES: tuple[str, ...] = ("F_x", "F_y", "M_z")


def layout(stage_young: float | None = None, stage_size: float | None = None) -> Layout:
    """The benchmark's parallelogram (:mod:`.published` dimensions and steel).

    Parameters
    ----------
    stage_young : float, optional
        Young's modulus of the stage [MPa] (a material region); default the beams' steel.
    stage_size : float, optional
        Element size in the stage [mm]; default the model's mesh size.
    """
    length, t, w, s = pub.LENGTH_MM, pub.THICKNESS_MM, pub.SEPARATION_MM, pub.STAGE_LENGTH_MM
    inner, outer = w / 2 - t / 2, w / 2 + t / 2

    def rect(x0: float, x1: float, y0: float, y1: float) -> tuple[tuple[float, float], ...]:
        return ((x0, y0), (x1, y0), (x1, y1), (x0, y1))

    face = ((0.0, inner), (0.0, -inner))
    f_bound, m_bound = MAX_A * pub.FORCE_UNIT_N, MAX_B * pub.MOMENT_UNIT_NMM
    return Layout(
        parts=(
            ("beam_top", rect(-length, 0.0, inner, outer)),
            ("beam_bottom", rect(-length, 0.0, -outer, -inner)),
            ("stage", rect(0.0, s, -outer, outer)),
        ),
        thickness=pub.HEIGHT_MM,
        clamp=(((-length, inner), (-length, outer)), ((-length, -outer), (-length, -inner))),
        stage=("stage",),
        loads=(
            Load("F_x", face, "force", (1.0, 0.0, 0.0), "N", f_bound),
            Load("F_y", face, "force", (0.0, 1.0, 0.0), "N", f_bound),
            Load("M_z", face, "couple", (0.0, 0.0, 1.0), "N·mm", m_bound),
        ),
        young=pub.YOUNG_MPA,
        poisson=pub.POISSON,
        part_young=() if stage_young is None else (("stage", float(stage_young)),),
        mesh_sizes=() if stage_size is None else (("stage", float(stage_size)),),
    )


def layers_for(size: float) -> int:
    """Q2 layers through the height H for in-plane elements of ``size`` mm: about cubic
    elements, at least one."""
    return max(1, math.ceil(pub.HEIGHT_MM / size - 1e-9))
