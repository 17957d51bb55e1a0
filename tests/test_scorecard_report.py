"""The scorecard's HTML report: one self-contained page whose every figure renders in a real (headless) browser."""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).parent))
from test_scorecard import session  # noqa: E402

from impactlab.data.validation.report import write_report  # noqa: E402
from impactlab.data.validation.scorecard import holdout_split, scorecard  # noqa: E402

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser") or shutil.which("google-chrome")
#: flags of a headless run that touches nothing outside the page (no GPU, no network, no profile sync)
HEADLESS = ("--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
            "--disable-component-update", "--disable-sync", "--no-first-run")
#: appended to a copy of the page only: after loading, count the images the browser decoded
PROBE = ("<script>window.addEventListener('load', function () {var images = Array.from(document.images);"
         "document.body.setAttribute('data-decoded', images.filter(function (i) {return i.complete && "
         "i.naturalWidth > 0;}).length + '/' + images.length);});</script>")


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    import attrs

    table = attrs.evolve(session(80), instrument="trackman")  # TrackMan's rows: the report carries its floor claims
    table.delivery["strike_toe"][:] = np.linspace(-0.02, 0.02, table.size)  # some strikes off the centre
    split = holdout_split(table, 0.3)
    predicted: dict = {}
    card = scorecard(table, ["restitution", "rigid_coulomb"], holdout=split, predictions=predicted)
    path = tmp_path_factory.mktemp("report") / "report.html"
    write_report(path, table, split, card, predicted)
    return path


@pytest.mark.slow
def test_the_report_is_one_self_contained_page(report):
    text = report.read_text()
    images = re.findall(r"<img [^>]*src='([^']*)'", text)
    # five predicted-against-measured pages, residual against club speed, spin axis, dispersion
    assert len(images) == 8 and all(src.startswith("data:image/png;base64,") for src in images)
    assert not re.search(r"(src|href)=['\"](https?:|//)", text) and "<script" not in text
    for heading in ("ball_speed [%]", "spin axis [deg]", "instrument floor", "median |error| by strike zone",
                    "regression", "VENDOR CLAIM"):
        assert heading in text, heading


@pytest.mark.slow
@pytest.mark.skipif(CHROMIUM is None, reason="no headless browser: install Debian's chromium (apt-get install -y "
                                             "chromium) to check that the report's figures render")
def test_every_figure_renders_in_headless_chromium(report, tmp_path):
    probe = tmp_path / "probe.html"
    probe.write_text(report.read_text().replace("</body>", PROBE + "</body>"))
    done = subprocess.run([CHROMIUM, *HEADLESS, "--virtual-time-budget=10000", "--dump-dom", probe.as_uri()],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr[-2000:]
    decoded = re.search(r'data-decoded="(\d+)/(\d+)"', done.stdout)
    assert decoded is not None, done.stdout[:2000]
    assert decoded.group(1) == decoded.group(2) == "8"


def test_a_curve_lying_on_another_is_named_in_the_legend():
    """restitution and rigid_coulomb give the same launches: the later curve must say it lies on the earlier one."""
    from impactlab.data.validation.report import _lies_on

    xs, ys = np.linspace(0.0, 1.0, 9), np.linspace(2.0, 3.0, 9)
    drawn = [("rigid_coulomb", xs, ys)]
    assert _lies_on(drawn, xs, ys + 1e-4, 1e-3) == "rigid_coulomb"
    assert _lies_on(drawn, xs, ys + 1e-2, 1e-3) is None
    assert _lies_on(drawn, xs[:-1], ys[:-1], 1e-3) is None  # another set of points is another curve
    nan = ys.copy()
    nan[3] = np.nan
    assert _lies_on(drawn, xs, nan, 1e-3) is None  # a gap where the other has a value: not the same curve
