"""The FE code fingerprint digests code, not text: a docstring, a comment, an annotation or a
module's name and place leave it, an arithmetic line or a constant moves it; typing-only imports
are not followed. Checked on source strings and on a small package written to a temporary
folder; and the re-keying of a format-3 store."""

from __future__ import annotations

import importlib
import json
import sys
import textwrap
from dataclasses import replace

import numpy as np
import pytest

from mechlib import fespecs as fespecs  # the FE families a store holds, registered
from mechlib.campaign import codedigest as cd
from mechlib.campaign import rekey as rk
from mechlib.campaign import store as st
from mechlib.campaign.sources import model_modules
from mechlib.campaign.taskcache import model_code_fingerprint, task_key
from mechlib.hexflex.spec import ModelSpec

BASE = '''
"""A module."""
from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, ClassVar

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

SCALE: float = 2.0  # a constant


@dataclass
class Pair:
    """Two numbers."""

    a: float
    b: float
    LIMIT: ClassVar[int] = 3

    def total(self, k: float = 1.0) -> float:
        """Their sum, times k."""
        # the arithmetic line
        return k * (self.a + self.b)
'''

#: edits that cannot change a result: each (old, new) applied to BASE keeps its digest
KEEPS = {
    "module docstring": ('"""A module."""', '"""A module, reworded."""'),
    "class docstring": ('"""Two numbers."""', '"""Two real numbers."""'),
    "function docstring": ('"""Their sum, times k."""', '"""Their sum times k."""'),
    "comment": ("# the arithmetic line", "# the line that sums"),
    "attribute docstring": (
        "SCALE: float = 2.0  # a constant",
        'SCALE: float = 2.0\n"""A scale."""',
    ),
    "trailing comment": ("  # a constant", "  # [1], a scale"),
    "layout": (
        "return k * (self.a + self.b)",
        "return k * (\n            self.a + self.b\n        )",
    ),
    "argument annotation": ("k: float = 1.0", "k: int | float = 1.0"),
    "return annotation": (') -> float:\n        """Their', ') -> np.floating:\n        """Their'),
    "annotated constant": ("SCALE: float = 2.0", "SCALE = 2.0"),
    "field annotation": ("    a: float\n", "    a: np.float64\n"),
    "typing-only import": ("from numpy.typing import ArrayLike", "import numpy.typing as npt"),
}
#: edits that can: each changes the digest
CHANGES = {
    "operator": ("self.a + self.b", "self.a - self.b"),
    "constant": ("SCALE: float = 2.0", "SCALE: float = 2.5"),
    "default": ("k: float = 1.0", "k: float = 2.0"),
    "field order": ("    a: float\n    b: float\n", "    b: float\n    a: float\n"),
    "class variable made a field": ("LIMIT: ClassVar[int] = 3", "LIMIT: int = 3"),
}


def _edit(old: str, new: str) -> str:
    assert BASE.count(old) == 1, old
    return BASE.replace(old, new)


@pytest.mark.parametrize("what", KEEPS)
def test_an_edit_that_cannot_change_a_result_keeps_the_digest(what) -> None:
    assert cd.code_digest(_edit(*KEEPS[what])) == cd.code_digest(BASE)


@pytest.mark.parametrize("what", CHANGES)
def test_an_edit_of_the_code_changes_the_digest(what) -> None:
    assert cd.code_digest(_edit(*CHANGES[what])) != cd.code_digest(BASE)


def test_the_else_branch_of_a_typing_block_is_code() -> None:
    src = "if TYPE_CHECKING:\n    X = 1\nelse:\n    X = {}\n"
    assert cd.code_digest(src.format(2)) != cd.code_digest(src.format(3))
    assert cd.code_digest(src.replace("X = 1", "X = 5").format(2)) == cd.code_digest(src.format(2))


# --- a package in a temporary folder ------------------------------------------------------------

PACKAGE = {
    "synth/__init__.py": '"""A package that only says what it is for."""\n',
    "synth/core.py": '"""Arithmetic."""\n\n\ndef f(a, b):\n    """Sum."""\n    return a + b\n',
    "synth/other.py": "def f(a, b):\n    return a * b\n",
    "synth/shapes.py": "class Shape:\n    pass\n",
    "synth/task.py": textwrap.dedent('''\
        from __future__ import annotations

        from typing import TYPE_CHECKING

        from synth.core import f
        from synth.other import f as g

        if TYPE_CHECKING:
            from synth.shapes import Shape


        def run(x: Shape) -> float:
            return f(x, 2.0) + g(x, 1.0)
        '''),
}  # fmt: skip


@pytest.fixture
def fingerprint_of(tmp_path, monkeypatch):
    """The fingerprint of the package ``files`` ({path: source}) whose tasks run ``task``, and
    its closure: written to a fresh folder, imported from there."""
    monkeypatch.setattr(cd, "PACKAGE", "synth")
    made = []

    def compute(files: dict[str, str], task: str = "synth.task", **kw) -> tuple[str, tuple]:
        root = tmp_path / f"tree{len(made)}"
        made.append(root)
        for path, text in files.items():
            (root / path).parent.mkdir(parents=True, exist_ok=True)
            (root / path).write_text(text)
        for name in [m for m in sys.modules if m == "synth" or m.startswith("synth.")]:
            monkeypatch.delitem(sys.modules, name)
        monkeypatch.syspath_prepend(str(root))
        importlib.invalidate_caches()
        closure = model_modules((task,), **kw)
        return model_code_fingerprint.__wrapped__((task,)), closure

    return compute


def test_a_package_keeps_its_fingerprint_through_docstrings_and_a_move(fingerprint_of) -> None:
    base, closure = fingerprint_of(PACKAGE)
    assert closure == ("synth", "synth.core", "synth.other", "synth.task")  # and its package
    reworded = {**PACKAGE, "synth/__init__.py": '"""Reworded."""\n',
                "synth/core.py": PACKAGE["synth/core.py"].replace("Sum.", "The sum.")}  # fmt: skip
    assert fingerprint_of(reworded)[0] == base
    # core.py moved and renamed to sub/arith.py, its importer updated
    moved = {k: v for k, v in PACKAGE.items() if k != "synth/core.py"}
    moved["synth/sub/__init__.py"] = '"""Arithmetic, in a package of its own."""\n'
    moved["synth/sub/arith.py"] = PACKAGE["synth/core.py"]
    moved["synth/task.py"] = PACKAGE["synth/task.py"].replace("synth.core", "synth.sub.arith")
    fp, closure = fingerprint_of(moved)
    assert "synth.sub.arith" in closure and fp == base


def test_a_package_changes_its_fingerprint_with_its_code(fingerprint_of) -> None:
    base, _ = fingerprint_of(PACKAGE)
    minus = {**PACKAGE, "synth/core.py": PACKAGE["synth/core.py"].replace("a + b", "a - b")}
    assert fingerprint_of(minus)[0] != base
    constant = {**PACKAGE, "synth/task.py": PACKAGE["synth/task.py"].replace("2.0", "3.0")}
    assert fingerprint_of(constant)[0] != base
    # the same name read from another module of the closure (both define ``f``)
    swapped = PACKAGE["synth/task.py"].replace("synth.core import f\n", "synth.other import f\n")
    swapped = swapped.replace("synth.other import f as g", "synth.core import f as g")
    assert fingerprint_of({**PACKAGE, "synth/task.py": swapped})[0] != base


def test_a_typing_only_import_is_not_followed(fingerprint_of) -> None:
    base, closure = fingerprint_of(PACKAGE)
    assert "synth.shapes" not in closure
    assert "synth.shapes" in fingerprint_of(PACKAGE, format3=True)[1]  # format 3 did
    edited = {**PACKAGE, "synth/shapes.py": "class Shape:\n    SIDES = 4\n"}
    assert fingerprint_of(edited)[0] == base


def test_the_fe_closure_leaves_out_the_solid_model_protocol() -> None:
    """``mechlib.fe.nonlinear`` imports the protocol under ``if TYPE_CHECKING:`` only."""
    assert "mechlib.fe.nonlinear" in model_modules(ModelSpec.TASK_MODULES)
    assert "mechlib.fe.protocol" not in model_modules(ModelSpec.TASK_MODULES)
    assert "mechlib.fe.protocol" in model_modules(ModelSpec.TASK_MODULES, format3=True)


# --- re-keying a store of format 3 ---------------------------------------------------------------


def _format3_store(folder, spec: str, old: dict[str, str], entries=None):
    """A format-3 store of two synthetic HexFlex entries keyed on the fingerprints ``old`` (or
    of ``entries``)."""
    forces = np.array([[0.5, -0.3, 0.2, 0.4, -0.1, 0.3]])
    entries = entries or [
        st.Entry(task_key(spec, kind, forces * s, 2, old["hexflex"], 3), spec, kind, 2,
                 forces * s, np.arange(width, dtype=float)[None, :] * s)
        for kind, width, s in (("nonlinear", 22, 1.0), ("linear", 6, -0.5))
    ]  # fmt: skip
    st.write_store(entries, folder, {"commit": "84391a6eb275", "seconds": 1388.0})
    m = json.loads((folder / st.MANIFEST).read_text())
    m.update(version=3, fingerprint=old["hexflex"], fingerprints=old)
    (folder / st.MANIFEST).write_text(json.dumps(m))
    return entries


def test_a_format3_store_of_the_current_code_is_rekeyed_bit_for_bit(tmp_path) -> None:
    from test_store import SPEC  # tests/ is on sys.path (pytest prepend import mode)

    folder = tmp_path / "store"
    old = rk.byte_fingerprints()
    before = _format3_store(folder, SPEC.key(), old)
    with pytest.raises(st.StoreError, match="format version 3; this code reads versions 4"):
        st.read_store(folder)
    manifest, n = rk.rekey_store(folder, "abc123")
    assert n == 2 and manifest["version"] == st.STORE_VERSION
    assert manifest["commit"] == "84391a6eb275" and manifest["seconds"] == 1388.0
    assert manifest["rekeyed"]["from"] == {"version": 3, "fingerprints": old}
    assert manifest["rekeyed"]["commit"] == "abc123"
    _, after = st.read_store(folder)
    new = st.fingerprints()["hexflex"]
    for a, b in zip(before, after, strict=True):
        assert b.key == task_key(a.spec, a.kind, a.forces, a.steps, new) != a.key
        np.testing.assert_array_equal(a.results, b.results)


def test_a_store_of_other_code_or_an_edited_entry_is_not_rekeyed(tmp_path) -> None:
    from test_store import SPEC

    folder = tmp_path / "store"
    _format3_store(folder, SPEC.key(), {**rk.byte_fingerprints(), "hexflex": "0" * 16})
    manifest = (folder / st.MANIFEST).read_text()
    with pytest.raises(st.StoreError, match=r"other than the current one .* cannot be re-keyed"):
        rk.rekey_store(folder, "abc123")
    assert (folder / st.MANIFEST).read_text() == manifest  # left as it was
    # an entry whose key is the digest of other inputs than those stored (other load steps)
    old = rk.byte_fingerprints()
    entries = _format3_store(folder, SPEC.key(), old)
    bad = replace(entries[1], key=task_key(SPEC.key(), "linear", entries[1].forces, 9,
                                           old["hexflex"], 3))  # fmt: skip
    _format3_store(folder, SPEC.key(), old, [entries[0], bad])
    with pytest.raises(st.StoreError, match=f"entry {bad.key} is not the format-3 digest"):
        rk.rekey_store(folder, "abc123")
    assert not (tmp_path / ".store.rekeyed").exists()
