"""Frame solver against beam theory, and the HexFlex frame model's invariants, fit and bad input."""

import numpy as np
import pytest

from mechlib import published as pub
from mechlib.hexflex import checks
from mechlib.hexflex import frame as fr
from mechlib.hexflex import frame_solver as fs
from mechlib.hexflex import geometry as geo
from mechlib.hexflex import identify as ident

E, NU = 70_000.0, 0.3
G = E / (2 * (1 + NU))
B, T = 0.4, 1.1  # section width (in plane) and depth (along z) [mm]
A = B * T
I_IN, I_OUT = T * B**3 / 12, B * T**3 / 12  # in-plane and out-of-plane bending inertias
KGA = fs.SHEAR_FACTOR * G * A
TIGHT = 1e-10
HINT = geo.HexFlexGeometry()  # ρ 22, R_t 45, s₀ 3, t 0.505, widths 0.276, L₁ 11.72, L₂ 3.95
FREE5 = ("thickness", "beam_width", "radial_width", "beam_length", "radial_length")


def cantilever(length: float, n: int, angle: float = 0.0) -> fs.Frame:
    """Clamped at the origin, ``n`` elements along the in-plane direction ``angle`` [rad]."""
    axis = np.array([np.cos(angle), np.sin(angle), 0.0])
    nodes = np.linspace(0, length, n + 1)[:, None] * axis
    elements = np.c_[np.arange(n), np.arange(1, n + 1)]
    return fs.Frame(nodes, elements, np.full(n, B), np.full(n, T), clamped=(0,))


def tip_load(frame: fs.Frame, node: int, load: list[float]) -> np.ndarray:
    f = np.zeros((len(frame.nodes), 6))
    f[node] = load
    return f


@pytest.mark.parametrize("n", [1, 3])
@pytest.mark.parametrize("shear", [False, True])
def test_cantilever_tip_deflection_and_rotation_in_both_planes(n: int, shear: bool) -> None:
    L, P = 7.0, 2.5
    frame = cantilever(L, n)
    for load, dof, rot_dof, inertia, rot_sign in ((1, 1, 5, I_IN, 1), (2, 2, 4, I_OUT, -1)):
        f = np.zeros(6)
        f[load] = P
        u = fs.solve_frame(frame, E, NU, tip_load(frame, n, f), shear=shear)[n]
        expected = P * L**3 / (3 * E * inertia) + (P * L / KGA if shear else 0.0)
        assert u[dof] == pytest.approx(expected, rel=TIGHT)
        # θz = +v', θy = −w' (right-handed rotations)
        assert u[rot_dof] == pytest.approx(rot_sign * P * L**2 / (2 * E * inertia), rel=TIGHT)


def test_cantilever_along_an_oblique_axis_bends_like_one_along_x() -> None:
    L, angle = 5.0, np.deg2rad(37.0)
    frame = cantilever(L, 2, angle)
    normal = np.array([-np.sin(angle), np.cos(angle)])
    u = fs.solve_frame(frame, E, NU, tip_load(frame, 2, [*normal, 0, 0, 0, 0]), shear=False)[2]
    assert u[:2] @ normal == pytest.approx(L**3 / (3 * E * I_IN), rel=TIGHT)
    assert u[:2] @ [np.cos(angle), np.sin(angle)] == pytest.approx(0.0, abs=1e-14)


def test_torsion_tip_twist_is_tl_over_gj() -> None:
    L, M = 6.0, 0.8
    frame = cantilever(L, 2)
    u = fs.solve_frame(frame, E, NU, tip_load(frame, 2, [0, 0, 0, M, 0, 0]))[2]
    assert u[3] == pytest.approx(M * L / (G * fs.torsion_constant(B, T)), rel=TIGHT)
    assert np.abs(u[[0, 1, 2, 4, 5]]).max() < 1e-14


@pytest.mark.parametrize("ratio", [1.0, 1.5, 2.0, 5.0, 10.0])
def test_roark_torsion_constant_against_saint_venant_series(ratio: float) -> None:
    a, b = ratio, 1.0  # long and short sides
    k = np.arange(1, 4001, 2)
    series = (
        a
        * b**3
        / 3
        * (1 - 192 / np.pi**5 * (b / a) * np.sum(np.tanh(k * np.pi * a / (2 * b)) / k**5))
    )
    assert fs.torsion_constant(a, b) == pytest.approx(series, rel=2.5e-3)  # Roark: ≤ 0.2 % here
    assert fs.torsion_constant(b, a) == fs.torsion_constant(a, b)


@pytest.mark.parametrize("shear", [False, True])
def test_l_frame_out_of_plane_load_matches_castigliano(shear: bool) -> None:
    # leg 1 clamped at the origin along x (length a), leg 2 along y (length b), load P along z
    a, b, P = 8.0, 5.0, 1.7
    nodes = np.array([[0, 0, 0], [a, 0, 0], [a, b, 0]], dtype=float)
    frame = fs.Frame(nodes, np.array([[0, 1], [1, 2]]), np.full(2, B), np.full(2, T), clamped=(0,))
    w = fs.solve_frame(frame, E, NU, tip_load(frame, 2, [0, 0, P, 0, 0, 0]), shear=shear)[2, 2]
    bending = P * (a**3 + b**3) / (3 * E * I_OUT)
    torsion = P * b**2 * a / (G * fs.torsion_constant(B, T))  # torque P·b along leg 1
    expected = bending + torsion + (P * (a + b) / KGA if shear else 0.0)
    assert w == pytest.approx(expected, rel=TIGHT)


def rigid_cross(L: float) -> fs.Frame:
    """Master at the origin, slaves at (±1, 0), (0, ±1); from each a beam of length L outward."""
    dirs = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0]], dtype=float)
    nodes = np.vstack([np.zeros(3), dirs, dirs * (1 + L)])
    elements = np.c_[np.arange(1, 5), np.arange(5, 9)]
    return fs.Frame(nodes, elements, np.full(4, B), np.full(4, T), (5, 6, 7, 8), {0: (1, 2, 3, 4)})


@pytest.mark.parametrize("shear", [False, True])
def test_rigid_body_on_symmetric_supports_translates_without_rotating(shear: bool) -> None:
    L, P = 4.0, 1.3
    frame = rigid_cross(L)
    loads = np.zeros((2, 9, 6))
    loads[0, 0, 2] = P  # central load along z: four guided beams bending out of plane
    loads[1, 0, 0] = P  # along x: two beams axial, two guided beams bending in plane
    u = fs.solve_frame(frame, E, NU, loads, shear=shear)
    assert np.abs(u[:, 0, 3:]).max() < 1e-14
    # a guided beam (both ends clamped against rotation): k = 1 / (L³/(12EI) + L/(κGA))
    k_out, k_in = (1 / (L**3 / (12 * E * i) + (L / KGA if shear else 0.0)) for i in (I_OUT, I_IN))
    assert u[0, 0, 2] == pytest.approx(P / (4 * k_out), rel=TIGHT)
    assert u[1, 0, 0] == pytest.approx(P / (2 * E * A / L + 2 * k_in), rel=TIGHT)
    np.testing.assert_allclose(u[:, 1:5], np.repeat(u[:, :1], 4, axis=1), rtol=0, atol=1e-15)


def test_slaves_follow_the_master_as_a_rigid_body() -> None:
    frame = rigid_cross(3.0)
    u = fs.solve_frame(frame, E, NU, tip_load(frame, 1, [0.3, -0.2, 0.9, 0.5, -0.4, 0.7]))
    for s in range(1, 5):
        d = frame.nodes[s] - frame.nodes[0]
        np.testing.assert_allclose(u[s, :3], u[0, :3] + np.cross(u[0, 3:], d), rtol=1e-13, atol=0)
        np.testing.assert_allclose(u[s, 3:], u[0, 3:], rtol=1e-13, atol=0)
    assert np.all(u[5:] == 0)


def test_a_frame_without_supports_is_a_mechanism() -> None:
    frame = cantilever(3.0, 1)
    free = fs.Frame(frame.nodes, frame.elements, frame.widths, frame.depths)
    with pytest.raises(ValueError, match="mechanism"):
        fs.solve_frame(free, E, NU, tip_load(free, 1, [0, 1, 0, 0, 0, 0]))


# --- HexFlex ----------------------------------------------------------------------------------
@pytest.mark.parametrize("shear", [False, True])
def test_hexflex_compliance_is_threefold_symmetric_with_the_eq8_zero_pattern(shear: bool) -> None:
    c = fr.hexflex_frame_compliance(HINT, shear=shear)
    assert checks.symmetry_defect(c) < 1e-12
    assert checks.zero_pattern_defect(c) < 1e-12
    assert np.all(ident.target_values(c) > 0)  # the signs of Eq 8
    s = fr.stage_compliance(HINT, shear=shear)
    np.testing.assert_allclose(s, s.T, rtol=0, atol=1e-12 * np.abs(s).max())  # Maxwell–Betti


def test_hexflex_compliance_is_exact_with_one_element_per_segment() -> None:
    one = fr.hexflex_frame_compliance(HINT)
    five = fr.hexflex_frame_compliance(HINT, n_elements=5)
    np.testing.assert_allclose(five, one, rtol=0, atol=1e-10 * np.abs(one).max())


def test_hexflex_compliance_scales_as_one_over_young_and_in_plane_as_one_over_thickness() -> None:
    c = fr.hexflex_frame_compliance(HINT)
    stiffer = fr.hexflex_frame_compliance(HINT, young=2 * fr.AL7075_YOUNG_MPA)
    np.testing.assert_allclose(stiffer, c / 2, rtol=1e-12, atol=1e-12 * np.abs(c).max())
    sens = ident.log_sensitivity(fr.hexflex_frame_compliance, HINT, ("thickness",))
    # x←T1D1 and θz←T1D1 are in-plane: every in-plane stiffness (EA, E t b³/12, κGA) is ∝ t
    np.testing.assert_allclose(sens[[0, 3], 0], -1.0, rtol=1e-9)


def test_point_support_ratio_is_the_point_spring_model() -> None:
    # six vertical springs k = 1 at the attachment points, unknowns (z, θx, θy): spring stretch
    # z + θx·y − θy·x; unit load along z at (0, R_t) gives the wrench (1, R_t, 0)
    e_r, e_s = geo.tab_frames()
    g = HINT
    p = np.vstack([g.beam_radius * e_r + s * g.tab_half_width * e_s for s in (1, -1)])
    a = np.c_[np.ones(6), p[:, 1], -p[:, 0]]
    z, theta_x, _ = np.linalg.solve(a.T @ a, [1.0, g.tab_outer, 0.0])
    assert fr.point_support_ratio(g) == pytest.approx(theta_x / z * fr.MM_PER_M, rel=1e-12)


@pytest.mark.parametrize(
    "changes",
    [
        {},
        {"thickness": 1.2, "beam_length": 6.0},
        {"beam_radius": 30.0, "radial_length": 12.0, "tab_outer": 50.0},
    ],
)
def test_beams_tilt_less_than_point_springs(changes: dict[str, float]) -> None:
    g = HINT.replace(**changes)
    for shear in (False, True):
        c = fr.hexflex_frame_compliance(g, shear=shear)
        assert 0 < c[3, 1] / c[2, 1] < fr.point_support_ratio(g)


def test_prefit_recovers_a_geometry_from_its_own_magnitudes() -> None:
    free = ("thickness", "beam_width", "radial_width", "beam_length")
    truth = HINT.replace(thickness=0.6, beam_width=0.3, radial_width=0.25, beam_length=10.0)
    target = ident.target_values(fr.hexflex_frame_compliance(truth))
    fitted, achieved = fr.prefit(target, HINT, free)
    np.testing.assert_allclose(achieved, target, rtol=1e-5)  # the anchor: O(1e-6)
    # four magnitudes, four dimensions, full rank (smallest singular value ≈ 0.2): unique
    for name in free:
        assert getattr(fitted, name) == pytest.approx(getattr(truth, name), rel=1e-5)
    again, _ = fr.prefit(target, HINT, free)
    assert again == fitted  # deterministic


def test_prefit_reaches_eq8_from_two_starts_at_two_different_geometries() -> None:
    target = ident.target_values(pub.EQ8_ST)
    fitted, achieved = fr.prefit(target, HINT, FREE5, shear=False)
    np.testing.assert_allclose(achieved, target, rtol=1e-5)  # the anchor: O(1e-6)

    def euler_bernoulli(g: geo.HexFlexGeometry) -> np.ndarray:
        return fr.hexflex_frame_compliance(g, shear=False)

    sv = np.linalg.svd(ident.log_sensitivity(euler_bernoulli, fitted, FREE5), compute_uv=False)
    assert sv[-1] > 0.1  # rank 4: four combinations of the five dimensions are determined ...
    other, achieved = fr.prefit(target, HINT.replace(radial_width=0.2), FREE5, shear=False)
    np.testing.assert_allclose(achieved, target, rtol=1e-5)  # the anchor: O(1e-6)
    assert abs(other.radial_width / fitted.radial_width - 1) > 0.05  # ... and the fifth is not


def test_hexflex_frame_nodes_are_the_centre_lines_of_geometry_py() -> None:
    frame = fr.hexflex_frame(HINT)  # T1's axis is +y, its s > 0 side is −x
    corner_s, ground = 3.0 + 11.72, 22.0 + 3.95
    expected = [[-3.0, 22.0], [-corner_s, 22.0], [-corner_s, ground]]  # attach, corner, clamp
    np.testing.assert_allclose(frame.nodes[1:4, :2], expected, atol=1e-12)
    np.testing.assert_allclose(frame.widths[:2], [HINT.beam_width, HINT.radial_width])
    assert frame.clamped[0] == 3 and frame.rigid == {0: (1, 4, 7, 10, 13, 16)}


def test_prefit_survives_geometries_the_constructor_rejects() -> None:
    # the target needs beam_radius 12, but below ≈ 20.44 the D1 segments hit the stage
    target = ident.target_values(
        fr.hexflex_frame_compliance(HINT.replace(stage_radius=12.0, beam_radius=12.0))
    )
    fitted, achieved = fr.prefit(target, HINT.replace(beam_radius=21.0), ("beam_radius",))
    low = (
        HINT.stage_radius - np.sqrt(3) * HINT.tab_half_width + HINT.beam_width / 2 + geo.MIN_GAP_MM
    )
    assert fitted.beam_radius == pytest.approx(low, abs=1e-3)  # stopped at the feasible edge
    assert achieved[2] < target[2]  # the tilt it could not reach


@pytest.mark.parametrize(
    ("call", "match"),
    [
        (lambda: fr.hexflex_frame_compliance(HINT, young=0.0), "young"),
        (lambda: fr.hexflex_frame_compliance(HINT, poisson=0.5), "poisson"),
        (lambda: fr.hexflex_frame_compliance(HINT, poisson=-1.0), "poisson"),
        (lambda: fr.hexflex_frame_compliance(HINT, n_elements=0), "n_elements"),
        (lambda: fr.prefit([1.0, 2.0, 3.0], HINT, FREE5), "target"),
        (lambda: fr.prefit([1.0, -2.0, 3.0, 4.0], HINT, FREE5), "target"),
        (lambda: fr.prefit([1.0] * 4, HINT, ("thickness", "width")), "free"),
        (lambda: fr.prefit([1.0] * 4, HINT, ("thickness", "thickness")), "free"),
        (
            lambda: fr.prefit([1.0] * 4, HINT, ("thickness",), bounds={"beam_width": (0.1, 1)}),
            "bounds",
        ),
        (lambda: fr.prefit([1.0] * 4, HINT, ("thickness",), bounds={"thickness": (1, 2)}), "start"),
        (lambda: fr.prefit([1.0] * 4, HINT, ("thickness",), young=-1.0), "young"),
        (
            lambda: ident.log_sensitivity(fr.hexflex_frame_compliance, HINT, ("thickness",), 0.0),
            "rel_step",
        ),
        (
            lambda: ident.log_sensitivity(fr.hexflex_frame_compliance, HINT, ("depth",)),
            "free dimension",
        ),
        (lambda: ident.target_values(np.zeros((6, 5))), "compliance"),
        (lambda: fs.solve_frame(cantilever(1.0, 1), E, NU, np.zeros((3, 6))), "loads"),
    ],
)
def test_bad_input_raises_value_error_naming_the_parameter(call, match: str) -> None:
    with pytest.raises(ValueError, match=match):
        call()
