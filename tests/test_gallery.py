"""Every figure of the gallery (the studies shipped in studies/ and studies/paper/) regenerated and inspected.

A figure fails when a panel has nothing drawn, a legend entry names a line with no finite point, or the
image is nearly blank; each also has to say its conditions (a title) and label its axes with units. Sweeps
are thinned to at most 7 values per range so that the whole gallery runs in seconds; the figures' code
paths are those of the full studies.
"""

from pathlib import Path

import numpy as np
import pytest
import yaml

import impactlab

ROOT = Path(__file__).resolve().parent.parent
STUDIES = sorted((ROOT / "studies").glob("*.yaml")) + sorted((ROOT / "studies" / "paper").glob("*.yaml"))


def thinned(path: Path) -> dict:
    text = yaml.safe_load(path.read_text())
    for _key, value in (text.get("sweep") or {}).items():
        if isinstance(value, dict) and "num" in value:
            value["num"] = min(int(value["num"]), 7)
    return text


@pytest.mark.slow
@pytest.mark.parametrize("path", STUDIES, ids=[path.stem for path in STUDIES])
def test_every_gallery_figure_shows_what_its_legend_and_axes_claim(path, tmp_path, drawn_figures):
    study = impactlab.load_study(thinned(path), file=str(path))
    result = impactlab.run_study(study, executor="serial")
    from impactlab.cli.study_commands import _draw  # what impactlab run --plot draws, sensitivity studies included

    pictures = _draw(result, tmp_path / f"{path.stem}.h5", None)
    assert len(drawn_figures) == len(pictures)
    for figure in drawn_figures:
        name = figure["path"].name
        assert not figure["problems"], (name, figure["problems"])
        assert figure["ink"] > 0.02, name  # not a blank canvas with a legend
        assert figure["title"].strip(), name
        for panel in figure["panels"]:
            if panel["marks"] and not panel["lines"]:  # a bar chart or an index map: its value axis has the unit
                assert panel["xlabel"].rstrip().endswith("]") or panel["ylabel"].rstrip().endswith("]") \
                    or not panel["xlabel"], (name, panel["xlabel"])
                continue
            assert panel["ylabel"].rstrip().endswith("]"), (name, panel["ylabel"])  # a unit on every axis
            assert panel["xlabel"].rstrip().endswith("]"), (name, panel["xlabel"])
            assert panel["lines"], name
            for label, (_xs, ys) in panel["lines"].items():
                assert np.isfinite(ys).any(), (name, label)


def test_the_audit_names_an_empty_panel_and_a_legend_entry_with_nothing_drawn(tmp_path):
    # the gallery test is only as good as this check: it must see what a reader would miss
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from impactlab.plot.style import FigureWarning, _save, audit

    figure, (full, empty) = plt.subplots(1, 2)
    full.plot([0, 1], [0, 1], label="drawn")
    full.plot([0, 1], [np.nan, np.nan], label="all NaN")
    full.legend()
    problems = audit(figure)
    assert any("'all NaN' has nothing drawn" in problem for problem in problems)
    assert any("panel 2" in problem for problem in problems)
    assert not any("'drawn'" in problem for problem in problems)
    with pytest.warns(FigureWarning, match="nothing drawn"):
        _save(figure, tmp_path / "bad.png")
    plt.close(figure)
