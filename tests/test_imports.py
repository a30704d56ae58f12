"""The package's modules import one another in one direction only: no import cycles.

The graph is read from the source (every `import` and `from … import`, at module level or
inside a function, since a deferred import hides a cycle without removing it). An edge goes to
the module named; a package's own `__init__` counts only where the package itself is imported
(Python initialises a parent package before its submodules, so a submodule naming a sibling
does not import the parent back).

And a run's start imports only what a run needs: not the chaos analysis, nor scipy's signal
processing, optimisers and integrators (docs/performance.md, "Start-up").
"""

import ast
import subprocess
import sys
from pathlib import Path

import sim

PACKAGE_ROOT = Path(sim.__file__).parent
#: what `sim run` does not need, each a quarter to half a second of a start to import: the
#: analyses' and the recordings' signal processing, the rare fallbacks' solvers
NOT_FOR_A_RUN = ("sim.analysis.run", "scipy.signal", "scipy.optimize", "scipy.integrate")


def module_names() -> dict[str, Path]:
    """Dotted name → source file of every module of the `sim` package."""
    names = {}
    for path in PACKAGE_ROOT.rglob("*.py"):
        parts = path.relative_to(PACKAGE_ROOT.parent).with_suffix("").parts
        if parts[-1] == "__init__":
            parts = parts[:-1]
        names[".".join(parts)] = path
    return names


def imports_of(path: Path, known: dict[str, Path]) -> set[str]:
    """The modules of the package that the file at `path` imports."""
    found = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            for alias in node.names:
                submodule = f"{node.module}.{alias.name}"
                found.add(submodule if submodule in known else node.module)
    return {name for name in found if name in known}


def import_graph() -> dict[str, set[str]]:
    known = module_names()
    return {name: imports_of(path, known) for name, path in known.items()}


def cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components with more than one module, or a module importing itself
    (Tarjan 1972)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: list[list[str]] = []

    def visit(node: str) -> None:
        index[node] = low[node] = len(index)
        stack.append(node)
        on_stack.add(node)
        for succ in sorted(graph[node]):
            if succ not in index:
                visit(succ)
                low[node] = min(low[node], low[succ])
            elif succ in on_stack:
                low[node] = min(low[node], index[succ])
        if low[node] == index[node]:
            component = []
            while True:
                member = stack.pop()
                on_stack.discard(member)
                component.append(member)
                if member == node:
                    break
            if len(component) > 1 or node in graph[node]:
                found.append(sorted(component))

    for node in sorted(graph):
        if node not in index:
            visit(node)
    return found


def test_the_cycle_finder_finds_a_cycle():
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}, "e": {"e"}}
    assert sorted(cycles(graph)) == [["a", "b", "c"], ["e"]]


def test_the_package_has_no_import_cycle():
    graph = import_graph()
    assert len(graph) > 40  # the walk found the package
    assert "sim.cli.analyze" in graph["sim.cli"]  # and reads imports
    assert cycles(graph) == []


def test_nothing_in_the_library_imports_the_command_line():
    graph = import_graph()
    importers = sorted(
        name
        for name, targets in graph.items()
        if not name.startswith("sim.cli")
        and any(t == "sim.cli" or t.startswith("sim.cli.") for t in targets)
    )
    assert importers == []


def test_the_command_line_and_the_simulator_start_without_the_analyses():
    shown = "import sys, sim.cli, sim.run; print(*sorted(set(sys.argv[1:]) & set(sys.modules)))"
    loaded = subprocess.run(
        [sys.executable, "-c", shown, *NOT_FOR_A_RUN], capture_output=True, text=True, check=True
    )
    assert loaded.stdout.split() == []
