"""The mechanism-independent FE core on the parallelogram: refusals before meshing, the linear
model against beam theory, the campaign, cache and cold check through it."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from mechlib import fespecs as fespecs  # the FE families a store holds, registered
from mechlib.campaign.cachecheck import spec_from_key
from mechlib.campaign.experiments import run_experiments
from mechlib.campaign.taskcache import model_code_fingerprint
from mechlib.compliant.layout import Layout, Load, check_load_design
from mechlib.compliant.model import MechanismModel
from mechlib.compliant.spec import MechanismSpec
from mechlib.hexflex.spec import ModelSpec
from mechlib.parallelogram import published as pub
from mechlib.parallelogram.mechanism import layout

SQUARE = ((0.0, 0.0), (10.0, 0.0), (10.0, 10.0), (0.0, 10.0))


def _base(**change) -> dict:
    fields = dataclasses.asdict(layout())
    fields["loads"] = layout().loads
    fields.update(change)
    return fields


def test_the_parallelogram_layout_is_accepted_and_names_its_regions() -> None:
    lay = layout()
    assert lay.names == ("beam_top", "beam_bottom", "stage")
    assert [ld.name for ld in lay.loads] == ["F_x", "F_y", "M_z"]
    assert lay.one_material and not layout(stage_young=5e6).one_material


def test_a_load_off_the_part_is_refused_naming_it() -> None:
    off = Load("F_y", ((-30.0, 10.0), (-30.0, -10.0)), "force", (0, 1, 0))
    with pytest.raises(ValueError, match=r"load 'F_y' is off the part.*nearest edge"):
        Layout(**_base(loads=(off,)))


def test_a_load_on_a_beam_or_across_a_joint_is_refused() -> None:
    on_beam = Load("F", ((-100.0, 77.5), (-50.0, 77.5)), "force", (0, 1, 0))
    with pytest.raises(ValueError, match=r"load 'F' is on part 'beam_top', not on the stage"):
        Layout(**_base(loads=(on_beam,)))
    across = Load("F", ((0.0, 77.5), (0.0, -77.5)), "force", (0, 1, 0))
    with pytest.raises(ValueError, match=r"load 'F' lies between parts"):
        Layout(**_base(loads=(across,)))


def test_a_stage_in_pieces_is_refused() -> None:
    parts = (*layout().parts, ("island", ((60.0, 0.0), (70.0, 0.0), (70.0, 10.0), (60.0, 10.0))))
    with pytest.raises(ValueError, match="planform must be one piece"):
        Layout(**_base(parts=parts))
    parts = (("a", SQUARE), ("b", ((10.0, 0.0), (20.0, 0.0), (20.0, 10.0), (10.0, 10.0))),
             ("c", ((20.0, 0.0), (30.0, 0.0), (30.0, 10.0), (20.0, 10.0))))  # fmt: skip
    with pytest.raises(ValueError, match=r"the stage region is not connected.*2 pieces"):
        Layout(parts=parts, thickness=1.0, clamp=(((10.0, 0.0), (20.0, 0.0)),), stage=("a", "c"),
               loads=(Load("F", ((0.0, 0.0), (0.0, 10.0))),), young=1.0, poisson=0.3)  # fmt: skip


def test_a_clamp_with_no_faces_is_refused() -> None:
    with pytest.raises(ValueError, match=r"clamp segment 0 .* lies on no face of the part"):
        Layout(**_base(clamp=(((-300.0, 0.0), (-300.0, 10.0)),)))
    with pytest.raises(ValueError, match="clamp segment 0 is on the stage"):
        Layout(**_base(clamp=(((50.0, -10.0), (50.0, 10.0)),)))


def test_bad_parts_and_loads_are_refused_by_name() -> None:
    with pytest.raises(ValueError, match="part 'bow' is not a simple polygon"):
        Layout(**_base(parts=(("bow", ((0, 0), (1, 1), (1, 0), (0, 1))),)))
    with pytest.raises(ValueError, match=r"load 'M_z' must lie in \[-4\.375e\+06"):
        check_load_design(layout(), [[0.0, 0.0, 5e6]])
    with pytest.raises(ValueError, match=r"loads must have 3 columns \(F_x, F_y, M_z\)"):
        check_load_design(layout(), np.zeros((2, 6)))


def test_linear_compliance_meets_guided_beam_theory_and_couples_no_force() -> None:
    m = MechanismModel(layout(), 10.0, 2)
    c = m.compliance()  # µm/N, µrad/(N·mm)
    guided = pub.LENGTH_MM**3 / (24 * pub.BENDING_STIFFNESS_NMM2) * 1e3
    assert c[1, 1] == pytest.approx(guided, rel=0.02)  # shear and the joints: within 2 %
    # the couple's load vector has zero resultant
    loads = m.load_vectors()
    dofs = m.fe.eq.reshape(-1, 3)
    free = dofs[:, 0] >= 0
    assert np.abs(loads[dofs[free, 0], 2].sum()) < 1e-12
    assert np.abs(loads[dofs[free, 1], 1].sum() - 1.0) < 1e-12


def test_campaign_caches_a_mechanism_and_keeps_the_hexflex_fingerprint(tmp_path) -> None:
    spec = MechanismSpec(layout(), 10.0, 1)
    assert spec_from_key(spec.key()) == spec
    assert model_code_fingerprint(spec.TASK_MODULES) != model_code_fingerprint(
        ModelSpec.TASK_MODULES
    )
    loads = np.array([pub.loads_to_newton(0.0, 2.0, 0.0)], dtype=float)
    first = run_experiments(spec, loads, kind="nonlinear", steps=1, cache_dir=tmp_path,
                            progress=False)  # fmt: skip
    again = run_experiments(spec, loads, kind="nonlinear", steps=1, cache_dir=tmp_path,
                            progress=False)  # fmt: skip
    assert np.array_equal(first, again) and len(list(tmp_path.glob("*.npy"))) == 1
    linear = run_experiments(spec, loads, kind="linear", progress=False)
    # at A_y = 2 the stage's u_y is shortened by the beams' arc: below the linear value
    assert 0.9 * linear[0, 1] < first[0, 1] < linear[0, 1]
    with pytest.raises(ValueError, match="load 'F_y' must lie in"):
        run_experiments(spec, [[0.0, 1e6, 0.0]], progress=False)


def test_a_load_face_whose_ends_are_no_mesh_vertices_is_refused_at_the_build() -> None:
    part_of_face = Load("F", ((0.0, 33.0), (0.0, -11.0)), "couple", (0, 0, 1), "N·mm")
    lay = Layout(**_base(loads=(part_of_face,)))  # on the stage's face: accepted before meshing
    with pytest.raises(ValueError, match=r"load 'F' .* is covered by facets over .* of its 44 mm"):
        MechanismModel(lay, 20.0, 1)
