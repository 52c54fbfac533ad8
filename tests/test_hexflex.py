"""HexFlex geometry, mesh, FE model invariants, beam check and bad input."""

import numpy as np
import pytest

from mechlib import published as pub
from mechlib.fe.pose import fit_operator
from mechlib.hexflex import checks
from mechlib.hexflex import geometry as geo
from mechlib.hexflex import identify as ident
from mechlib.hexflex.fe import mesh as ms
from mechlib.hexflex.fe.model import HexFlexModel
from mechlib.hexflex.spec import ModelSpec
from mechlib.hexflex.studies import beamcheck, convergence

SMALL = geo.HexFlexGeometry(
    stage_radius=12.0,
    tab_half_width=2.0,
    tab_outer=22.0,
    beam_radius=11.0,
    beam_width=1.0,
    beam_length=8.0,
    radial_width=1.0,
    radial_length=5.0,
    thickness=0.8,
)


@pytest.fixture(scope="module")
def shell_model() -> HexFlexModel:
    return HexFlexModel(SMALL, element="shell", mesh_size=1.0)


def test_actuator_layout_reproduces_the_sign_pattern_of_eq8() -> None:
    d = geo.actuator_directions()
    np.testing.assert_allclose(
        d[0::2, :2], [[1, 0], [0.5, np.sqrt(3) / 2], [-0.5, np.sqrt(3) / 2]], atol=1e-12
    )
    # moment about z of a D1 force at the tab axis: its sign is the sign of Eq 8's θz row
    e_r, _ = geo.tab_frames()
    mz = e_r[:, 0] * d[0::2, 1] - e_r[:, 1] * d[0::2, 0]
    assert np.array_equal(np.sign(mz), np.sign(pub.EQ8_ST[5, 0::2]))
    # moments about x and y of a +z force at each tab: signs of Eq 8's θx and θy rows
    assert np.array_equal(np.sign(np.round(e_r[:, 1], 9)), np.sign(pub.EQ8_ST[3, 1::2]))
    assert np.array_equal(np.sign(np.round(-e_r[:, 0], 9)), np.sign(pub.EQ8_ST[4, 1::2]))


def test_symmetry_completed_mesh_has_merged_cut_lines_and_three_fold_symmetry() -> None:
    sector = ms.sector_mesh(SMALL, 1.0)
    full = ms.full_mesh(sector, 1.0)
    assert len(full.quads) == 6 * len(sector.quads)
    # every edge is shared by at most two quads: the cut lines were merged
    edges = np.sort(np.stack([full.quads, np.roll(full.quads, -1, axis=1)], -1).reshape(-1, 2), 1)
    _, counts = np.unique(edges, axis=0, return_counts=True)
    assert counts.max() == 2
    a = 2 * np.pi / 3
    rot = np.array([[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]])
    from scipy.spatial import cKDTree

    dist, _ = cKDTree(full.nodes).query(full.nodes @ rot.T)
    assert dist.max() < 1e-9


@pytest.mark.parametrize(("size", "across"), [(1.0, 2), (0.5, 2), (0.3, 4), (0.2, 6)])
@pytest.mark.parametrize("part", ["beam", "radial"])
def test_flexures_are_structured_with_an_even_element_count_across(size, across, part) -> None:
    sector = ms.sector_mesh(SMALL, size)
    parts = geo.classify(sector.nodes[sector.quads].mean(axis=1), SMALL)
    ((r0, r1, s0, s1),) = SMALL.rectangles()[part]
    quads = sector.quads[parts == geo.PARTS.index(part)]
    x, y = sector.nodes[quads, 0], sector.nodes[quads, 1]  # leg T1: (x, y) = (s, r)
    # the D1 segment runs along s (x), the radial segment along r (y)
    (a0, a1, w0, w1), along, across_xy = (
        ((s0, s1, r0, r1), x, y) if part == "beam" else ((r0, r1, s0, s1), y, x)
    )
    columns = np.unique(np.round(across_xy, 9))
    np.testing.assert_allclose(columns, np.linspace(w0, w1, across + 1), atol=1e-9)
    rows = np.unique(np.round(along, 9))
    np.testing.assert_allclose(rows[[0, -1]], [a0, a1], atol=1e-9)
    step = np.diff(rows)
    end = ms.BEAM_ASPECT * (w1 - w0) / across
    assert max(step[0], step[-1]) <= 1.2 * end  # short elements at both joints
    assert step.max() <= 1.2 * ms.MID_WIDTHS * (w1 - w0)
    assert len(quads) == across * (len(rows) - 1)


@pytest.mark.parametrize("element", ["shell", "q2"])
def test_actuator_loads_act_at_the_external_edge(element: str) -> None:
    """Each unit load vector has resultant = its direction and moment = (R_t e_r) × direction
    (the edge's centre on the mid-plane), over every DOF node (Q2: vertices, edges, faces)."""
    p = HexFlexModel(SMALL, element=element, mesh_size=1.0).fe
    coors = np.asarray(p.field.get_coor(), dtype=float)
    dofs = p.eq.reshape(-1, p.n_comp)[: len(coors)]
    dirs = geo.actuator_directions()
    points = np.c_[geo.actuator_points(SMALL), np.zeros(3)]
    for j in range(6):
        f = np.where(dofs[:, :3] >= 0, p.loads[np.maximum(dofs[:, :3], 0), j], 0.0)
        np.testing.assert_allclose(f.sum(axis=0), dirs[j], atol=1e-12)
        moment = np.cross(coors, f).sum(axis=0)
        np.testing.assert_allclose(moment, np.cross(points[j // 2], dirs[j]), atol=1e-9)
        loaded = np.abs(f).sum(axis=1) > 0
        r, s = geo.local_coordinates(coors[loaded])
        assert np.allclose(r[:, j // 2], SMALL.tab_outer)  # only the external edge is loaded
        assert np.all(np.abs(s[:, j // 2]) <= SMALL.tab_half_width + 1e-9)


def test_the_zero_pattern_checked_is_eq8s() -> None:
    c = pub.EQ8_ST.copy()
    assert checks.zero_pattern_defect(c) == 0.0
    for i, j in zip(*np.nonzero(pub.EQ8_ST == 0), strict=True):
        bad = c.copy()
        bad[i, j] = 1e-3 * np.abs(c[i]).max()
        assert checks.zero_pattern_defect(bad) == pytest.approx(1e-3)


def test_model_invariants_symmetry_zero_pattern_reciprocity(shell_model: HexFlexModel) -> None:
    c = shell_model.compliance()
    assert checks.symmetry_defect(c) < 1e-6
    assert checks.zero_pattern_defect(c) < 1e-6
    p = shell_model.port_compliance()
    assert np.abs(p - p.T).max() < 1e-9 * np.abs(p).max()
    assert np.all(np.sign(c[pub.EQ8_ST != 0]) == np.sign(pub.EQ8_ST[pub.EQ8_ST != 0]))
    # a symmetry defect is detected when one column is perturbed
    bad = c.copy()
    bad[0, 2] *= 1.01
    assert checks.symmetry_defect(bad) > 1e-3


def test_poses_are_linear_and_the_fit_recovers_a_rigid_motion(shell_model: HexFlexModel) -> None:
    f = np.array([[0.3, -1.0, 0.5, 0.2, -0.7, 1.0]])
    np.testing.assert_allclose(
        shell_model.poses(f)[0], shell_model.compliance() @ f[0], rtol=1e-9, atol=1e-9
    )
    pts = np.random.default_rng(0).normal(size=(20, 3))
    t, th = np.array([1e-3, -2e-3, 5e-4]), np.array([1e-5, 2e-5, -3e-5])
    u = t + np.cross(th, pts)
    np.testing.assert_allclose(fit_operator(pts) @ u.ravel(), np.r_[1e3 * t, 1e6 * th], atol=1e-9)


def test_q2_beam_matches_timoshenko_within_one_percent() -> None:
    for direction in ("in_plane", "out_of_plane"):
        fe = beamcheck.fe_tip(20.0, 1.0, 0.6, 71700.0, 0.33, direction, n_width=2, tip_length=1.0)
        th = beamcheck.timoshenko_tip(19.5, 1.0, 0.6, 71700.0, 0.33, direction, at=20.0)
        assert fe / th == pytest.approx(1.0, abs=0.01)


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ({"thickness": 0.1}, r"thickness \[mm\] must be in \[0.2, 5.0\], got 0.1"),
        ({"beam_width": 4.0}, r"beam_width \[mm\] must be in \[0.1, 3.0\], got 4"),
        ({"tab_half_width": 6.0}, r"tab_half_width \[mm\] must be < √3/4 · stage_radius"),
        (
            {"beam_radius": 9.0},
            r"beam_radius \[mm\] must be >= .*would touch the stage\), got 9 mm",
        ),
        (
            {"radial_length": 1.0, "beam_width": 2.0},
            r"radial_length \[mm\] must be >= beam_width/2 \+ 0.5 = 1.5 mm \(no free radial"
            r" segment\), got 1 mm",
        ),
        (
            {"tab_outer": 15.0, "beam_radius": 14.8},
            r"tab_outer \[mm\] must be >= .*the tab ends inside its beams",
        ),
        (
            {"beam_length": 16.0},
            r"beam_length \[mm\] must be <= .*do not fit between the tabs\), got 16 mm",
        ),
    ],
)
def test_bad_geometry_is_refused_by_name_before_meshing(change, message) -> None:
    with pytest.raises(ValueError, match=message):
        SMALL.replace(**change)


def test_geometry_by_name_round_trips_and_refuses_unknown_or_missing_names() -> None:
    assert geo.HexFlexGeometry.from_dict(SMALL.as_dict()) == SMALL
    with pytest.raises(ValueError, match=r"unknown: \['colour'\], missing: \['thickness'\]"):
        geo.HexFlexGeometry.from_dict(
            {**{k: v for k, v in SMALL.as_dict().items() if k != "thickness"}, "colour": 1.0}
        )


def test_grounded_sectors_clear_the_tabs_and_meet_the_clamped_ends() -> None:
    polys = geo.ground_polygons(SMALL, outer=40.0)
    assert len(polys) == 3
    for poly in polys:
        r, s = geo.local_coordinates(poly)
        # no vertex of a sector lies inside a tab (|s| < tab half-width, r > 0 in its frame)
        inside = (np.abs(s) < SMALL.tab_half_width) & (r > 0)
        assert not inside.any()
    # every clamped end of a radial segment lies on the inner edge of one sector
    e_r, e_s = geo.tab_frames()
    edges = [(p[i], p[i + 1]) for p in polys for i in (0, 1)]
    for k in range(3):
        for sign in (1.0, -1.0):
            for s_end in (
                SMALL.corner_s - SMALL.radial_width / 2,
                SMALL.corner_s + SMALL.radial_width / 2,
            ):
                q = SMALL.ground_radius * e_r[k] + sign * s_end * e_s[k]
                dist = [_segment_distance(q, a, b) for a, b in edges]
                assert min(dist) < 1e-9


def _segment_distance(q: np.ndarray, a: np.ndarray, b: np.ndarray) -> float:
    t = np.clip(np.dot(q - a, b - a) / np.dot(b - a, b - a), 0.0, 1.0)
    return float(np.linalg.norm(q - (a + t * (b - a))))


def test_a_stiff_body_keeps_the_symmetry_and_only_stiffens() -> None:
    soft = HexFlexModel(SMALL, element="shell", mesh_size=1.0)
    stiff = HexFlexModel(SMALL, element="shell", mesh_size=1.0, body_factor=1e3)
    c = stiff.compliance()
    assert checks.symmetry_defect(c) < 1e-6 and checks.zero_pattern_defect(c) < 1e-6
    # a stiffer body can only make the structure stiffer: no port compliance grows
    assert np.all(np.diag(stiff.port_compliance()) <= np.diag(soft.port_compliance()) * (1 + 1e-9))
    with pytest.raises(ValueError, match=r"body_factor must be in \[1.0, 1000000.0\]"):
        HexFlexModel(SMALL, element="shell", mesh_size=1.0, body_factor=0.5)


def test_bad_input_gets_clear_errors(shell_model: HexFlexModel) -> None:
    with pytest.raises(ValueError, match=r"mesh_size \[mm\] must be"):
        ms.sector_mesh(SMALL, 2.0)
    with pytest.raises(ValueError, match=r"forces \[N\] must lie in \[-50, 50\]"):
        shell_model.poses(np.full((1, 6), 60.0))
    with pytest.raises(ValueError, match="element must be one of"):
        HexFlexModel(SMALL, element="q1")
    with pytest.raises(ValueError, match=r"coarsening must be"):
        HexFlexModel(SMALL, element="shell", mesh_size=1.0, coarsening=0.5)
    with pytest.raises(ValueError, match=r"poisson must be"):
        HexFlexModel(SMALL, element="shell", poisson=0.5)


def _row(element: str, fraction: float, coarse: float, mags: list[float]) -> dict:
    c = np.zeros((6, 6))
    for (i, j, sign), v in zip(ident.TARGET_ENTRIES, mags, strict=True):
        c[i, j] = sign * v
    return {"element": element, "fraction": fraction, "coarse_widths": coarse, "compliance": c}


def test_convergence_changes_are_measured_between_the_right_meshes() -> None:
    rows = [
        _row("q2", 0.25, 4.0, [101.0, 10.0, 10.0, 10.0]),
        _row("q2", 0.5, 4.0, [100.0, 10.0, 10.0, 10.0]),  # the chosen mesh
        _row("q2", 1 / 6, 4.0, [101.0, 10.0, 10.05, 10.0]),
        _row("q2", 0.5, 2.0, [100.0, 10.2, 10.0, 10.0]),  # free region refined
        _row("shell", 1 / 6, 4.0, [101.0, 10.0, 10.05, 10.3]),
        _row("shell", 0.5, 4.0, [90.0, 10.0, 10.0, 10.0]),
    ]
    got = convergence.changes(rows, 0.5, 4.0)
    np.testing.assert_allclose(got["fractions"], [0.5, 0.25, 1 / 6])
    np.testing.assert_allclose(got["steps"], [0.01, 0.005])
    assert got["next"] == pytest.approx(0.01)
    assert got["finest"] == pytest.approx(1 / 101)  # x: 100 against 101
    assert got["coarse_region"] == pytest.approx(0.02)
    assert got["shell_vs_q2"] == pytest.approx(0.03)
    assert np.isnan(convergence.changes(rows, 1 / 6, 4.0)["next"])
    with pytest.raises(ValueError, match="chosen_fraction must be one of the Q2 fractions"):
        convergence.changes(rows, 0.3, 4.0)


def test_fitted_dimensions_on_their_bounds_are_named() -> None:
    g = SMALL.replace(thickness=geo.DIMENSION_BOUNDS["thickness"][1] / 1.005)
    assert ident.at_bounds(g, ["beam_length", "thickness"]) == ["thickness"]


_EXPONENTS = np.array([[-3.0, -1.0, 3.0], [-3.0, -1.0, 1.0], [-3.0, -1.0, 0.5], [-1.0, -3.0, 2.0]])
_FREE = ["thickness", "beam_width", "beam_length"]


def _power_law(g: geo.HexFlexGeometry, exponents: np.ndarray = _EXPONENTS) -> np.ndarray:
    """A synthetic compliance whose four magnitudes are power laws of three dimensions."""
    dims = np.log([getattr(g, n) for n in _FREE])
    c = np.zeros((6, 6))
    for (i, j, sign), v in zip(ident.TARGET_ENTRIES, np.exp(exponents @ dims), strict=True):
        c[i, j] = sign * v
    return c


def test_log_sensitivity_recovers_power_law_exponents() -> None:
    got = ident.log_sensitivity(_power_law, SMALL, _FREE)
    np.testing.assert_allclose(got, _EXPONENTS, atol=1e-6)
    # forward differences, and one-sided ones on a bound, are exact on a power law too
    np.testing.assert_allclose(ident.log_sensitivity(_power_law, SMALL, _FREE, central=False),
                               _EXPONENTS, atol=1e-6)  # fmt: skip
    on_bound = SMALL.replace(thickness=geo.DIMENSION_BOUNDS["thickness"][1])
    np.testing.assert_allclose(ident.log_sensitivity(_power_law, on_bound, _FREE), _EXPONENTS,
                               atol=1e-6)  # fmt: skip
    with pytest.raises(ValueError, match="free dimension must be one of"):
        ident.log_sensitivity(_power_law, SMALL, ["colour"])


def test_identify_converges_with_an_inexact_surrogate_jacobian() -> None:
    truth = SMALL.replace(thickness=0.9, beam_width=1.1, beam_length=8.5)
    target = ident.target_values(_power_law(truth))
    rough = _EXPONENTS * 1.15  # the surrogate's sensitivities are 15 % off
    fit = ident.identify(SMALL, target, _FREE, _power_law, lambda g: _power_law(g, rough),
                         max_evaluations=12, tol=1e-6, grid_decimals=None)  # fmt: skip
    assert np.abs(fit.relative_error).max() < 1e-6
    assert fit.n_evaluations < 12
    # least squares with 3 dimensions for 4 magnitudes: the truth is the exact solution
    for n in _FREE:
        assert getattr(fit.geometry, n) == pytest.approx(getattr(truth, n), rel=1e-5)
    with pytest.raises(ValueError, match="target must be 4 positive"):
        ident.identify(SMALL, [1.0, 2.0], _FREE, _power_law, _power_law)
    with pytest.raises(ValueError, match="free dimensions must be distinct"):
        ident.identify(SMALL, target, ["thickness", "thickness"], _power_law, _power_law)


def test_identify_raises_by_name_when_a_bound_holds_the_fit() -> None:
    """A target that needs a dimension beyond its bound: no convergence, an error naming the
    misfit and the dimension on the bound, with the best fit attached."""
    low = geo.DIMENSION_BOUNDS["thickness"][0]
    truth = SMALL.replace(thickness=low)
    target = ident.target_values(_power_law(truth)) * np.array([1.5, 1.5, 1.5, 1.2])
    with pytest.raises(ident.IdentificationError, match=r"did not converge.*\['thickness'\]") as e:
        ident.identify(SMALL, target, _FREE, _power_law, _power_law, max_evaluations=10)
    assert e.value.result.n_evaluations <= 10
    assert ident.at_bounds(e.value.result.geometry, _FREE) == ["thickness"]
    with pytest.raises(ValueError, match=r"grid_decimals must be .*2"):
        ident.identify(SMALL, target, _FREE, _power_law, _power_law, grid_decimals=2)


def test_midplane_shapes_of_the_inverse_forces_move_the_stage_by_the_poses(
    shell_model: HexFlexModel,
) -> None:
    # Fig 3's data: the shapes of pure poses. The shell's mid-plane nodes are its FE nodes, so a
    # rigid-body fit over the stage's nodes recovers each requested pose.
    poses = np.diag([10.0, 10.0, 10.0, 100.0, 100.0, 100.0])  # µm, µrad
    forces = shell_model.forces_for_poses(poses)
    shapes = shell_model.midplane_shapes(forces)
    nodes = shell_model.planar.nodes
    assert shapes.shape == (6, len(nodes), 3)
    points = np.c_[nodes, np.zeros(len(nodes))]
    stage = geo.in_stage(points, SMALL)
    fit = fit_operator(points[stage])
    fitted = np.array([fit @ s[stage].ravel() for s in shapes])
    np.testing.assert_allclose(fitted, poses, atol=1e-6 * np.abs(poses).max())
    one = shell_model.midplane_displacements(forces[2])  # one solve: the same to round-off
    np.testing.assert_allclose(shapes[2], one, rtol=1e-12, atol=1e-12 * np.abs(one).max())


def test_the_convergence_study_reads_its_models_from_the_cache(tmp_path, monkeypatch) -> None:
    from mechlib.campaign import experiments as ex

    first = convergence.study(SMALL, [1.0], elements=("shell",), cache_dir=tmp_path)
    ex.release_models()
    monkeypatch.setattr(ModelSpec, "build", lambda self: pytest.fail("a model was built"))
    again = convergence.study(SMALL, [1.0], elements=("shell",), cache_dir=tmp_path)
    assert again[0]["n_dofs"] == first[0]["n_dofs"] > 0
    np.testing.assert_array_equal(again[0]["compliance"], first[0]["compliance"])
