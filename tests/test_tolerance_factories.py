"""Tolerances made from a notebook's parameter: the same floats as the literals they replace."""

from __future__ import annotations

import pytest

from mechlib.reporting import plans
from mechlib.reporting.records import Recorder
from mechlib.reporting.tolerances import grid_share


def test_a_grid_share_allows_ten_points_of_the_grid() -> None:
    assert grid_share(400).atol == 6.25e-05 == 10 / 400**2
    assert grid_share(3).atol == 10 / 9
    assert grid_share(400).rtol == 0.0
    for bad in (0, -5, 2.5, True):
        with pytest.raises(ValueError, match=f"points must be an integer >= 1, got {bad!r}"):
            grid_share(bad)


def test_the_fivebar_window_shares_take_their_tolerance_from_the_grid() -> None:
    rec = Recorder(
        "fivebar_identification",
        paste=lambda name, value: None,
        plan=plans.load("fivebar_identification"),
    )
    rec.value("fig10.window_shares", [0.3, 0.25], context={"fig10_points": 200})
    assert rec.values["fig10.window_shares"]["atol"] == 10 / 200**2
    assert rec.glued["fig10_working"] == {"key": "fig10.window_shares", "index": 1}
