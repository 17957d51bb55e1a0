"""The package layout keeps its layers: no import cycle, no import from a layer above, functions that fit on a
screen, modules of a readable size, no private name imported across subpackages, and impactlab's own imports at
the top of each module (the few deferred on purpose are listed below).

Every module of ``impactlab`` is parsed with :mod:`ast` (nothing is imported), so every import counts: those
at the top of a module, those deferred into a function body, and those under ``if TYPE_CHECKING``. Importing
``impactlab.a.b`` also runs the package ``impactlab.a`` (its ``__init__``), so that edge is in the graph too.
The layer rule holds for every import; the cycle check leaves out the ``if TYPE_CHECKING`` ones, which never
run (an annotation may name a type of a module that imports this one).

The layers, lowest first (docs/architecture.md draws them); a module may import from its own layer and any
layer below it, never from one above:

0. foundation: ``errors``, ``units``, ``vocabulary``, ``validators``, ``_version``, ``foreign``
1. ``physics`` (plain array functions in SI)
2. ``peers`` (other codes run as references: LAMMPS)
3. ``scene`` (ball, face, club head, strike, delivery, scene)
4. ``model`` and the ``impactlab.case_inputs`` shim (the plugin contract)
5. ``study`` (YAML studies, sweeps, case arrays, measured-dataset registry)
6. ``io`` (result files, atomic writes, simulator interchange)
7. ``run`` (run_study, executors, progress store, assembly, faults, sensitivity runs)
8. ``data`` (shot tables, calibration and fitting, validation runs, convergence)
9. ``plot`` (every figure)
10. top: ``cli``, ``testing``, ``__main__`` and the package ``__init__`` (whose lazy re-exports reach any layer)
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parent.parent / "impactlab"

#: layer of each first name under impactlab (a module or a subpackage), lowest first
LAYERS: dict[str, int] = {
    "errors": 0, "units": 0, "vocabulary": 0, "validators": 0, "_version": 0, "foreign": 0,
    "physics": 1,
    "peers": 2,
    "scene": 3,
    "model": 4, "case_inputs": 4,
    "study": 5,
    "io": 6,
    "run": 7,
    "data": 8,
    "plot": 9,
    "cli": 10, "testing": 10, "__main__": 10, "": 10,  # "": the package itself (impactlab/__init__.py)
}
MAX_TOP_MODULES = 12
#: a module's lines: a loose cap, so that a module holds one concern rather than being cut by size
MAX_LINES = 800
#: a function's lines of code (its docstring left out: numpydoc asks every public function for one, and what it
#: documents is no reason to split the code); the numba kernels are left out (one compiled loop each, whose
#: steps share registers; a call between them costs what the kernel exists to save)
MAX_FUNCTION_LINES = 80
KERNELS = PACKAGE / "physics" / "kernels"
#: functions over the cap allowed for a while (a split in progress elsewhere); empty: every function is split
LONG_FUNCTIONS_ALLOWED: set[tuple[str, str]] = set()


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


MODULES = {_module_name(path): path for path in sorted(PACKAGE.rglob("*.py"))}


def _resolve(name: str) -> str | None:
    """The longest prefix of a dotted name that is a module of impactlab (None: not impactlab's)."""
    parts = name.split(".")
    while parts:
        if ".".join(parts) in MODULES:
            return ".".join(parts)
        parts.pop()
    return None


def _type_checking_only(tree: ast.Module) -> set[int]:
    """ids of the import nodes inside an ``if TYPE_CHECKING:`` block (imported by type checkers, never run)."""
    found = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.If) and isinstance(node.test, ast.Name) and node.test.id == "TYPE_CHECKING":
            found.update(id(inner) for statement in node.body for inner in ast.walk(statement))
    return found


def _imports(module: str, *, type_checking: bool = True) -> set[str]:
    """Every impactlab module ``module`` imports anywhere in its text (deferred ones too; with ``type_checking``
    False, those under ``if TYPE_CHECKING`` left out)."""
    path = MODULES[module]
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    found = set()
    tree = ast.parse(path.read_text(), str(path))
    skipped = set() if type_checking else _type_checking_only(tree)
    for node in ast.walk(tree):
        if id(node) in skipped:
            continue
        names = []
        if isinstance(node, ast.Import):
            names = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:  # relative: resolved against the module's own package
                anchor = package.split(".")[: len(package.split(".")) - node.level + 1]
                base = ".".join(anchor + ([base] if base else []))
            # "from a.b import c" imports the module a.b.c when there is one, else names of a.b
            names = [f"{base}.{alias.name}" for alias in node.names] + [base]
        for name in names:
            target = _resolve(name)
            if target is None or target == module:
                continue
            found.add(target)
            parts = target.split(".")
            # running impactlab.a.b runs the package impactlab.a first, unless the importer is inside impactlab.a
            # (then Python has run it already); the root package is left out: nothing inside impactlab imports it
            found.update(parent for end in range(2, len(parts))
                         if not f"{module}.".startswith(f"{(parent := '.'.join(parts[:end]))}."))
    found.discard(module)
    return found


GRAPH = {module: _imports(module) for module in MODULES}
#: the imports that run (the graph of the cycle check)
RUNTIME_GRAPH = {module: _imports(module, type_checking=False) for module in MODULES}


def _layer(module: str) -> int:
    first = module.split(".")[1] if "." in module else ""
    assert first in LAYERS, f"{module}: not in a layer of tests/test_architecture.py (add it, and to the docs)"
    return LAYERS[first]


def _cycle() -> list[str] | None:
    """One import cycle (as a path that returns to its start), or None."""
    state: dict[str, int] = {}  # 1: on the current path, 2: finished
    stack: list[str] = []

    def visit(module: str) -> list[str] | None:
        state[module] = 1
        stack.append(module)
        for target in sorted(RUNTIME_GRAPH[module]):
            if state.get(target) == 1:
                return stack[stack.index(target):] + [target]
            if target not in state:
                found = visit(target)
                if found:
                    return found
        stack.pop()
        state[module] = 2
        return None

    for module in sorted(RUNTIME_GRAPH):
        if module not in state:
            found = visit(module)
            if found:
                return found
    return None


def test_the_graph_sees_imports_of_every_kind():
    """The parser finds a top-level, a deferred, a package and a TYPE_CHECKING import (else the checks below prove
    nothing)."""
    assert "impactlab.errors" in GRAPH["impactlab.vocabulary"]  # deferred, inside a function
    assert "impactlab.units" in GRAPH["impactlab.vocabulary"]  # at the top
    assert "impactlab.model" in GRAPH["impactlab.study.core"]  # the package of impactlab.model.base
    assert "impactlab.model.base" in GRAPH["impactlab.model.planning"]  # under if TYPE_CHECKING: layers only
    assert "impactlab.model.base" not in RUNTIME_GRAPH["impactlab.model.planning"]
    assert len(MODULES) > 60


def test_no_import_cycle():
    assert _cycle() is None, "import cycle: " + " -> ".join(_cycle() or [])


def test_a_planted_cycle_is_found(monkeypatch):
    """The cycle search finds a cycle when one is there (a check that passes on any graph is no check)."""
    monkeypatch.setitem(RUNTIME_GRAPH, "impactlab.errors", RUNTIME_GRAPH["impactlab.errors"] | {"impactlab.vocabulary"})
    assert _cycle() in (["impactlab.errors", "impactlab.vocabulary", "impactlab.errors"],
                        ["impactlab.vocabulary", "impactlab.errors", "impactlab.vocabulary"])


def test_no_module_imports_from_a_layer_above_its_own():
    upward = sorted(f"{module} (layer {_layer(module)}) imports {target} (layer {_layer(target)})"
                    for module, targets in GRAPH.items() for target in targets if _layer(target) > _layer(module))
    assert not upward, "\n".join(upward)


def test_few_modules_at_the_top():
    top = sorted(path.name for path in PACKAGE.glob("*.py"))
    assert len(top) <= MAX_TOP_MODULES, top


def test_no_module_over_800_lines():
    long = {module: n for module, path in MODULES.items() if (n := len(path.read_text().splitlines())) > MAX_LINES}
    assert not long, long


def _code_lines(function: ast.FunctionDef | ast.AsyncFunctionDef) -> int:
    """A function's lines from its ``def`` to its last line, its docstring left out."""
    lines = function.end_lineno - function.lineno + 1  # type: ignore[operator]
    first = function.body[0]
    if isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant) and isinstance(first.value.value, str):
        lines -= first.end_lineno - first.lineno + 1  # type: ignore[operator]
    return lines


def _long_functions(paths: dict[str, Path]) -> dict[tuple[str, str], int]:
    found = {}
    for module, path in paths.items():
        if path.is_relative_to(KERNELS):
            continue
        for node in ast.walk(ast.parse(path.read_text(), str(path))):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and _code_lines(node) > MAX_FUNCTION_LINES:
                found[(module, node.name)] = _code_lines(node)
    return found


MODELS = PACKAGE.parent / "models"


def test_no_function_over_80_lines_outside_the_kernels():
    """A function a maintainer reads on one screen: the long ones are split along their steps (the built-in models
    too: they are the example plugin authors copy)."""
    paths = {**MODULES, **{f"models.{path.stem}": path for path in sorted(MODELS.glob("*.py"))}}
    long = {key: n for key, n in _long_functions(paths).items() if key not in LONG_FUNCTIONS_ALLOWED}
    assert not long, long


def test_the_allowed_long_functions_are_still_long():
    """An entry of the allowlists whose function was split (or renamed) leaves the list, so that it allows nothing
    else later."""
    paths = {**MODULES, **{f"models.{path.stem}": path for path in sorted(MODELS.glob("*.py"))}}
    long = _long_functions(paths)
    assert LONG_FUNCTIONS_ALLOWED <= set(long), LONG_FUNCTIONS_ALLOWED - set(long)


def test_a_planted_long_function_is_found(tmp_path):
    """The length rule counts code, not the docstring (a check that passes on any module is no check)."""
    body = "    x = 0\n" * MAX_FUNCTION_LINES
    doc = '    """' + "doc\n" * 50 + '    """\n'
    (tmp_path / "long.py").write_text(f"def long():\n{body}\n\ndef documented():\n{doc}    return 0\n")
    assert _long_functions({"long": tmp_path / "long.py"}) == {("long", "long"): MAX_FUNCTION_LINES + 1}


def _private_imports(module: str) -> set[str]:
    """``target:name`` for each private name (``_x``) ``module`` imports from a module of another (sub)package."""
    path = MODULES[module]
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    found = set()
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if not isinstance(node, ast.ImportFrom):
            continue
        base = node.module or ""
        if node.level:
            anchor = package.split(".")[: len(package.split(".")) - node.level + 1]
            base = ".".join(anchor + ([base] if base else []))
        target = _resolve(base)
        if target is None:
            continue
        home = target if MODULES[target].name == "__init__.py" else target.rpartition(".")[0]
        for alias in node.names:
            private = alias.name.startswith("_") and not alias.name.startswith("__")
            if private and home != package:
                found.add(f"{target}:{alias.name}")
    return found


def test_no_private_name_is_imported_across_subpackages():
    """A private name is private to its subpackage: ``impactlab.data.sessions`` may share ``_norm`` among its own
    modules, no module outside it may import it (it would be an API without a promise)."""
    crossing = {module: found for module in MODULES if (found := _private_imports(module))}
    assert not crossing, crossing


def test_the_private_import_rule_sees_a_crossing(monkeypatch, tmp_path):
    planted = tmp_path / "planted.py"
    # across (study -> data) is found; within one subpackage (data.sessions.values -> data.sessions.x) is not
    planted.write_text("from impactlab.study.structuring import _hook\nfrom .values import _norm\n")
    monkeypatch.setitem(MODULES, "impactlab.data.sessions.planted", planted)
    assert _private_imports("impactlab.data.sessions.planted") == {"impactlab.study.structuring:_hook"}


def test_the_public_names_import_from_impactlab():
    """Every name of ``impactlab.__all__`` resolves, to the object its home module defines (lazy ones too)."""
    import impactlab
    from impactlab.data.fit import calibration, fitting
    from impactlab.data.sessions import shots
    from impactlab.errors import ModelContractError
    from impactlab.scene.clubs import ClubHead, Strike
    from impactlab.scene.core import Delivery

    for name in impactlab.__all__:
        assert getattr(impactlab, name) is not None, name
    assert (impactlab.Delivery, impactlab.ClubHead, impactlab.Strike) == (Delivery, ClubHead, Strike)
    assert impactlab.ModelContractError is ModelContractError
    assert impactlab.read_shots is shots.read_shots and impactlab.predict is shots.predict
    assert impactlab.calibrate is calibration.calibrate and impactlab.fit is fitting.fit
    assert set(impactlab.__all__) <= set(dir(impactlab))
    with pytest.raises(AttributeError, match="no attribute 'read_shot'"):
        impactlab.read_shot  # noqa: B018


def test_import_impactlab_leaves_the_heavy_parts_for_later():
    """``import impactlab`` loads neither the data layer (scipy.optimize), matplotlib nor SALib."""
    import subprocess
    import sys

    code = ("import sys, impactlab; print(sorted(m for m in ('impactlab.data', 'impactlab.run', 'scipy.optimize', "
            "'matplotlib', 'SALib', 'dask') if m in sys.modules))")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120, check=True)
    assert done.stdout.strip() == "[]", done.stdout


#: deferred imports of impactlab modules kept on purpose: the package's lazy wrappers, and the CLI's fit and
#: validate commands, whose modules import scipy.optimize (about 0.2 s every other command would pay)
DEFERRED_ALLOWED = {
    "impactlab": {"impactlab.study.core", "impactlab.run.runner", "impactlab.io.results", "impactlab.model.registry"},
    "impactlab.cli.data_commands": {"impactlab.data.fit.fitting", "impactlab.data.shot_report"},
    # the compiled flight kernel: numba is imported (0.4 s) on a process's first flight, not with impactlab
    "impactlab.physics.flight": {"impactlab.physics", "impactlab.physics.kernels"},
}


def test_impactlab_imports_sit_at_the_top_of_their_modules():
    """An import of impactlab deferred into a function hides the layering from a reader; only the allowed ones."""
    deferred = {}
    for module, path in MODULES.items():
        tree = ast.parse(path.read_text(), str(path))
        for function in ast.walk(tree):
            if not isinstance(function, (ast.FunctionDef, ast.AsyncFunctionDef)):
                continue
            for node in ast.walk(function):
                if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("impactlab"):
                    target = _resolve(node.module)
                    if target not in DEFERRED_ALLOWED.get(module, set()):
                        deferred.setdefault(module, set()).add(node.module)
                elif isinstance(node, ast.Import):
                    for alias in node.names:
                        if alias.name.startswith("impactlab"):
                            deferred.setdefault(module, set()).add(alias.name)
    assert not deferred, deferred
