"""ARCHITECTURE.md's drawings are the import graph as ``python -m mechlib.pipeline.housegraph``
draws it now, and the drawing shows the imports the house's rules are about."""

from __future__ import annotations

import pytest

from mechlib.paths import REPO_ROOT
from mechlib.pipeline import housegraph

ARCHITECTURE = REPO_ROOT / "ARCHITECTURE.md"
KNOWN = housegraph.modules()


def test_architecture_carries_the_current_drawings() -> None:
    text = ARCHITECTURE.read_text()
    assert [m[1] for m in housegraph.MARKED.findall(text)] == ["house", "hexflex"]
    # if this fails: .venv/bin/python -m mechlib.pipeline.housegraph --write ARCHITECTURE.md
    assert housegraph.redraw(text, KNOWN) == text


def test_a_stale_drawing_is_redrawn_and_an_unknown_one_refused() -> None:
    stale = "<!-- housegraph hexflex -->\n```mermaid\nflowchart TD\n```\n<!-- /housegraph -->"
    drawn = housegraph.redraw(stale, KNOWN)
    assert housegraph.mermaid("hexflex", KNOWN) in drawn and drawn != stale
    with pytest.raises(ValueError, match="no drawing 'attic'"):
        housegraph.redraw("<!-- housegraph attic -->\n<!-- /housegraph -->", KNOWN)


def test_the_house_shows_every_room_in_its_wing() -> None:
    house = housegraph.mermaid("house", KNOWN)
    build = house.split('subgraph g1["build wing"]')[1].split("end")[0]
    assert 'mechlib_pipeline["pipeline/"]' in build
    assert 'mechlib_doe["doe.py"]' in house.split('subgraph g0["science wing"]')[1].split("end")[0]
    tops = {housegraph.room(m, "mechlib") for m in KNOWN} - {None}
    assert all(f'{t.replace(".", "_")}["' in house for t in tops)
    assert "  mechlib_pipeline --> mechlib_reporting\n" in house  # the build wing reads records
    assert "  mechlib_screening --> mechlib_doe\n" in house


def test_the_hexflex_drawing_shows_its_fe_room_on_the_core() -> None:
    hexflex = housegraph.mermaid("hexflex", KNOWN)
    assert "  mechlib_hexflex_fe --> mechlib_fe\n" in hexflex  # the HexFlex's instance of the core
    assert "  mechlib_hexflex_rom --> mechlib_hexflex_spec\n" in hexflex
    assert "  mechlib_hexflex_rom --> mechlib_campaign\n" in hexflex  # the shared campaign
    assert "mechlib_hexflex_fe --> mechlib_hexflex_spec" not in hexflex  # rooms below only
    assert "mechlib_campaign --> mechlib_hexflex" not in hexflex  # the campaign names no mechanism


def test_the_command_prints_a_drawing(capsys: pytest.CaptureFixture[str]) -> None:
    assert housegraph.main(["hexflex"]) == 0
    assert capsys.readouterr().out == housegraph.mermaid("hexflex", KNOWN)
