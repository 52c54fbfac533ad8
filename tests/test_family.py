"""Members of the Eq 8 family: the beam model's reach of Eq 8 at fixed plate thicknesses."""

import json
from pathlib import Path

import numpy as np
import pytest

from mechlib import published as pub
from mechlib.hexflex import family
from mechlib.hexflex import identify as ident
from mechlib.hexflex.geometry import HexFlexGeometry

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
