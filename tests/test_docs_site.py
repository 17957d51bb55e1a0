"""The documentation site's generated gallery is current, and names every figure in docs/figures with its title."""

import importlib.util
from pathlib import Path

DOCS = Path(__file__).resolve().parent.parent / "docs"


def _gallery_module():
    spec = importlib.util.spec_from_file_location("gallery", DOCS / "gallery.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_gallery_page_is_current():
    assert (DOCS / "gallery.md").read_text() == _gallery_module().gallery(), "run: python docs/gallery.py"


def test_every_figure_has_a_caption_from_its_study():
    page = (DOCS / "gallery.md").read_text()
    for png in sorted((DOCS / "figures").glob("*.png")):
        assert f"(figures/{png.name})" in page
    assert "a study no longer shipped" not in page, "a figure whose study is gone: remove it or name its source"
