"""Invariants of a HexFlex compliance (three-fold symmetry, Eq 8's zero pattern, reciprocity)
and the tilt-to-lift ratio that rules out a stage hung on three hinged links."""

from __future__ import annotations

import numpy as np

from mechlib.hexflex.geometry import TAB_ANGLES_DEG, TAB_D1_SIGNS

#: Pose rows and force columns that are in-plane (x, y, θz; D1) and out-of-plane (z, θx, θy; D2).
IN_PLANE_ROWS, OUT_ROWS = (0, 1, 5), (2, 3, 4)
D1_COLS, D2_COLS = (0, 2, 4), (1, 3, 5)
#: (row, column) of the zeros that the part's mirror symmetry about T1's axis adds: T1's loads
#: (along x and z) cause no y translation nor θy rotation (y←T1D1, θy←T1D2).
MIRROR_ZEROS: tuple[tuple[int, int], ...] = ((1, 0), (4, 1))
#: Largest relative defects for the model's invariants to hold: far above the round-off of a
#: direct solve in double precision, far below any modelling error.
SYMMETRY_TOL = 1e-6
ZERO_PATTERN_TOL = 1e-6
RECIPROCITY_TOL = 1e-9
#: Largest pose → forces → pose error [µm, µrad] of the FE model's own inverse (round-off).
ROUNDTRIP_TOL = 1e-6
#: θx / z of a rigid stage carried at three hinged joints on a circle of radius ρ, times ρ:
#: lifting one joint by z₁ lifts the centre by z₁/3 and tilts the stage by z₁/(1.5 ρ).
HINGED_TILT_FACTOR = 2.0
MM_PER_M = 1e3


def rotate_pose(pose: np.ndarray, angle_deg: float) -> np.ndarray:
    """Pose (6,) of the stage rotated about z: translations and rotations turn as vectors."""
    a = np.deg2rad(angle_deg)
    r = np.array([[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1]])
    return np.r_[r @ pose[:3], r @ pose[3:]]


def symmetry_prediction(compliance: np.ndarray) -> np.ndarray:
    """Columns of T2 and T3 predicted from T1's by rotating it to their tabs (with D1 signs)."""
    c = np.asarray(compliance, dtype=float)
    out = c.copy()
    for k in (1, 2):
        angle = TAB_ANGLES_DEG[k] - TAB_ANGLES_DEG[0]
        sign = TAB_D1_SIGNS[k] / TAB_D1_SIGNS[0]
        out[:, 2 * k] = sign * rotate_pose(c[:, 0], angle)
        out[:, 2 * k + 1] = rotate_pose(c[:, 1], angle)
    return out


def symmetry_defect(compliance: np.ndarray) -> float:
    """max |C − rotated T1 columns| relative to max |C| in each row group (scale-free)."""
    c = np.asarray(compliance, dtype=float)
    d = np.abs(c - symmetry_prediction(c))
    scale = np.abs(c).max(axis=1, keepdims=True)
    return float((d / scale).max())


def zero_pattern_defect(compliance: np.ndarray) -> float:
    """Largest entry of Eq 8's zero pattern relative to its row's largest entry: out-of-plane
    responses to D1, in-plane responses to D2 (mid-plane symmetry) and :data:`MIRROR_ZEROS`."""
    c = np.asarray(compliance, dtype=float)
    scale = np.abs(c).max(axis=1)
    zeros = [(i, j) for i in OUT_ROWS for j in D1_COLS]
    zeros += [(i, j) for i in IN_PLANE_ROWS for j in D2_COLS] + list(MIRROR_ZEROS)
    return float(max(abs(c[i, j]) / scale[i] for i, j in zeros))


def reciprocity_defect(port_compliance: np.ndarray) -> float:
    """max |P − Pᵀ| / max |P| of a square port compliance: 0 for a linear elastic structure
    (Maxwell–Betti)."""
    p = np.asarray(port_compliance, dtype=float)
    if p.ndim != 2 or p.shape[0] != p.shape[1]:
        raise ValueError(f"port_compliance must be a square matrix, got shape {p.shape}")
    return float(np.abs(p - p.T).max() / np.abs(p).max())


def tilt_per_lift(compliance: np.ndarray) -> float:
    """θx←T1D2 / z←T1D2 [rad/m] of a compliance in Eq 8's order and units (µrad/N, µm/N)."""
    c = np.asarray(compliance, dtype=float)
    return float(c[3, 1] / c[2, 1])


def max_hinged_radius(ratio: float) -> float:
    """Largest joint radius ρ [mm] at which a stage on three hinged links reaches a tilt-to-lift
    ``ratio`` [rad/m]: such a stage has θx / z ≤ ``HINGED_TILT_FACTOR`` / ρ.

    A rigid stage settles in the plane of its three joints (120° apart): lifting one joint by z₁
    lifts the centre by z₁/3 and tilts the stage by z₁/(1.5 ρ), so θx / z = 2/ρ.
    """
    if not ratio > 0:
        raise ValueError(f"ratio must be > 0 rad/m, got {ratio}")
    return HINGED_TILT_FACTOR / ratio * MM_PER_M
