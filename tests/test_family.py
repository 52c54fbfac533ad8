"""Members of the Eq 8 family: the beam model's reach of Eq 8 at fixed plate thicknesses."""

import json
from pathlib import Path

import numpy as np
import pytest

from mechlib import published as pub
from mechlib.hexflex import identify as ident
from mechlib.hexflex.geometry import HexFlexGeometry
from mechlib.hexflex.studies import family

REFS = Path(__file__).parent / "references" / "hexflex_model.json"


def _identified() -> HexFlexGeometry:
    values = json.loads(REFS.read_text())["values"]
    dims = {k.split(".", 1)[1]: v["value"] for k, v in values.items() if k.startswith("geometry.")}
    return HexFlexGeometry.from_dict(dims)


def test_the_beam_model_reaches_eq8_at_thin_plates_only():
    # at the identified member's own thickness the five in-plane dimensions can meet Eq 8;
    # a 1/8-inch plate would need flexures longer or narrower than the layout allows
    target = ident.target_values(pub.EQ8_ST)
    g = _identified()
    reach = family.frame_reach(target, g, [g.thickness, 3.175])
    assert reach[0] < 0.1
    assert reach[1] > 50.0


def test_a_thickness_out_of_bounds_is_refused_before_any_model():
    with pytest.raises(ValueError, match=r"thickness \[mm\].*6"):
        family.check_thickness(6.0)
    target = ident.target_values(pub.EQ8_ST)
    with pytest.raises(ValueError, match="thickness"):
        family.frame_reach(target, _identified(), [0.1])
    assert np.isfinite(family.check_thickness(0.45))


def _fake_identify(miss: float):
    """An :func:`ident.identify` stand-in (no FE model): it returns its start with every
    magnitude ``miss`` (relative) off the target, raising as identify does when that is beyond
    tol, and keeps the settings it was given."""
    seen = {}

    def fake(start, target, free, compliance_fn, surrogate_fn, max_evaluations, tol, **steer):
        seen.update(max_evaluations=max_evaluations, tol=tol, thickness=start.thickness)
        assert steer == {"jacobian": "secant", "log_quantum": family.fit_log_quantum(tol)}
        assert list(free) == list(family.FE_FREE)
        t = np.asarray(target, dtype=float)
        hist = np.zeros((max_evaluations, len(free) + 4))
        fit = ident.Identification(start, t * (1 + miss), t, max_evaluations, hist)
        if abs(np.log1p(miss)) > tol:
            raise ident.IdentificationError(f"misfit {abs(np.log1p(miss)):.3g} > tol {tol:g}", fit)
        return fit

    return fake, seen


def test_a_member_that_misses_eq8_beyond_tol_is_refused_by_name(monkeypatch):
    target = ident.target_values(pub.EQ8_ST)
    g = _identified()
    fake, seen = _fake_identify(miss=2e-3)  # |log(1.002)| ≈ 2.0e-3 > tol
    monkeypatch.setattr(ident, "identify", fake)
    with pytest.raises(ident.IdentificationError, match=r"thickness 0\.45 mm: misfit 0\.002 > tol"):
        family.identify_member(target, g, 0.45, 0.5, max_evaluations=3, tol=1e-3)
    assert seen == {"max_evaluations": 3, "tol": 1e-3, "thickness": 0.45}
    # within tol the member is kept, with its worst relative error in percent
    fake, _ = _fake_identify(miss=-5e-4)
    monkeypatch.setattr(ident, "identify", fake)
    member = family.identify_member(target, g, 0.45, 0.5, max_evaluations=3, tol=1e-3)
    assert member.worst_pct == pytest.approx(0.05)
    assert member.geometry.thickness == 0.45 and member.evaluations == 3


def test_member_thicknesses_exclude_the_identified_one_and_repeats():
    assert family.check_member_thicknesses([0.45, 0.35], 0.6416) == [0.45, 0.35]
    with pytest.raises(ValueError, match=r"identified member's thickness 0\.6416"):
        family.check_member_thicknesses([0.45, 0.6416], 0.6416)
    with pytest.raises(ValueError, match="must not repeat"):
        family.check_member_thicknesses([0.45, 0.45], 0.6416)
    with pytest.raises(ValueError, match=r"thickness \[mm\]"):
        family.check_member_thicknesses([0.1], 0.6416)
    for bad in ([], 0.45, "0.45", None, [[0.45]]):
        with pytest.raises(ValueError, match="at least one other member"):
            family.check_member_thicknesses(bad, 0.6416)


def test_mesh_fractions_are_checked_as_decreasing_and_named_as_given():
    assert family.check_mesh_fractions([0.5, 0.25]) == [0.5, 0.25]
    with pytest.raises(ValueError, match=r"strictly decreasing .*got \[0\.25, 0\.5\]"):
        family.check_mesh_fractions([0.25, 0.5])
    with pytest.raises(ValueError, match=r"mesh_fractions .*got '\[0\.5, 0\.35\]'"):
        family.check_mesh_fractions("[0.5, 0.35]")  # a list passed as text
    with pytest.raises(ValueError, match=r"in \[0\.1, 1\.0\], got \[0\.5, 0\.05\]"):
        family.check_mesh_fractions([0.5, 0.05])
