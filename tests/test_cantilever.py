"""The non-linear solver on problems with known answers: the elastica cantilever and rigid motion.

The FE side goes through the HexFlex's own code path (``NonlinearSolver`` with ``SVKTangent``
and CHOLMOD) on :class:`mechlib.hexflex.studies.cantilever.Cantilever`.
"""

import math

import numpy as np
import pytest
from scipy.integrate import solve_bvp

from mechlib.fe.boxmesh import box_hexahedra
from mechlib.fe.nonlinear import NonlinearSolver
from mechlib.fe.svk_tangent import SVKTangent
from mechlib.hexflex.studies.cantilever import ELASTICA_TOL, Cantilever
from mechlib.hexflex.studies.elastica import MAX_ALPHA, elastica_tip

#: Mattiasson (1981), "Numerical results from large deflection beam and frame problems analysed
#: by means of elliptic integrals", Int. J. Numer. Meth. Eng. 17(1) 145–153, the cantilever under
#: a dead end load at PL²/EI = 1: δ/L, (L − x_tip)/L, θ₀ [rad], five decimals, as commonly quoted
#: (the paper itself was not at hand: the closed form, checked against the BVP below, gives them
#: to the last digit).
MATTIASSON_ALPHA_1 = (0.30172, 0.05643, 0.46135)
#: Half a unit in the table's last decimal.
TABLE_TOL = 5e-6
#: Bisshopp & Drucker (1945), Q. Appl. Math. 3(3) 272–275, at PL²/EI = 3: δ/L ≈ 0.60 (as quoted,
#: two decimals, by MOOSE's large-rotation shell test, idaholab/moose).
BISSHOPP_DRUCKER_ALPHA_3 = 0.60
BISSHOPP_DRUCKER_TOL = 5e-3
#: The closed form against SciPy's collocation BVP solver (its tolerance 1e-10).
BVP_TOL = 1e-7
FE_TOL = ELASTICA_TOL
#: The same with ν = 0 (no Poisson restraint at the clamp): what is left is shear, +0.02 % in δ
#: (Timoshenko's PL/κGA: +0.024 %), and no rotation change; 128 × 1 × 1 elements: +0.020…0.032 %,
#: +0.042…0.062 %, +0.0003…0.006 %; the default mesh within 0.010 %, 0.019 %, 0.005 % of it.
FE_TOL_NO_POISSON = (0.0005, 0.001, 0.0002)
#: Rigid rotation: ‖internal force‖ / ‖K u‖ (round-off of the TL residual; measured 7e-14).
RIGID_TOL = 1e-11
#: A small homogeneous stretch: the TL internal force equals K u to first order (relative
#: difference ≈ the strain, 1e-6).
STRETCH = 1e-6
ROTATION_RAD = 0.1


def _elastica_bvp(alpha: float) -> tuple[float, float, float]:
    """δ/L, shortening/L, θ₀ from θ'' + α cos θ = 0, θ(0) = 0, θ'(1) = 0, with x, y integrated
    along (x' = cos θ, y' = sin θ) — independent of the elliptic-integral closed form."""

    def rhs(s, y):
        theta, dtheta = y[0], y[1]
        return np.vstack([dtheta, -alpha * np.cos(theta), np.cos(theta), np.sin(theta)])

    def bc(ya, yb):
        return np.array([ya[0], yb[1], ya[2], ya[3]])

    s = np.linspace(0.0, 1.0, 201)
    guess = np.vstack([alpha * (s - s**2 / 2), alpha * (1 - s), s, alpha * s**2 / 2])
    sol = solve_bvp(rhs, bc, s, guess, tol=1e-10, max_nodes=100_000)
    assert sol.success, sol.message
    theta0, _, x1, z1 = sol.y[:, -1]
    return z1, 1.0 - x1, theta0


# the elastica reference ------------------------------------------------------------------------
@pytest.mark.parametrize("alpha", [0.25, 1.0, 2.0, 4.0])
def test_elastica_closed_form_equals_bvp(alpha: float) -> None:
    np.testing.assert_allclose(elastica_tip(alpha), _elastica_bvp(alpha), rtol=BVP_TOL)


def test_elastica_against_tables() -> None:
    np.testing.assert_allclose(elastica_tip(1.0), MATTIASSON_ALPHA_1, rtol=0, atol=TABLE_TOL)
    deflection = elastica_tip(3.0).deflection
    assert abs(deflection - BISSHOPP_DRUCKER_ALPHA_3) <= BISSHOPP_DRUCKER_TOL


def test_elastica_small_load_limit() -> None:
    alpha = 1e-3  # δ/L = α/3, θ₀ = α/2, shortening = α²/15 (linear theory), up to O(α²)
    tip = elastica_tip(alpha)
    np.testing.assert_allclose(tip, (alpha / 3, alpha**2 / 15, alpha / 2), rtol=1e-5)
    assert elastica_tip(0.0) == (0.0, 0.0, 0.0)


@pytest.mark.parametrize("alpha", [-0.1, MAX_ALPHA + 0.1, math.nan, math.inf])
def test_elastica_rejects_bad_alpha(alpha: float) -> None:
    with pytest.raises(ValueError, match="alpha"):
        elastica_tip(alpha)


# the FE model ----------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def beam() -> Cantilever:
    return Cantilever()


@pytest.fixture(scope="module")
def solver(beam: Cantilever) -> NonlinearSolver:
    return NonlinearSolver(beam)


def _relative_to_elastica(beam: Cantilever, solver: NonlinearSolver, alpha: float) -> np.ndarray:
    fe_tip, stats = beam.solve(alpha, solver=solver)
    assert stats.residual <= 1e-6
    return np.array(fe_tip) / np.array(elastica_tip(alpha)) - 1.0


@pytest.mark.parametrize("alpha", [0.25, 1.0, 2.0])
def test_fe_matches_elastica(beam: Cantilever, solver: NonlinearSolver, alpha: float) -> None:
    relative = _relative_to_elastica(beam, solver, alpha)
    assert np.all(np.abs(relative) <= FE_TOL), f"alpha = {alpha}: relative {relative}"


def test_fe_matches_elastica_without_poisson() -> None:
    beam = Cantilever(poisson=0.0)
    solver = NonlinearSolver(beam)
    for alpha in (0.25, 1.0, 2.0):
        relative = _relative_to_elastica(beam, solver, alpha)
        assert np.all(np.abs(relative) <= FE_TOL_NO_POISSON), f"alpha = {alpha}: {relative}"


def test_fe_independent_of_load_steps(beam: Cantilever, solver: NonlinearSolver) -> None:
    one, _ = beam.solve(2.0, steps=1, solver=solver)
    three, _ = beam.solve(2.0, steps=3, solver=solver)
    np.testing.assert_allclose(one, three, rtol=1e-5)  # hyperelastic: no path dependence


def test_linear_tangent_is_the_assembled_stiffness(beam: Cantilever) -> None:
    tangent = SVKTangent(beam).matrix(np.zeros(beam.n_dofs))
    stiffness = beam.assembled_stiffness()
    assert abs(tangent - stiffness).max() <= 1e-12 * abs(stiffness).max()


def test_end_load_is_consistent(beam: Cantilever) -> None:
    load = beam.load_vectors()[:, 0].reshape(-1, 3)
    np.testing.assert_allclose(load.sum(axis=0), [0.0, 0.0, 1.0], atol=1e-14)
    # one Q2 face: Lagrange weights of a uniform traction, corner : mid-side : centre = 1 : 4 : 16
    assert sorted(np.unique(np.round(36 * load[load[:, 2] != 0, 2], 12))) == [1.0, 4.0, 16.0]


def _rigid_motion(beam: Cantilever, angle: float, axis, shift) -> np.ndarray:
    """Reduced displacements u = (R − I) X + t of a rigid motion on every node (a floating
    model: every node free), R by Rodrigues' formula."""
    n = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
    cross = np.array([[0.0, -n[2], n[1]], [n[2], 0.0, -n[0]], [-n[1], n[0], 0.0]])
    rot = np.eye(3) + np.sin(angle) * cross + (1.0 - np.cos(angle)) * cross @ cross
    dofs = beam.fe.eq.reshape(-1, 3)
    assert np.all(dofs >= 0)
    u = np.empty(beam.n_dofs)
    u[dofs.ravel()] = (beam.fe.coors @ (rot - np.eye(3)).T + np.asarray(shift)).ravel()
    return u


def test_rigid_rotation_gives_no_internal_force() -> None:
    free = Cantilever(n_length=4, clamped=False)
    tangent = SVKTangent(free)
    stiffness = free.assembled_stiffness()
    u = _rigid_motion(free, ROTATION_RAD, (1.0, 2.0, 3.0), (0.3, -0.2, 0.1))
    force = tangent.internal_force(u)
    linear = stiffness @ u  # not zero: the linear strain of a finite rotation
    assert np.linalg.norm(force) <= RIGID_TOL * np.linalg.norm(linear)
    assert np.linalg.norm(linear) >= 1e-3 * abs(stiffness).max() * np.abs(u).max()
    # a deformation is not missed: a small stretch gives K u to first order
    stretch = np.empty(free.n_dofs)
    stretch[free.fe.eq] = STRETCH * free.fe.coors.ravel()
    np.testing.assert_allclose(
        tangent.internal_force(stretch), stiffness @ stretch, rtol=0,
        atol=10 * STRETCH * np.abs(stiffness @ stretch).max(),
    )  # fmt: skip


def test_floating_model_refuses_to_solve() -> None:
    with pytest.raises(ValueError, match="clamped"):
        Cantilever(n_length=2, clamped=False).back_substitute(np.zeros(1))


@pytest.mark.parametrize(
    ("kwargs", "name"),
    [
        ({"depth": 10.0}, "depth"),
        ({"width": 1.0}, "width"),
        ({"n_length": 1}, "n_length"),
        ({"n_section": 9}, "n_section"),
        ({"poisson": 0.5}, "poisson"),
        ({"young": -1.0}, "young"),
    ],
)
def test_bad_beam_is_refused(kwargs: dict, name: str) -> None:
    with pytest.raises(ValueError, match=name):
        Cantilever(**kwargs)


def test_bad_load_is_refused(beam: Cantilever) -> None:
    with pytest.raises(ValueError, match="end load"):
        beam.check_forces([1.01 * beam.load_for(MAX_ALPHA)])
    with pytest.raises(ValueError, match="alpha"):
        beam.solve(MAX_ALPHA + 1.0)
    with pytest.raises(ValueError, match="clamp_size"):
        box_hexahedra((10.0, 1.0, 1.0), (2, 1, 1), clamp_size=6.0)
