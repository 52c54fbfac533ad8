"""The parallelogram comparison: elastica beside the published 3-D FE (rows, differences, the
published files' evidence, the mesh case), the arrays the figures draw, and the claims' rules."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mechlib.parallelogram import comparison as cmp
from mechlib.parallelogram import drawing
from mechlib.parallelogram import elastica as el
from mechlib.parallelogram import published as pub
from mechlib.reporting import claimlist, claims

S = pub.SWEEP_SUBSET
C = pub.AXIAL_COMPLIANCE


def _row(a_x: float, a_y: float, b: float, pose: tuple[float, float, float]) -> list[float]:
    return [a_x, a_y, b, *pose]


# --- the rows compared ----------------------------------------------------------------------


def test_applied_loads_and_fe_poses_correct_the_couple_and_the_rotation() -> None:
    sweep = np.array([_row(5, 3, -2, (0.1, 0.2, 0.3)), _row(5, -3, 2, (0.1, -0.2, -0.3))])
    np.testing.assert_array_equal(cmp.applied_loads(sweep), [[5, 3, 2], [5, -3, -2]])
    poses = cmp.fe_poses(sweep)
    np.testing.assert_array_equal(poses[:, :2], [[0.1, 0.2], [0.1, -0.2]])
    assert poses[0, 2] == pytest.approx(math.asin(2 * math.sin(0.3)) - 0.3, rel=1e-14)
    assert poses[0, 2] > 0.3  # the file under-reports the rotation
    with pytest.raises(ValueError, match=r"sweep must be a finite \(n, 6\) array"):
        cmp.applied_loads(sweep[:, :5])


def test_solve_loads_mirrors_and_continues_to_the_straight_path_solution() -> None:
    loads = [[-3.0, 4.0, 1.0], [-3.0, -4.0, -1.0], [-3.0, 2.0, 1.0], [2.0, 0.0, -1.0]]
    poses = cmp.solve_loads(loads, axial_compliance=C)
    np.testing.assert_array_equal(poses[1], poses[0] * [1, -1, -1])  # solved once, mirrored
    for load, pose in zip(loads, poses, strict=True):
        direct = el.solve_pose(*load, axial_compliance=C)  # from zero along the load path
        np.testing.assert_allclose(pose, [direct.u_x, direct.u_y, direct.phi], atol=1e-8)
    assert poses[3, 2] < 0  # a clockwise couple alone turns the stage clockwise
    with pytest.raises(ValueError, match=r"loads must be a finite \(n, 3\) array"):
        cmp.solve_loads([[0.0, 1.0]])


def test_at_printed_couple_solves_only_the_rows_whose_couple_was_lost() -> None:
    sweep = np.array([_row(0, 1, -1, (0, 0, 0)), _row(0, 1, 0, (0, 0, 0))])
    sentinel = np.array([[9.0, 9.0, 9.0], [7.0, 7.0, 7.0]])
    out = cmp.at_printed_couple(sweep, sentinel, axial_compliance=C)
    np.testing.assert_array_equal(out[1], sentinel[1])  # printed = applied: kept as given
    direct = el.solve_pose(0.0, 1.0, -1.0, axial_compliance=C)
    np.testing.assert_allclose(out[0], [direct.u_x, direct.u_y, direct.phi], atol=1e-9)
    with pytest.raises(ValueError, match="one row per sweep row"):
        cmp.at_printed_couple(sweep, sentinel[:1])


def test_compared_rows_and_relative_excess() -> None:
    loads = np.array([[0, 0, 0], [5, 0, 3], [0, 0.5, 0], [-5, -1, 0]], dtype=float)
    np.testing.assert_array_equal(
        cmp.compared_rows(loads),
        [[0, 0, 0], [0, 1, 1], [0, 1, 1], [1, 1, 1]],
    )
    fe = np.array([[1.0, 2.0, 4.0], [2.0, 4.0, 8.0]])
    rel = cmp.relative_excess(1.1 * fe, fe, [[True, False, True], [True, True, True]])
    np.testing.assert_allclose(rel[~np.isnan(rel)], 0.1, rtol=1e-12)
    assert np.isnan(rel[0, 1])
    with pytest.raises(ValueError, match="non-zero FE values"):
        cmp.relative_excess(fe, fe * [0, 1, 1], np.ones((2, 3), bool))


def test_summarise_shares_and_worst_by_on_known_differences() -> None:
    loads = np.array([[0, 1, 0], [0, 2, 0], [0, 4, 0], [5, 0, 0]], dtype=float)
    fe = np.array([[-1.0, 1.0, 0.1], [-2.0, 2.0, 0.2], [-4.0, 4.0, 0.4], [0.5, 0.0, 0.0]])
    model = fe + np.array([[0.1, 0.1, 0.0], [0.0, 0.4, 0.02], [0.2, 0.0, 0.0], [0.0, 0.0, 0.0]])
    s = cmp.summarise(model, fe, loads)
    np.testing.assert_allclose(s.worst_abs, [0.2, 0.4, 0.02])
    np.testing.assert_allclose(s.median_abs, [0.05, 0.05, 0.0])
    # in % of full scale: of the largest |FE value| (4, 4, 0.4), not max − min (4.5 for u_x)
    np.testing.assert_allclose(s.worst_share_pct, 100 * np.array([0.2 / 4, 0.4 / 4, 0.02 / 0.4]))
    # relative: u_x over |A_y| ≥ 1 (rows 0-2), u_y and φ over the loaded rows (0-2)
    np.testing.assert_allclose(s.worst_rel_pct, [10.0, 20.0, 10.0])
    np.testing.assert_allclose(s.median_rel_pct, [5.0, 10.0, 0.0])
    np.testing.assert_array_equal(s.worst_row, [2, 1, 1])
    np.testing.assert_allclose(cmp.shares_pct(model, fe)[1], [0.0, 10.0, 5.0])
    part = cmp.summarise(model, fe, loads, where=[True, False, False, False], span_of=fe)
    np.testing.assert_allclose(part.worst_share_pct, [100 * 0.1 / 4, 2.5, 0.0])
    levels, worst = cmp.worst_by([1, 2, 1, 3], [[1.0, np.nan], [2.0, np.nan], [3.0, 4.0], [0, 1]])
    assert levels.tolist() == [1, 2, 3]
    np.testing.assert_array_equal(worst[:, 0], [3.0, 2.0, 0.0])
    assert worst[0, 1] == 4.0 and np.isnan(worst[1, 1])
    with pytest.raises(ValueError, match="where select some"):
        cmp.summarise(model, fe, loads, where=np.zeros(4, bool))


def test_the_transcription_shows_the_lost_couple_sign_and_the_mirrored_rows() -> None:
    ev = cmp.sweep_evidence(S)
    assert ev.couple_pairs > 40 and ev.identical == ev.couple_pairs
    assert 0 < ev.with_unloaded < ev.couple_pairs  # the corners have no row with B = 0
    assert ev.differ_from_unloaded == ev.with_unloaded  # a couple was applied, not none
    assert ev.negative > 0 and ev.mirrored == ev.negative
    # a sweep whose couple sign was kept has no identical pair
    kept = np.array([_row(0, 1, 3, (0, 0.1, 0.02)), _row(0, 1, -3, (0, 0.1, -0.02)),
                     _row(0, 1, 0, (0, 0.1, 0.0)), _row(0, -1, 0, (0, -0.1, 0.0))])  # fmt: skip
    assert tuple(cmp.sweep_evidence(kept)) == (1, 0, 1, 1, 1, 1)


def test_the_mesh_case_beside_the_published_meshes() -> None:
    mesh = cmp.mesh_case()
    np.testing.assert_array_equal(mesh.meshes, pub.MESH_STUDY)
    sol = el.solve_pose(*pub.MESH_STUDY_LOADS, axial_compliance=C)
    np.testing.assert_allclose(mesh.elastica[:2], pub.to_mm([sol.u_x, sol.u_y]), rtol=1e-12)
    # beam theory is more compliant than every mesh, and the finer meshes come closer
    assert np.all(mesh.excess_pct[:, :2] > 0) and np.all(np.diff(mesh.excess_pct[:, 1]) < 0)
    y = pub.MESH_STUDY[:, 4]
    assert mesh.gap_closed[1] == pytest.approx((y[-1] - y[0]) / (mesh.elastica[1] - y[0]))
    assert 0 < mesh.gap_closed[1] < 1


# --- what the figures draw ------------------------------------------------------------------


def test_by_line_arranges_the_sweep_lines() -> None:
    a_y, grid = drawing.by_line(S, S[:, 3:], [-5.0, 0.0], [0.0, 3.0])
    assert grid.shape == (2, 2, 33, 3) and a_y.tolist() == pub.A_Y_LEVELS.tolist()
    np.testing.assert_array_equal(grid[1, 1], pub.sweep_line(0.0, 3.0)[:, 3:])
    with pytest.raises(ValueError, match=r"line \(A_x, B\) = \(1, 0\)"):
        drawing.by_line(S, S[:, 3:], [1.0], [0.0])


def test_stage_outline_turns_about_the_load_point_and_load_points() -> None:
    rest = drawing.stage_outline([0.0, 0.0, 0.0])
    edge = pub.HALF_WIDTH + pub.THICKNESS_MM / (2 * pub.LENGTH_MM)
    np.testing.assert_allclose(rest[:4], [[1, -edge], [1.2, -edge], [1.2, edge], [1, edge]])
    turned = drawing.stage_outline([0.1, -0.2, 0.5])
    np.testing.assert_allclose(
        np.linalg.norm(turned - [1.1, -0.2], axis=1), np.linalg.norm(rest - [1.0, 0.0], axis=1)
    )
    assert turned[3, 0] < 1.1  # counter-clockwise: the top corner moves back
    pts = drawing.load_points([[0.1, 0.2, 0.0], [np.nan] * 3])
    assert pts[0].tolist() == [1.1, 0.2] and np.isnan(pts[1]).all()


def test_deformed_shapes_and_fe_at() -> None:
    lines, outlines, poses = drawing.deformed([[0.0, 5.0, 0.0]], n_points=11)
    assert lines.shape == (1, 2, 11, 2) and outlines.shape == (1, 5, 2)
    np.testing.assert_allclose(lines[0, :, 0], [[0, pub.HALF_WIDTH], [0, -pub.HALF_WIDTH]])
    np.testing.assert_allclose(outlines[0], drawing.stage_outline(poses[0]))
    fe = drawing.fe_at(S, [[0.0, 5.0, 0.0], [1.0, 5.0, 0.0], [-10.0, -20.0, -3.0]])
    row = pub.sweep_line(0.0, 0.0)[pub.A_Y_LEVELS == 5.0][0]
    assert fe[0, :2].tolist() == row[3:5].tolist() and np.isnan(fe[1]).all()
    assert np.isfinite(fe[2]).all()  # a mirrored corner, under the couple it really carries


# --- the claims' rules ----------------------------------------------------------------------


def _verdict(claim_id: str, values: dict[str, object]) -> str:
    return claims.evaluate(
        claimlist.claim(claim_id), {k: {"value": v} for k, v in values.items()}
    ).word


def test_the_bounds_follow_from_poisson_and_the_claims_read_them() -> None:
    assert cmp.PLATE_BOUND == pytest.approx(0.0989, abs=1e-4)
    assert cmp.SHORTENING_BOUND == pytest.approx(0.2076, abs=1e-4)
    assert cmp.STAGE_CENTRE_OFFSET == pytest.approx(0.1)
    bound = "ours.parallelogram.plate_bound"
    assert _verdict(bound, {"excess.abs_max_pct": [20.0, 9.8, 9.8]}) == claims.HOLDS
    assert _verdict(bound, {"excess.abs_max_pct": [21.0, 9.8, 30.0]}) == claims.MIXED
    more = "ours.parallelogram.more_compliant"
    assert _verdict(more, {"excess.uy_pct": [0.5, 5], "excess.ux_pct": [-1, 9]}) == claims.MIXED
    small = "ours.parallelogram.phi_small_loads"
    assert _verdict(small, {"small.phi_worst_share_pct": 12.0}) == claims.DOES_NOT_HOLD
    assert _verdict(small, {"small.phi_worst_share_pct": 3.4}) == claims.HOLDS
    stretch = "ours.parallelogram.stretch_turns_stage"
    assert _verdict(stretch, {"couple.median_rel_pct": [3.0, 90.0]}) == claims.HOLDS
    assert _verdict(stretch, {"couple.median_rel_pct": [3.0, 40.0]}) == claims.MIXED
    point = "ours.parallelogram.load_point"
    assert _verdict(point, {"load_point.median_miss_rad": [2e-5, 1e-5]}) == claims.DOES_NOT_HOLD
    assert {c.page for c in claimlist.CLAIMS.values() if "ours.parallelogram." in c.id} == {
        "beyond_hexflex"
    }
