"""The house's two wings and its import graph, read statically from the sources.

* The science wing (``mechlib`` minus ``mechlib.pipeline``) never imports the build wing
  (``mechlib.pipeline``): notebooks import only the science wing, and the Makefile re-executes
  them when a science file changes (its ``MECHLIB_SRC`` leaves the build wing out).
* No two modules import each other, through any path, at module level or inside a function or
  an ``if TYPE_CHECKING:`` block.
"""

from __future__ import annotations

import re

from mechlib.paths import REPO_ROOT
from mechlib.pipeline.housegraph import BUILD_WING, TOOLS, import_graph, modules
from mechlib.pipeline.housegraph import inside as _in

#: left out of the circle check (none)
UNCHECKED: set[str] = set()
#: import circles accepted (none)
TOLERATED_CIRCLES: list[set[str]] = []

#: the graph ARCHITECTURE.md draws (``python -m mechlib.pipeline.housegraph``)
MODULES = modules()
GRAPH = import_graph(MODULES)


def circles(graph: dict[str, set[str]]) -> list[set[str]]:
    """The strongly connected components of more than one module (Tarjan's algorithm)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    found: list[set[str]] = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        for w in sorted(graph[v]):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = set()
            while True:
                w = stack.pop()
                component.add(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(component)

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return found


def test_the_graph_is_read() -> None:
    assert "mechlib.reporting.records" in GRAPH["mechlib.pipeline.execute"]
    assert "mechlib.hexflex.geometry" in GRAPH["mechlib.hexflex.fe.model"]  # `from pkg import mod`
    assert circles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [{"a", "b", "c"}]


def test_the_science_wing_never_imports_the_build_wing() -> None:
    crossing = {
        m: sorted(i for i in imports if _in(i, BUILD_WING))
        for m, imports in GRAPH.items()
        if not _in(m, BUILD_WING) and not any(_in(m, t) for t in TOOLS)
    }
    assert {m: i for m, i in crossing.items() if i} == {}


def test_the_makefile_reexecutes_notebooks_on_a_science_change_only() -> None:
    makefile = (REPO_ROOT / "Makefile").read_text()
    source = re.search(r"^MECHLIB_SRC\s*:=(.*)$", makefile, re.M)
    assert source and "$(filter-out mechlib/pipeline/%," in source.group(1)


def test_no_two_modules_import_each_other() -> None:
    checked = {m: i - UNCHECKED for m, i in GRAPH.items() if m not in UNCHECKED}
    assert [c for c in circles(checked) if c not in TOLERATED_CIRCLES] == []


def test_every_module_is_under_400_lines() -> None:
    long = {m: n for m, p in MODULES.items() if (n := len(p.read_text().splitlines())) >= 400}
    assert long == {}


def test_every_notebook_is_a_declared_chapter() -> None:
    from mechlib.pipeline.chapters import CHAPTERS

    notebooks = sorted(p.stem for p in (REPO_ROOT / "notebooks").glob("*.ipynb"))
    assert sorted(CHAPTERS) == notebooks  # an undeclared notebook would never be executed


#: what each room of ``mechlib.hexflex`` may import inside ``mechlib.hexflex`` (its package
#: docstring says the same): the top (geometry, checks, frame_solver, frame, identify) nothing
#: below it; the FE model the top's geometry only (it defines results: the FE cache's
#: fingerprint digests it); the campaign specification (``spec``) the FE model; the compliances
#: as campaign tasks the specification; the ROM and the studies all of these; nothing in
#: ``mechlib.hexflex`` imports a study. The campaign itself is :mod:`mechlib.campaign`.
HEXFLEX_ROOMS = {
    "top": set(),
    "fe": {"top"},
    "spec": {"top", "fe"},
    "compliance": {"top", "fe", "spec"},
    "rom": {"top", "fe", "spec", "compliance"},
    "studies": {"top", "fe", "spec", "compliance"},
}


def _room(module: str) -> str | None:
    parts = module.split(".")
    if parts[:2] != ["mechlib", "hexflex"] or len(parts) < 3:
        return None
    return parts[2] if parts[2] in HEXFLEX_ROOMS else "top"


def test_each_hexflex_room_imports_only_the_rooms_below_it() -> None:
    crossing = {
        (m, i)
        for m, imports in GRAPH.items()
        for i in imports
        if _room(m)
        and _room(i)
        and _room(i) != _room(m)
        and _room(i) not in HEXFLEX_ROOMS[_room(m)]
    }
    assert crossing == set()
    assert {_room(m) for m in GRAPH} >= set(HEXFLEX_ROOMS)  # every room exists


def test_the_fe_model_imports_only_geometry_params_and_the_fe_core_from_mechlib() -> None:
    outside = {
        i
        for m, imports in GRAPH.items()
        if _in(m, "mechlib.hexflex.fe")
        for i in imports
        if not _in(i, "mechlib.hexflex.fe") and not _in(i, "mechlib.fe")
    }
    assert outside <= {"mechlib.hexflex.geometry", "mechlib.params", "mechlib.blas"}


def test_the_fe_core_and_the_compliant_layouts_import_no_hexflex() -> None:
    # the solid FE core imports no mechanism (each mechanism's fingerprint holds the core and
    # its own model only); a compliant layout's model is the core's other instance
    core = {i for m, imports in GRAPH.items() if _in(m, "mechlib.fe") for i in imports}
    assert {i for i in core if not _in(i, "mechlib.fe")} <= {"mechlib.params", "mechlib.blas"}
    layouts = {i for m, imports in GRAPH.items() if _in(m, "mechlib.compliant") for i in imports}
    assert not {i for i in layouts if _in(i, "mechlib.hexflex")}


def test_the_recorder_imports_no_science() -> None:
    # the notebooks' bookkeeping primitive sits below every mechanism: what it reaches, through
    # any chain of imports, is the claims engine, the report rows and plain utilities; the
    # registry of claims (which reads the science packages' constants) is passed in
    allowed = {
        "mechlib.reporting.records",
        "mechlib.reporting.claims",
        "mechlib.reporting.report",
        "mechlib.reporting.categories",
        "mechlib.reporting.jsonready",
        "mechlib.reporting.recordglue",
        "mechlib.reporting.recordhelpers",
        "mechlib.reporting.recordplan",
        "mechlib.reporting.tolerance",
        "mechlib.reporting.tolerances",
        "mechlib.params",
        "mechlib.paths",
        "mechlib.blasinfo",
        "mechlib.reporting",
        "mechlib",
    }
    reached, todo = set(), ["mechlib.reporting.records"]
    while todo:
        m = todo.pop()
        if m not in reached:
            reached.add(m)
            todo += sorted(GRAPH.get(m, set()))
    assert reached <= allowed, sorted(reached - allowed)


#: the mechanism packages: none imports another's (each is an instance of the shared cores:
#: the FE core :mod:`mechlib.fe`, the compliant-layout layer :mod:`mechlib.compliant`, the
#: campaign :mod:`mechlib.campaign`, the calibration engine, the dyad :mod:`mechlib.dyad`);
#: what names several of them is a composition root above them (:mod:`mechlib.fespecs`,
#: :mod:`mechlib.mechanism_catalog`)
MECHANISMS = (
    "mechlib.hexflex",
    "mechlib.parallelogram",
    "mechlib.fivebar",
    "mechlib.mechanisms",
)


def _mechanism(module: str) -> str | None:
    return next((p for p in MECHANISMS if _in(module, p)), None)


def test_no_mechanism_package_imports_another_s() -> None:
    crossing = {
        (m, i)
        for m, imports in GRAPH.items()
        for i in imports
        if _mechanism(m) and _mechanism(i) and _mechanism(m) != _mechanism(i)
    }
    assert crossing == set(), sorted(crossing)


def test_the_compliant_layer_sits_below_every_mechanism() -> None:
    """Any planar compliant mechanism is a :class:`~mechlib.compliant.layout.Layout` (the
    parallelogram is one): the layer imports the FE core and the ground floor, no mechanism."""
    layer = {i for m, imports in GRAPH.items() if _in(m, "mechlib.compliant") for i in imports}
    outside = {i for i in layer if not _in(i, "mechlib.compliant") and not _in(i, "mechlib.fe")}
    assert outside <= {"mechlib.params", "mechlib.blas"}, sorted(outside)


def test_the_campaign_names_no_mechanism() -> None:
    # the runner, cache, store and cold checks work on the Spec protocol and the family
    # registry (mechlib.campaign.spec); mechlib.fespecs registers the families
    campaign = {i for m, imports in GRAPH.items() if _in(m, "mechlib.campaign") for i in imports}
    assert not {i for i in campaign if _mechanism(i)}, sorted(i for i in campaign if _mechanism(i))
    # nor a family by its name: the registry finds a task's family from its key text
    import ast

    from mechlib.fespecs import HEXFLEX, MECHANISM

    names = {HEXFLEX.name, MECHANISM.name}
    for path in sorted((REPO_ROOT / "mechlib" / "campaign").glob("*.py")):
        tree = ast.parse(path.read_text())
        found = {n.value for n in ast.walk(tree) if isinstance(n, ast.Constant)} & names
        assert not found, (path.name, found)


def test_no_module_reads_another_s_private_members() -> None:
    """A module uses another's public interface (e.g. the SVK tangent's per-element data for the
    reduced-order model and material regions): no ``obj._name`` but on ``self`` or ``cls``."""
    import ast

    found = []
    for path in sorted((REPO_ROOT / "mechlib").rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            if (
                isinstance(node, ast.Attribute)
                and node.attr.startswith("_")
                and not node.attr.startswith("__")
                and not (isinstance(node.value, ast.Name) and node.value.id in ("self", "cls"))
            ):
                found.append(f"{path.relative_to(REPO_ROOT)}:{node.lineno} {ast.unparse(node)}")
    assert found == []


def test_every_linear_model_extends_the_one_factorised_base() -> None:
    from mechlib.compliant.model import MechanismModel
    from mechlib.fe.linear import FactorisedModel, FactorisedStiffness
    from mechlib.hexflex.fe.model import HexFlexModel
    from mechlib.hexflex.studies.cantilever import Cantilever

    assert issubclass(HexFlexModel, FactorisedModel) and issubclass(MechanismModel, FactorisedModel)
    assert issubclass(Cantilever, FactorisedStiffness)
    for model in (HexFlexModel, MechanismModel):  # the solve and the pose written once
        own = set(vars(model))
        assert not own & {"back_substitute", "solve_reduced", "pose_of", "compliance", "poses"}
