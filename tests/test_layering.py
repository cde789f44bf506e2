"""The floors of the house: data flow one way (``tce/__init__.py``, README "Layout").

signals (process plumbing), display (text helpers), files (atomic writing) and messages (input
errors), importing no tce module -> structures -> core -> analysis
-> study -> plot -> report -> cli, with ``quality`` beside the
command line. A module may import its own floor and the floors below, never one above; no
subpackage imports the command line; no import circles between modules (function-level
imports count: a lazy import is still a dependency). Read from the source with :mod:`ast`,
nothing imported.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

import tce

ROOT = Path(tce.__file__).parent
#: floor of each subpackage (a module may import modules of its floor and below)
FLOORS = {"signals": -1, "display": -1, "files": -1, "messages": -1, "structures": 0, "core": 1, "analysis": 2, "study": 3, "plot": 4, "report": 5, "cli": 6,
          "quality": 6}


def _module(path: Path) -> str:
    rel = path.relative_to(ROOT.parent).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _imports(path: Path) -> set[str]:
    """Modules of tce imported anywhere in ``path`` (relative imports resolved)."""
    name = _module(path)
    package = name if path.name == "__init__.py" else name.rsplit(".", 1)[0]
    found: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            found |= {a.name for a in node.names if a.name.split(".")[0] == "tce"}
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[: len(package.split(".")) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            if target.split(".")[0] != "tce":
                continue
            for alias in node.names:  # "from . import plot" imports the module tce.plot
                sub = f"{target}.{alias.name}"
                found.add(sub if _exists(sub) else target)
    return found - {name}


def _exists(module: str) -> bool:
    rel = Path(*module.split(".")[1:])
    return (ROOT / rel).with_suffix(".py").is_file() or (ROOT / rel / "__init__.py").is_file()


def _graph() -> dict[str, set[str]]:
    return {_module(p): _imports(p) for p in sorted(ROOT.rglob("*.py"))}


def _floor(module: str) -> int | None:
    parts = module.split(".")
    return FLOORS.get(parts[1]) if len(parts) > 1 else None


def test_every_subpackage_has_a_floor() -> None:
    tops = {p.stem if p.is_file() else p.name for p in ROOT.iterdir()
            if (p.suffix == ".py" and p.stem != "__init__") or (p / "__init__.py").is_file()}
    assert tops <= set(FLOORS), f"give {sorted(tops - set(FLOORS))} a floor in FLOORS"


def test_no_module_imports_a_higher_floor() -> None:
    bad = [f"{m} imports {t}" for m, targets in _graph().items() for t in sorted(targets)
           if _floor(m) is not None and _floor(t) is not None and _floor(t) > _floor(m)]
    assert not bad, "\n".join(bad)


def test_study_does_not_import_plot_nor_the_command_line() -> None:
    bad = [f"{m} imports {t}" for m, targets in _graph().items() if m.startswith("tce.study")
           for t in targets if t.startswith(("tce.plot", "tce.cli", "tce.report", "tce.quality"))]
    assert not bad, "\n".join(bad)


def _cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components of more than one module (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    out: list[list[str]] = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in graph.get(v, ()):
            if w not in graph:
                continue
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


@pytest.mark.parametrize("package", sorted(FLOORS))
def test_no_import_circles(package: str) -> None:
    """No circle among a subpackage's modules (the package ``__init__`` files, which re-export
    names lazily, are left out: importing ``tce.plot.data`` does not run a circle)."""
    graph = {m: {t for t in ts if not _is_init(t)} for m, ts in _graph().items()
             if m.startswith(f"tce.{package}") and not _is_init(m)}
    assert not _cycles(graph), _cycles(graph)


def _is_init(module: str) -> bool:
    return (ROOT / Path(*module.split(".")[1:]) / "__init__.py").is_file() or module == "tce"


def test_the_cycle_finder_finds_a_cycle() -> None:
    assert _cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]


def test_dir_lists_what_users_import_and_no_helpers() -> None:
    names = dir(tce)
    for name in ("LoadPattern", "PointLoad", "DistributedLoad", "load_assembly", "Analysis", "Material",
                 "load_path", "semicircular_arch", "run_study", "load_study"):
        assert name in names and name in tce.__all__
        assert getattr(tce, name) is not None
    assert not {"Any", "sys", "importlib", "annotations"} & set(names)


def test_the_tce_0_1_module_paths_are_gone() -> None:
    import importlib

    for old in ("tce.arch", "tce.loadpath", "tce.runner"):
        with pytest.raises(ModuleNotFoundError):
            importlib.import_module(old)
