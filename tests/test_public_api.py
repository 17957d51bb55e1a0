"""The public API is a list: docs/writing-a-model.md's "Public paths" names the modules a plugin may import, each
module's ``__all__`` the names, and the built-in models (the example every plugin author copies) import nothing
else. Parsed with :mod:`ast` from the models' source; the list is read from the docs page, not restated here."""

from __future__ import annotations

import ast
import importlib
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
MODELS = ROOT / "models"


def public_paths() -> list[str]:
    """The modules of the docs' "Public paths" list (each bullet's backticked names before its colon)."""
    text = (ROOT / "docs" / "writing-a-model.md").read_text()
    section = text[text.index("## Public paths"):].split("\n## ", 1)[0]
    paths = []
    for line in section.splitlines():
        if line.startswith("- "):
            paths += re.findall(r"`([\w.]+)`", line[2:].split(": ", 1)[0])
    return paths


PUBLIC = public_paths()


def _public_names(path: str) -> set[str]:
    module = importlib.import_module(path)
    return set(module.__all__)


def test_the_list_names_the_plugin_modules_and_each_has_an_all_that_resolves():
    assert {"impactlab", "impactlab.model", "impactlab.units", "impactlab.vocabulary", "impactlab.physics.hertz",
            "impactlab.scene.materials", "impactlab_models.shared"} <= set(PUBLIC), PUBLIC
    every_physics = {f"impactlab.physics.{path.stem}" for path in (ROOT / "impactlab" / "physics").glob("*.py")
                     if path.stem != "__init__"}
    assert every_physics <= set(PUBLIC), every_physics - set(PUBLIC)
    for path in PUBLIC:
        module = importlib.import_module(path)
        assert isinstance(getattr(module, "__all__", None), (list, tuple)), f"{path} has no __all__"
        missing = [name for name in module.__all__ if not hasattr(module, name)]
        private = [name for name in module.__all__ if name.startswith("_") and not name.startswith("__")]
        assert not missing and not private, (path, missing, private)


def _imports(path: Path) -> list[tuple[str, str | None]]:
    """(module, name) for each impactlab import of a models file (name None: ``import module``); the models'
    package-relative imports are resolved to ``impactlab_models``."""
    found = []
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            found += [(alias.name, None) for alias in node.names if alias.name.startswith("impactlab")]
        elif isinstance(node, ast.ImportFrom):
            module = node.module or ""
            if node.level:
                module = "impactlab_models" + (f".{module}" if module else "")
            if module.startswith("impactlab"):
                found += [(module, alias.name) for alias in node.names]
    return found


def _not_public(imports: list[tuple[str, str | None]]) -> list[str]:
    bad = []
    for module, name in imports:
        if name is None:
            if module not in PUBLIC:
                bad.append(module)
        elif f"{module}.{name}" in PUBLIC:  # a public submodule (from impactlab.physics import hertz)
            continue
        elif module not in PUBLIC or name not in _public_names(module):
            bad.append(f"{module}:{name}")
    return bad


def test_the_built_in_models_import_only_public_names():
    """Each built-in model imports only names of the public list (their shared helpers through
    ``impactlab_models.shared``); ``shared`` itself re-exports the private helper modules of its own package."""
    bad = {}
    for path in sorted(MODELS.glob("*.py")):
        if path.name.startswith("_") or path.name == "shared.py":
            continue
        if found := _not_public(_imports(path)):
            bad[path.name] = found
    assert not bad, bad


def test_the_shared_helpers_import_only_public_names():
    """What ``impactlab_models.shared`` re-exports is built from public names of impactlab too (a plugin copying
    ``_compliant.py`` would otherwise copy a private import)."""
    bad = {}
    for name in ("_common.py", "_compliant.py"):
        imports = [(module, item) for module, item in _imports(MODELS / name)
                   if not module.startswith("impactlab_models")]
        if found := _not_public(imports):
            bad[name] = found
    assert not bad, bad


def test_a_private_import_is_seen(tmp_path):
    """The check refuses a private module, a private name, and a name left out of ``__all__``."""
    plugin = tmp_path / "plugin.py"
    plugin.write_text("from impactlab.model.diagnostics import LARGE_CONTACT_RATIO\n"
                      "from impactlab.physics.hertz import _scaled\n"
                      "from impactlab.physics.hertz import np\n"
                      "from impactlab_models._compliant import CompliantOptions\n"
                      "from impactlab.physics import hertz\n"
                      "from impactlab.model import ImpactModel\n")
    assert _not_public(_imports(plugin)) == ["impactlab.model.diagnostics:LARGE_CONTACT_RATIO",
                                             "impactlab.physics.hertz:_scaled", "impactlab.physics.hertz:np",
                                             "impactlab_models._compliant:CompliantOptions"]
