"""HexFlex helpers that need no FE solve: compliance checks on hand-made matrices, the
geometry → compliance makers of the identification."""

import numpy as np
import pytest

from mechlib.hexflex import checks, frame
from mechlib.hexflex import geometry as geo
from mechlib.hexflex.fe import model
from mechlib.hexflex.geometry import TAB_ANGLES_DEG


def test_reciprocity_defect_of_a_symmetric_and_a_skewed_matrix() -> None:
    p = np.array([[2.0, 0.5], [0.5, 4.0]])
    assert checks.reciprocity_defect(p) == 0.0
    p[0, 1] = 0.6  # |P - Pᵀ| = 0.1 against max |P| = 4
    assert checks.reciprocity_defect(p) == pytest.approx(0.025)
    with pytest.raises(ValueError, match="square"):
        checks.reciprocity_defect(np.ones((2, 3)))


def test_tilt_per_lift_reads_thx_and_z_under_t1d2() -> None:
    c = np.zeros((6, 6))
    c[2, 1], c[3, 1] = 3.0, 6.0  # z←T1D2 = 3 µm/N, θx←T1D2 = 6 µrad/N: 2 rad/m
    c[2, 0], c[3, 0] = 1.0, 9.0  # the T1D1 column must not be read
    assert checks.tilt_per_lift(c) == 2.0


def test_the_hinged_link_bound_from_the_plane_through_three_joints() -> None:
    """Lift T1's joint of three on a circle of radius rho: the plane through them lifts the
    centre by z1/3 and tilts by 2/rho times that (rad/m for rho in mm, x 1e3)."""
    rho, z1 = 22.0, 1.0
    a = np.deg2rad(TAB_ANGLES_DEG)
    joints = np.column_stack([rho * np.cos(a), rho * np.sin(a)])
    lift = np.array([z1, 0.0, 0.0])  # T1 sits on the +y axis
    (z0, slope_x, slope_y), *_ = np.linalg.lstsq(np.c_[np.ones(3), joints], lift, rcond=None)
    assert z0 == pytest.approx(z1 / 3) and slope_x == pytest.approx(0.0, abs=1e-15)
    ratio = slope_y / z0 * 1e3  # θx = ∂z/∂y for a small tilt, per mm → per m
    assert ratio == pytest.approx(2 / rho * 1e3, rel=1e-12)
    assert checks.max_hinged_radius(ratio) == pytest.approx(rho, rel=1e-12)
    with pytest.raises(ValueError, match="ratio must be > 0"):
        checks.max_hinged_radius(-1.0)


def test_compliance_makers_build_the_model_and_return_its_compliance() -> None:
    built = []

    class Fake:
        def __init__(self, g: object) -> None:
            built.append(g)

        def compliance(self) -> np.ndarray:
            return np.full((6, 6), float(len(built)))

    fe_compliance = model.compliance_maker(Fake)
    assert fe_compliance("g1")[0, 0] == 1.0 and fe_compliance("g2")[0, 0] == 2.0
    assert built == ["g1", "g2"]
    g = geo.HexFlexGeometry()
    frame_compliance = frame.compliance_maker(young=70000.0, poisson=0.3)
    expected = frame.hexflex_frame_compliance(g, 70000.0, 0.3)
    np.testing.assert_array_equal(frame_compliance(g), expected)
    assert not np.allclose(expected, frame.hexflex_frame_compliance(g))  # the material counts
