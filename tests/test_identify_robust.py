"""The FE identification converges to one geometry whatever the processor's round-off.

The FE model is stood in for by the beam model with shear (milliseconds), the surrogate that
steers the steps by the Euler–Bernoulli beam model: their sensitivities differ as the FE's and
the beam model's do. Round-off on another processor is imitated by relative perturbations of
1e-6 of the "FE" magnitudes, of the surrogate's sensitivities, or of the start.
"""

import numpy as np
import pytest

from mechlib import published as pub
from mechlib.hexflex import frame as fr
from mechlib.hexflex import identify as ident
from mechlib.hexflex.geometry import HexFlexGeometry
from mechlib.hexflex.studies import family

TARGET = ident.target_values(pub.EQ8_ST)
START = HexFlexGeometry(
    stage_radius=25.0, tab_half_width=3.0, tab_outer=45.0, beam_radius=22.0, beam_width=0.276,
    beam_length=11.72, radial_width=0.276, radial_length=3.95, thickness=0.505,
)  # fmt: skip
TOL = 1e-3
NOISE = 1e-6


def _noisy(fn, seed: int, noise: float = NOISE):
    """``fn`` with every entry off by a relative ``noise`` that depends on the geometry and
    seed."""

    def out(g: HexFlexGeometry) -> np.ndarray:
        key = int(abs(hash(tuple(np.round(list(g.as_dict().values()), 12)))) % 2**32)
        rng = np.random.default_rng([seed, key])
        return fn(g) * (1 + noise * rng.standard_normal((6, 6)))

    return out


def _noisy_sensitivity(seed: int):
    """:func:`ident.log_sensitivity` with every entry off by a seeded relative 1e-6."""
    rng = np.random.default_rng(seed)
    exact = ident.log_sensitivity

    def out(*args, **kwargs) -> np.ndarray:
        jac = exact(*args, **kwargs)
        return jac * (1 + NOISE * rng.standard_normal(jac.shape))

    return out


def _fe(g: HexFlexGeometry) -> np.ndarray:
    return fr.hexflex_frame_compliance(g, shear=True) * np.array([1.01, 0.98, 1.02, 1, 1, 0.99])


def _surrogate(g: HexFlexGeometry) -> np.ndarray:
    return fr.hexflex_frame_compliance(g, shear=False)


def _identify(start, free, fe=_fe, surrogate=_surrogate):
    return ident.identify(start, TARGET, free, fe, surrogate, tol=TOL)


@pytest.mark.parametrize("free", [("thickness", "beam_width", "beam_length", "radial_length"),
                                  family.FAMILY_FREE])  # fmt: skip
def test_identification_converges_to_one_geometry_under_round_off(free, monkeypatch) -> None:
    start = START.replace(thickness=0.45) if "thickness" not in free else START
    start, _ = fr.prefit(TARGET, start, free, shear=False)
    base = _identify(start, free)
    assert np.abs(np.log(base.achieved / TARGET)).max() <= TOL
    assert 2 <= base.n_evaluations < ident.MAX_EVALUATIONS
    dims = np.array([getattr(base.geometry, n) for n in free])
    runs = {
        "FE magnitudes": _identify(start, free, fe=_noisy(_fe, 1)),
        "start": _identify(start.replace(**{free[0]: getattr(start, free[0]) * (1 + NOISE)}), free),
    }
    monkeypatch.setattr(ident, "log_sensitivity", _noisy_sensitivity(2))
    runs["surrogate sensitivities"] = _identify(start, free)
    for what, fit in runs.items():
        assert np.abs(np.log(fit.achieved / TARGET)).max() <= TOL, what
        assert fit.n_evaluations == base.n_evaluations, what  # the same path
        # what the pages compute from a member holds within rtol 1e-3 if its dimensions hold
        # within 1e-4 (measured: the departures move up to 3x a change of the dimensions); a
        # perturbation of 1e-6 (a million times FE round-off) moved them by up to 1.02e-5
        moved = np.abs(np.array([getattr(fit.geometry, n) for n in free]) / dims - 1).max()
        assert moved <= 1e-4, f"{what}: the identified dimensions moved by {moved:.2e}"


def test_prefit_is_unique_where_the_magnitudes_leave_a_dimension_free() -> None:
    free = family.FAMILY_FREE
    g = START.replace(thickness=0.45)
    a, achieved = fr.prefit(TARGET, g, free)
    b, _ = fr.prefit(TARGET, g.replace(beam_length=g.beam_length * (1 + NOISE)), free)
    np.testing.assert_allclose(achieved, TARGET, rtol=1e-5)
    for n in free:  # a start moved by 1e-6 moves the fit by about as much, not by the path
        assert getattr(b, n) == pytest.approx(getattr(a, n), rel=3 * NOISE)


def _family_member(monkeypatch, fe, prefit_shift: float = 0.0) -> family.Member:
    """:func:`family.identify_member` at 0.45 mm with ``fe`` standing in for the FE model and
    the beam model's pre-fit moved by ``prefit_shift`` [mm] (its least squares' own spread)."""
    exact = fr.prefit

    def prefit(*args, **kwargs):
        g, achieved = exact(*args, **kwargs)
        return g.replace(**{n: getattr(g, n) + prefit_shift for n in family.FAMILY_FREE}), achieved

    monkeypatch.setattr(family.cc, "compliance_maker", lambda specs, cache_dir=None: fe)
    monkeypatch.setattr(family.frame, "prefit", prefit)
    return family.identify_member(TARGET, START, 0.45, 0.5, tol=TOL)


def test_a_family_member_is_the_same_under_another_processors_round_off(monkeypatch) -> None:
    """The member's FE fit reads misfits to ``FIT_LOG_QUANTUM`` and starts from the pre-fit on a
    1 µm grid: FE magnitudes off by a relative 1e-6 (200 times the 5e-9 measured between BLAS
    kernels; without the quantum this path changes) and a pre-fit off by 3e-7 mm (its least
    squares' spread between kernels) leave the member bit for bit unchanged."""
    base = _family_member(monkeypatch, _fe_off)
    assert np.abs(np.log(base.achieved / TARGET)).max() <= TOL
    assert 4 <= base.evaluations < ident.MAX_EVALUATIONS  # secant updates steer it
    start, _ = fr.prefit(TARGET, START.replace(thickness=0.45), family.FAMILY_FREE)
    assert base.geometry.radial_width == round(start.radial_width, family.START_DECIMALS)
    for shift, fe in ((3e-7, _fe_off), (0.0, _noisy(_fe_off, 3, noise=1e-6))):
        other = _family_member(monkeypatch, fe, shift)
        assert other.geometry == base.geometry, shift
        assert other.evaluations == base.evaluations


def _fe_off(g: HexFlexGeometry) -> np.ndarray:
    """A stand-in FE whose sensitivities differ from the surrogate's by tens of percent: every
    magnitude scaled by (beam width)^0.8 (beam length)^-0.6."""
    return _fe(g) * (g.beam_width / 0.3) ** 0.8 * (g.beam_length / 12.0) ** -0.6


def test_secant_steps_converge_where_the_surrogate_is_off() -> None:
    free = list(family.FE_FREE)
    start, _ = fr.prefit(TARGET, START.replace(thickness=0.45), family.FAMILY_FREE, shear=False)
    fits = {
        j: ident.identify(start, TARGET, free, _fe_off, _surrogate, tol=1e-5, jacobian=j)
        for j in ident.JACOBIANS
    }
    for j, fit in fits.items():
        assert np.abs(np.log(fit.achieved / TARGET)).max() <= 1e-5, j
    assert fits["secant"].n_evaluations < fits["surrogate"].n_evaluations


def test_each_secant_jacobian_maps_the_last_step_onto_the_misfits_change(monkeypatch) -> None:
    free = list(family.FE_FREE)
    start, _ = fr.prefit(TARGET, START.replace(thickness=0.45), family.FAMILY_FREE, shear=False)
    used, pinv = [], np.linalg.pinv
    monkeypatch.setattr(np.linalg, "pinv", lambda a: (used.append(a.copy()), pinv(a))[1])
    fit = ident.identify(start, TARGET, free, _fe_off, _surrogate, tol=1e-5, jacobian="secant")
    x = np.log(fit.history[:, : len(free)])
    r = np.log(fit.history[:, len(free) :] / TARGET)
    assert len(used) == fit.n_evaluations - 1 >= 3
    for k in range(1, len(used)):  # Broyden: J_k (x_k - x_{k-1}) = r_k - r_{k-1}
        np.testing.assert_allclose(used[k] @ (x[k] - x[k - 1]), r[k] - r[k - 1], atol=1e-12)


def test_bad_steering_settings_are_refused_by_name() -> None:
    with pytest.raises(ValueError, match="jacobian"):
        ident.identify(START, TARGET, ["beam_width"], _fe, _surrogate, jacobian="exact")
    with pytest.raises(ValueError, match="log_quantum"):
        ident.identify(START, TARGET, ["beam_width"], _fe, _surrogate, tol=1e-3, log_quantum=2e-3)
    with pytest.raises(ValueError, match="fe_free"):
        family.identify_member(TARGET, START, 0.45, 0.5, fe_free=["thickness"])


def test_rounded_misfits_stop_the_fit_only_within_tol() -> None:
    """A misfit of 1.04e-3 rounds to 1.0e-3 = tol on a 1e-4 quantum: not converged (the true
    misfit is above tol), whereas 0.94e-3 is."""
    for miss, converges in ((1.04e-3, False), (0.94e-3, True)):

        def fe(g, miss=miss):
            c = np.zeros((6, 6))
            for (i, j, sign), t in zip(ident.TARGET_ENTRIES, TARGET, strict=True):
                c[i, j] = sign * t * np.exp(miss)
            return c

        def run(fe=fe):
            return ident.identify(START, TARGET, ["beam_width"], fe, _surrogate, tol=1e-3,
                                  max_evaluations=2, log_quantum=1e-4)  # fmt: skip

        if converges:
            assert run().n_evaluations == 1
        else:
            with pytest.raises(ident.IdentificationError, match="did not converge"):
                run()
