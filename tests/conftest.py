import numpy as np
import pytest

from impactlab.scene.materials import BALL_PRESETS


@pytest.fixture
def golf_inputs():
    """Urethane ball on a rigid face at 80 mph; call with overrides (arrays broadcast)."""

    def make(**changes):
        ball = BALL_PRESETS["urethane_tour"]
        base = dict(ball_radius=ball.radius, ball_mass=ball.mass, ball_inertia_factor=ball.inertia_factor,
                    ball_youngs_modulus=ball.material.youngs_modulus, ball_poisson_ratio=ball.material.poisson_ratio,
                    face_youngs_modulus=np.inf, face_poisson_ratio=0.0, friction=0.4, restitution=1.0,
                    speed=35.7632, angle=np.radians(15.0), spin=0.0)
        base.update(changes)
        arrays = {key: np.atleast_1d(np.asarray(value, dtype=float)) for key, value in base.items()}
        n = max(array.size for array in arrays.values())
        return {key: np.broadcast_to(array, (n,)).copy() for key, array in arrays.items()}

    return make


@pytest.fixture
def drawn_figures(monkeypatch):
    """Every figure saved during the test: its file, what plotting.audit finds wrong, its lines and labels.

    Tests then assert on what a figure shows (the values on its lines, its axis labels) instead of the size
    of the PNG, which a blank figure with a long legend also reaches.
    """
    import io
    from pathlib import Path

    from matplotlib.figure import Figure
    from matplotlib.image import imread

    from impactlab.plot.style import audit

    record = []
    original = Figure.savefig

    def savefig(self, fname, *args, **kwargs):
        panels = [{"xlabel": axis.get_xlabel(), "ylabel": axis.get_ylabel(),
                   "lines": {line.get_label(): (np.asarray(line.get_xdata(), float),
                                                np.asarray(line.get_ydata(), float))
                             for line in axis.get_lines() if not line.get_label().startswith("_")},
                   "marks": len(axis.patches) + len(axis.images) + len(axis.collections)}
                  for axis in self.axes if axis.get_visible()]
        title = self._suptitle.get_text() if self._suptitle is not None else ""
        # impactlab draws into memory and writes the file atomically (io.safe_output.write_figure): the buffer
        # is named after the file it goes to
        entry = {"path": Path(getattr(fname, "name", fname)), "problems": audit(self), "panels": panels,
                 "title": title or " ".join(axis.get_title() for axis in self.axes)}
        result = original(self, fname, *args, **kwargs)
        pixels = imread(io.BytesIO(fname.getvalue()) if hasattr(fname, "getvalue") else str(fname))[..., :3]
        entry["ink"] = float(np.mean(np.any(pixels < 0.9, axis=-1)))  # share of pixels that are not near-white
        record.append(entry)
        return result

    monkeypatch.setattr(Figure, "savefig", savefig)
    return record
