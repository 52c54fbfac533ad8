"""The FE code fingerprint digests code, not text: a docstring, a comment, an annotation or a
module's name and place leave it, an arithmetic line or a constant moves it; typing-only imports
are not followed. Checked on source strings and on a small package written to a temporary
folder."""

from __future__ import annotations

import importlib
import sys
import textwrap

import numpy as np
import pytest

from mechlib import fespecs as fespecs  # the FE families a store holds, registered
from mechlib.campaign import codedigest as cd
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
    edited = {**PACKAGE, "synth/shapes.py": "class Shape:\n    SIDES = 4\n"}
    assert fingerprint_of(edited)[0] == base


def test_a_module_digest_covers_what_it_imports_all_the_way_down(fingerprint_of) -> None:
    """``core`` and ``other`` differ only in what they import (the same code otherwise): an
    unchanged ``via`` that reads ``f`` from the one or the other computes different things, and
    the fingerprint tells them apart although the closure holds the same modules."""
    files = {
        "synth/__init__.py": PACKAGE["synth/__init__.py"],
        "synth/plus.py": "def f(a, b):\n    return a + b\n",
        "synth/times.py": "def f(a, b):\n    return a * b\n",
        "synth/core.py": "from synth.plus import f\n",
        "synth/other.py": "from synth.times import f\n",
        "synth/via.py": "from synth.core import f\n",
        "synth/side.py": "from synth import core, other\n",  # both stay in the closure
        "synth/task.py": "from synth import side\nfrom synth.via import f\n\n\n"
        "def run(x):\n    return f(x, 2.0)\n",
    }
    base, closure = fingerprint_of(files)
    rerouted = {**files, "synth/via.py": "from synth.other import f\n"}
    fp, closure2 = fingerprint_of(rerouted)
    assert closure == closure2 and {"synth.core", "synth.other", "synth.plus"} <= set(closure)
    assert fp != base


def test_a_dataclass_field_is_not_a_class_attribute() -> None:
    field = "class C:\n    x: float = 1.0\n"
    attribute = "class C:\n    x = 1.0\n"
    assert cd.code_digest(field) != cd.code_digest(attribute)
    assert cd.code_digest("x: float = 1.0\n") == cd.code_digest("x = 1.0\n")  # a module's


def test_a_module_imported_from_its_package_is_named_by_its_digest() -> None:
    src = "from mechlib.hexflex import geometry as geo\n"
    one = {"mechlib.hexflex": "a" * 64, "mechlib.hexflex.geometry": "b" * 64}
    other = {**one, "mechlib.hexflex.geometry": "c" * 64}
    assert cd.code_digest(src, "", one) != cd.code_digest(src, "", other)


def test_the_fe_closure_holds_the_task_runner_and_the_specification() -> None:
    """What a task computes is decided by the specification's ``build`` and ``SOLVE_METHOD``
    and by the runner's solve (``mechlib.campaign.solve``): all in every family's key."""
    from mechlib.compliant.spec import MechanismSpec

    for spec in (ModelSpec, MechanismSpec):
        closure = model_modules((*spec.TASK_MODULES, "mechlib.campaign.solve"))
        assert spec.__module__ in closure and "mechlib.campaign.solve" in closure
        assert "mechlib.campaign.experiments" not in closure  # the runner's bookkeeping is not
    assert "mechlib.fe.nonlinear" in model_modules(ModelSpec.TASK_MODULES)
    # ``mechlib.fe.nonlinear`` imports the solid model protocol under TYPE_CHECKING only
    assert "mechlib.fe.protocol" not in model_modules(ModelSpec.TASK_MODULES)


@pytest.mark.parametrize("edited", ["mechlib.campaign.solve", "mechlib.hexflex.spec"])
def test_an_edit_of_the_solve_or_the_specification_changes_the_fingerprint(
    edited, monkeypatch
) -> None:
    """The fingerprint itself (not only the closure list) digests the task's solve, which
    :func:`model_code_fingerprint` adds to every family, and the specification's module."""
    from mechlib.campaign import taskcache

    read = taskcache._source
    before = model_code_fingerprint.__wrapped__(ModelSpec.TASK_MODULES)
    monkeypatch.setattr(
        taskcache, "_source", lambda n: read(n) + b"\n_EDITED = 1\n" if n == edited else read(n)
    )
    assert model_code_fingerprint.__wrapped__(ModelSpec.TASK_MODULES) != before


def test_every_family_lists_its_specification_module_among_its_task_modules() -> None:
    """A family's ``build`` and ``SOLVE_METHOD`` live in its specification's module: a family
    that left it out of ``TASK_MODULES`` would leave them out of its key."""
    from mechlib.campaign.spec import families

    for fam in families():
        assert fam.spec.__module__ in fam.spec.TASK_MODULES, fam.name


def test_the_key_of_a_task_follows_its_fingerprint() -> None:
    forces = np.array([[0.5, -0.3, 0.2, 0.4, -0.1, 0.3]])
    spec = ModelSpec.__module__
    one = task_key(spec, "nonlinear", forces, 2, "0" * 16)
    assert one == task_key(spec, "nonlinear", forces.copy(), 2, "0" * 16)
    assert one != task_key(spec, "nonlinear", forces, 2, "1" * 16)


def test_keyword_only_marks_and_local_annotations_are_code() -> None:
    kw_only = "class C:\n    _: KW_ONLY\n    x: int = 1\n"
    field = "class C:\n    _: int\n    x: int = 1\n"
    assert cd.code_digest(kw_only) != cd.code_digest(field)
    # a bare annotation makes a name local to its function (reading it then fails)
    local = "X = 1\n\n\ndef f():\n    X: int\n    return X\n"
    assert cd.code_digest(local) != cd.code_digest(local.replace("    X: int\n", ""))


def test_every_package_that_holds_a_module_is_in_the_closure(fingerprint_of) -> None:
    files = {
        "synth/__init__.py": PACKAGE["synth/__init__.py"],
        "synth/deep/__init__.py": "SCALE = 2.0\n",  # runs when anything below it is imported
        "synth/deep/er/__init__.py": '"""Only its purpose."""\n',
        "synth/deep/er/task.py": "def run(x):\n    return x\n",
    }
    base, closure = fingerprint_of(files, task="synth.deep.er.task")
    assert {"synth", "synth.deep", "synth.deep.er"} <= set(closure)
    edited = {**files, "synth/deep/__init__.py": "SCALE = 3.0\n"}
    assert fingerprint_of(edited, task="synth.deep.er.task")[0] != base
