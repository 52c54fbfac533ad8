"""Stage pose at finite rotation (mechlib.fe.finite_pose) against closed-form rigid motions.

Point sets stand in for the stage's nodes: a planar one (shell mesh, z = 0), the same planar set
on two layers z = ±h (Q2 vertices) and an anisotropic solid one; all have their centroid away
from the stage centre ``C`` so that the translation of the centre is tested, not the centroid's.
"""

import numpy as np
import pytest

from mechlib.fe import finite_pose as fp
from mechlib.fe.pose import POSE_SCALE, fit_operator

SEED = 20100101
N_POINTS = 40
HALF_THICKNESS = 0.25  # [mm]
EXTENT = np.array([12.0, 7.0, 2.0])  # anisotropic box of the solid point set [mm]
C = np.array([0.4, -0.3, 0.0])  # stage centre, away from the centroids [mm]
TILT = 0.05  # the non-linear runs' largest tilt [rad]
EXACT = 1e-12  # round-off bound in mm and rad (coordinates ~10 mm, angles ≤ 0.3 rad)
ORDER2_RATIO = (3.6, 4.4)  # an O(θ²) difference shrinks ~4× when θ halves
SMALL_FIELD = 1e-4  # scale ε of a non-rigid displacement field [mm] (the linear runs' order)
# relative gap between the small fit and the registration of such a field: O(ε / size) ≈ 1e-5
# here; any other weighting of the nodes makes it O(1)
LINEAR_AGREEMENT = 1e-4


def _planar(rng: np.random.Generator) -> np.ndarray:
    xy = rng.uniform(-1.0, 1.0, (N_POINTS, 2)) * EXTENT[:2]
    return np.c_[xy, np.zeros(N_POINTS)]


def _layered(rng: np.random.Generator) -> np.ndarray:
    p, offset = _planar(rng), np.array([0.0, 0.0, HALF_THICKNESS])
    return np.r_[p + offset, p - offset]


def _solid(rng: np.random.Generator) -> np.ndarray:
    return rng.uniform(-1.0, 1.0, (N_POINTS, 3)) * EXTENT + [1.0, 0.5, 0.2]


SETS = {"planar": _planar, "layered": _layered, "solid": _solid}


def points(kind: str) -> np.ndarray:
    return SETS[kind](np.random.default_rng(SEED))


def rx(a: float) -> np.ndarray:
    c, s = np.cos(a), np.sin(a)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def ry(a: float) -> np.ndarray:
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def rz(a: float) -> np.ndarray:
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def rodrigues(rotvec: np.ndarray) -> np.ndarray:
    """Rotation matrix of a rotation vector (axis × angle), written out."""
    angle = np.linalg.norm(rotvec)
    k = np.cross(np.eye(3), rotvec / angle)  # the axis's cross-product matrix
    return np.eye(3) + np.sin(angle) * k + (1.0 - np.cos(angle)) * k @ k


def motion(x: np.ndarray, rot: np.ndarray, shift: np.ndarray) -> np.ndarray:
    """Displacements of ``x`` rotating by ``rot`` about ``C`` and then translating by ``shift``."""
    return (x - C) @ rot.T + C + shift - x


def si(pose: np.ndarray) -> np.ndarray:
    """Pose back in mm and rad."""
    return pose / POSE_SCALE


@pytest.mark.parametrize("kind", SETS)
def test_pure_translation_is_the_same_in_every_convention(kind):
    x = points(kind)
    shift = np.array([0.03, -0.02, 0.05])
    poses = fp.finite_poses(x, np.broadcast_to(shift, x.shape), C)
    for name in fp.CONVENTIONS:
        np.testing.assert_allclose(si(poses[name]), np.r_[shift, 0, 0, 0], rtol=0, atol=EXACT)


@pytest.mark.parametrize("kind", ["planar", "layered"])
def test_rotation_about_the_normal_small_fit_returns_sine(kind):
    """Rotation by φ about the z axis through ``C``: u = (R − I)(X − C).

    Exact: t = 0, rotation vector = Euler = (0, 0, φ). Small fit (LS of u = t + θ × (X − C)):
    with d the points' offsets from their centroid X̄, the z-rotation field's residual at
    θ = (0, 0, sin φ) is (cos φ − 1)(dx, dy, 0), orthogonal to every rotation field when
    Σ dx dz = Σ dy dz = 0 (a plane, or two mirrored layers), so θ = (0, 0, sin φ) and
    t = ū − θ × (X̄ − C) = (cos φ − 1)(X̄ − C).
    """
    x = points(kind)
    phi = TILT
    poses = fp.finite_poses(x, motion(x, rz(phi), np.zeros(3)), C)
    exact = np.r_[0, 0, 0, 0, 0, phi]
    np.testing.assert_allclose(si(poses["rotvec"]), exact, rtol=0, atol=EXACT)
    np.testing.assert_allclose(si(poses["euler_xyz"]), exact, rtol=0, atol=EXACT)
    arm = x.mean(axis=0) - C
    small = np.r_[(np.cos(phi) - 1.0) * arm, 0, 0, np.sin(phi)]
    np.testing.assert_allclose(si(poses["small"]), small, rtol=0, atol=EXACT)
    assert abs(si(poses["small"])[5] - phi) > 1e3 * EXACT  # the sine is not the angle


@pytest.mark.parametrize("kind", SETS)
def test_equal_tilts_euler_xyz_and_rotation_vector_differ_at_second_order(kind):
    """R = Rx(a) Ry(a): intrinsic Euler XYZ angles (a, a, 0) by construction.

    Quaternion product (c, s, 0, 0)(c, 0, s, 0) = (c², cs, cs, s²) with c, s = cos, sin(a/2):
    rotation vector = φ (c, c, s)/√(2c² + s²), φ = 2 atan2(s √(2c² + s²), c²), so its z
    component is ≈ a²/2 (the BCH term θx θy / 2) while Euler θz is 0.
    """
    x = points(kind)
    a = TILT
    shift = np.array([0.01, 0.02, -0.03])
    poses = fp.finite_poses(x, motion(x, rx(a) @ ry(a), shift), C)
    c, s = np.cos(a / 2), np.sin(a / 2)
    norm = np.sqrt(2 * c**2 + s**2)
    phi = 2 * np.arctan2(s * norm, c**2)
    np.testing.assert_allclose(si(poses["euler_xyz"]), np.r_[shift, a, a, 0], rtol=0, atol=EXACT)
    rotvec = np.r_[shift, phi * np.array([c, c, s]) / norm]
    np.testing.assert_allclose(si(poses["rotvec"]), rotvec, rtol=0, atol=EXACT)
    gap = si(poses["rotvec"] - poses["euler_xyz"])[5]
    assert abs(gap - a**2 / 2) < a**3  # second order, with a third-order remainder


@pytest.mark.parametrize("kind", SETS)
def test_random_rigid_motion_is_recovered_exactly(kind):
    rng = np.random.default_rng(SEED + 1)
    x = points(kind)
    rotvec = rng.normal(size=3)
    rotvec *= 0.3 / np.linalg.norm(rotvec)
    shift = rng.normal(scale=0.1, size=3)
    rot = rodrigues(rotvec)
    u = motion(x, rot, shift)
    t, r = fp.register(x, x + u, C)
    np.testing.assert_allclose(t, shift, rtol=0, atol=EXACT)
    np.testing.assert_allclose(r.as_matrix(), rot, rtol=0, atol=EXACT)
    poses = fp.finite_poses(x, u, C)
    np.testing.assert_allclose(si(poses["rotvec"]), np.r_[shift, rotvec], rtol=0, atol=EXACT)
    ex, ey, ez = si(poses["euler_xyz"])[3:]
    np.testing.assert_allclose(rx(ex) @ ry(ey) @ rz(ez), rot, rtol=0, atol=EXACT)  # intrinsic
    assert np.abs(rz(ez) @ ry(ey) @ rx(ex) - rot).max() > 1e3 * EXACT  # not extrinsic


def test_centre_defaults_to_the_origin_like_the_small_fit():
    x = points("solid")
    u = motion(x, rodrigues(np.array([0.02, -0.01, 0.03])), np.array([0.01, 0.0, 0.02]))
    t_origin, _ = fp.register(x, x + u)
    t_c, r = fp.register(x, x + u, C)
    np.testing.assert_allclose(t_origin, t_c + r.apply(-C) + C, rtol=0, atol=EXACT)
    poses = fp.finite_poses(x, u)
    np.testing.assert_allclose(poses["small"], fit_operator(x) @ u.ravel(), rtol=1e-14, atol=0)
    np.testing.assert_allclose(si(poses["rotvec"])[:3], t_origin, rtol=0, atol=EXACT)


@pytest.mark.parametrize("kind", SETS)
def test_small_fit_agrees_with_the_exact_registration_to_second_order(kind):
    x = points(kind)
    axis = np.array([0.6, -0.48, 0.64])  # unit vector, tilts and twist together
    shift = np.array([0.02, -0.01, 0.03])

    def gap(angle: float) -> float:
        u = motion(x, rodrigues(angle * axis), angle / TILT * shift)
        poses = fp.finite_poses(x, u, C)
        return float(np.abs(si(poses["small"] - poses["rotvec"])).max())

    ratio = gap(TILT) / gap(TILT / 2)
    assert ORDER2_RATIO[0] < ratio < ORDER2_RATIO[1]


@pytest.mark.parametrize("kind", SETS)
def test_non_rigid_data_is_fitted_with_equal_weights(kind):
    """The small fit linearises the equal-weight registration: on a tiny non-rigid displacement
    field (scale ε) the two differ by O(ε²), i.e. O(ε / size) relative to the pose, while any
    other weighting of the nodes moves the rotation by O(ε), of the order of the pose itself."""
    x = points(kind)
    noise = np.random.default_rng(SEED + 2).normal(size=x.shape)
    poses = fp.finite_poses(x, SMALL_FIELD * noise, C)
    gap = np.abs(poses["small"] - poses["rotvec"])
    assert np.all(gap < LINEAR_AGREEMENT * np.abs(poses["small"]).max())


def test_many_sets_match_one_at_a_time():
    x = points("layered")
    us = np.stack([motion(x, rx(a) @ rz(-a), np.array([a, 0.0, -a])) for a in (0.01, 0.03)])
    many = fp.finite_poses(x, us, C)
    for i, u in enumerate(us):
        one = fp.finite_poses(x, u, C)
        for name in fp.CONVENTIONS:
            assert one[name].shape == (fp.N_POSE,)
            assert many[name].shape == (len(us), fp.N_POSE)
            np.testing.assert_allclose(many[name][i], one[name], rtol=1e-14, atol=1e-9)


def test_convention_differences_known_answer():
    a = np.array([[0.0, 0, 0, 0, 0, 1], [2.0, 4, 0, 1, 1, 1]])
    b = a + np.array([[0.5, 0, 0, 0, 0, 0], [0.0, -1, 0, 0, 0, 3]])
    d = fp.convention_differences({"a": a, "b": b})
    assert list(d) == ["a vs b"]
    np.testing.assert_array_equal(d["a vs b"]["max_abs"], [0.5, 1, 0, 0, 0, 3])
    np.testing.assert_array_equal(d["a vs b"]["relative"], [0.25, 0.25, np.nan, 0, 0, 1])


def test_convention_differences_of_equal_tilts():
    x = points("planar")
    tilts = (TILT / 2, TILT)
    us = np.stack([motion(x, rx(a) @ ry(a), np.zeros(3)) for a in tilts])
    d = fp.convention_differences(fp.finite_poses(x, us, C))
    assert list(d) == ["small vs rotvec", "small vs euler_xyz", "rotvec vs euler_xyz"]
    gap = d["rotvec vs euler_xyz"]["max_abs"][5] / POSE_SCALE[5]
    assert abs(gap - TILT**2 / 2) < TILT**3


@pytest.mark.parametrize(
    ("args", "name"),
    [
        ((np.zeros((2, 3)), np.zeros((2, 3))), "points"),
        ((np.c_[np.arange(5.0), 2 * np.arange(5.0), np.zeros(5)], np.zeros((5, 3))), "points"),
        ((np.eye(3), np.zeros((4, 3))), "displaced"),
        ((np.eye(3), np.full((3, 3), np.nan)), "displaced"),
        ((np.r_[np.eye(3)[:2], [[np.nan, 0, 0]]], np.zeros((3, 3))), "points"),
        ((np.eye(3), np.eye(3), [0.0, 1.0]), "center"),
    ],
)
def test_register_rejects_bad_input(args, name):
    with pytest.raises(ValueError, match=name):
        fp.register(*args)


@pytest.mark.parametrize(
    ("displacements", "name"),
    [
        (np.zeros((4, 3)), "displacements"),
        (np.zeros((2, 3, 2)), "displacements"),
        (np.zeros(9), "displacements"),
        (np.r_[np.zeros((2, 3)), [[0, np.inf, 0]]], "displacements"),
    ],
)
def test_finite_poses_rejects_bad_input(displacements, name):
    with pytest.raises(ValueError, match=name):
        fp.finite_poses(np.eye(3), displacements)


@pytest.mark.parametrize(
    "poses",
    [
        {"small": np.zeros((2, 6))},
        {"small": np.zeros((2, 6)), "rotvec": np.zeros((3, 6))},
        {"small": np.zeros((2, 6)), "rotvec": np.zeros((2, 5))},
        {"small": np.zeros((2, 6)), "rotvec": np.full((2, 6), np.nan)},
    ],
)
def test_convention_differences_rejects_bad_input(poses):
    with pytest.raises(ValueError, match="poses_by_convention"):
        fp.convention_differences(poses)
