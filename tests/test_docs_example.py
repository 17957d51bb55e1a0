"""The plugin example in docs/writing-a-model.md runs and passes the conformance suite."""

import re
from pathlib import Path

from impactlab.testing import check_model

DOC = Path(__file__).resolve().parents[1] / "docs" / "writing-a-model.md"


def test_documented_plugin_passes_conformance():
    blocks = re.findall(r"```python\n(.*?)```", DOC.read_text(), flags=re.S)
    namespace = {}
    exec(compile(blocks[0], str(DOC), "exec"), namespace)  # noqa: S102 - our own documentation
    check_model(namespace["StickyModel"])


def test_user_guide_lists_every_output_and_sweepable_field():
    from impactlab.vocabulary import INPUT_BY_PATH, OUTPUTS

    guide = (DOC.parent / "user-guide.md").read_text()
    for name, spec in OUTPUTS.items():
        assert f"| `{name}` | {spec.units} |" in guide, name
    for path in INPUT_BY_PATH:
        assert f"`{path}`" in guide, path
