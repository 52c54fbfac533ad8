"""make bench's command line (mechlib.bench.cli): which sections run, an unknown one refused."""

from __future__ import annotations

import pytest

from mechlib.bench import cli


def test_only_the_named_sections_run_in_their_order(monkeypatch) -> None:
    ran: list[str] = []
    monkeypatch.setattr(cli, "RUNS", {n: (lambda n=n: ran.append(n)) for n in cli.RUNS})
    assert cli.main(["--only", "lean,postures"]) == 0
    assert ran == ["postures", "lean"]
    ran.clear()
    assert cli.main([]) == 0
    assert ran == list(cli.SECTIONS) and "book" not in ran  # the book only when named


def test_an_unknown_section_is_refused_by_name(capsys) -> None:
    with pytest.raises(SystemExit) as stop:
        cli.main(["--only", "postures,nope"])
    assert stop.value.code == 2
    assert "unknown sections ['nope']; allowed: postures" in capsys.readouterr().err
