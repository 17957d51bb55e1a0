"""``impactlab validate --dataset SESSION --report report.html``: the scorecard and what a fitter looks at, on one page.

One self-contained HTML file (figures embedded as base64 PNG, no script, no server, nothing fetched): the scorecard
tables (:mod:`.scorecard`), and for the held-out rows

- predicted against measured, per output and model, as density plots (hexagonal bins: thousands of shots);
- each model's median residual against club speed, with its interquartile band;
- spin axis against face to path: the measured shots' density beside each model's median;
- per club, the dispersion (carry against side, 95 % ellipses) of the monitor's launch and of each model's launch,
  both flown by impactlab's flight model in standard air (:func:`impactlab.scene.flight.fly`).

Every figure says its units and conditions, measured beside predicted.
"""

from __future__ import annotations

import base64
import html
import io
import math
import os
from pathlib import Path

import numpy as np
import xarray as xr

from impactlab.data.sessions.shots import ShotTable, shot_errors
from impactlab.io.safe_output import write_atomically
from impactlab.scene.flight import fly
from impactlab.units import MPH, RAD_TO_DEG, RADS_TO_RPM

#: (field, label, factor from SI) of the outputs drawn
QUANTITIES = (("ball_speed", "ball speed [mph]", 1.0 / MPH),
              ("vertical_launch_angle", "launch angle [deg]", RAD_TO_DEG),
              ("horizontal_launch_angle", "launch direction [deg]", RAD_TO_DEG),
              ("spin_rate", "spin rate [rpm]", RADS_TO_RPM), ("spin_axis", "spin axis [deg]", RAD_TO_DEG))
#: most shots flown per club for the dispersion figure (evenly spaced over the held-out rows)
FLOWN = 600
#: chi-square quantile of 2 degrees of freedom at 95 %: the ellipse of a bivariate normal holding 95 % of it
CHI2_95 = 5.991


def _png(figure) -> str:
    buffer = io.BytesIO()
    figure.savefig(buffer, format="png", dpi=90)
    return base64.b64encode(buffer.getvalue()).decode("ascii")


def _figure(width: float, height: float):
    from matplotlib.figure import Figure  # no pyplot: the caller's figures and backend stay untouched

    return Figure(figsize=(width, height), layout="constrained")


def predicted_measured(test: ShotTable, predicted: dict, field: str, label: str, factor: float):
    """One panel per model: hexbin density of predicted against measured ``field`` on the held-out rows."""
    names = list(predicted)
    columns = min(4, len(names))
    rows = math.ceil(len(names) / columns)
    figure = _figure(3.3 * columns, 3.1 * rows + 0.4)
    axes = figure.subplots(rows, columns, squeeze=False).ravel()
    measured = test.measured[field] * factor
    finite = measured[np.isfinite(measured)]
    low, high = (np.percentile(finite, [0.5, 99.5]) if finite.size else (0.0, 1.0))
    pad = 0.05 * (high - low or 1.0)
    low, high = low - pad, high + pad
    images = []
    for axis, name in zip(axes, names):
        values = predicted[name][field] * factor
        keep = np.isfinite(values) & np.isfinite(measured)
        if keep.any():
            images.append(axis.hexbin(measured[keep], values[keep], gridsize=40, extent=(low, high, low, high),
                                      mincnt=1, bins="log", cmap="viridis"))
        axis.plot([low, high], [low, high], "r-", lw=0.8, label="predicted = measured")
        axis.set_xlim(low, high)
        axis.set_ylim(low, high)
        axis.set_title(f"{name} ({int(keep.sum())} shots)", fontsize=9)
        axis.set_xlabel(f"measured {label}", fontsize=8)
        axis.set_ylabel(f"predicted {label}", fontsize=8)
        axis.tick_params(labelsize=7)
    for axis in axes[len(names):]:
        axis.set_visible(False)
    if images:  # one colour scale for every panel, so that one colour bar reads them all
        most = max(float(np.max(image.get_array())) for image in images)
        for image in images:
            image.set_clim(1.0, max(most, 2.0))
        figure.colorbar(images[0], ax=list(axes[:len(names)]), label="shots per hexagon", shrink=0.6)
    axes[0].legend(fontsize=7, loc="upper left")
    figure.suptitle(f"{test.name}: predicted against measured {label}, held-out shots (colour: shots per hexagon, "
                    "log scale)", fontsize=10)
    return figure


def _least(count: int) -> int:
    """Fewest points of a bin drawn: 10, fewer (down to 3) for a small table."""
    return max(3, min(10, count // 20))


def _binned(x: np.ndarray, y: np.ndarray, edges: np.ndarray, least: int | None = None):
    """Per bin of ``x``: centre, median, 25th and 75th percentile of ``y`` (bins with at least ``least`` points)."""
    least = _least(int(np.isfinite(y).sum())) if least is None else least
    centre, median, lower, upper = [], [], [], []
    for a, b in zip(edges[:-1], edges[1:]):
        inside = y[(x >= a) & (x < b) & np.isfinite(y)]
        if inside.size >= least:
            centre.append(0.5 * (a + b))
            median.append(np.median(inside))
            lower.append(np.percentile(inside, 25))
            upper.append(np.percentile(inside, 75))
    return np.array(centre), np.array(median), np.array(lower), np.array(upper)


def _lies_on(drawn: list, xs: np.ndarray, ys: np.ndarray, tolerance: float) -> str | None:
    """The name of an earlier curve of ``drawn`` [(name, xs, ys)] that (xs, ys) lies on within ``tolerance`` (same
    points, finite values), or None: a curve hidden under another is said in the legend, never left unsaid."""
    for name, x0, y0 in drawn:
        if x0.shape == xs.shape and np.all(np.isfinite(ys) == np.isfinite(y0)):
            both = np.isfinite(ys) & np.isfinite(y0)
            if both.any() and np.all(np.abs(x0[both] - xs[both]) <= tolerance) \
                    and np.all(np.abs(y0[both] - ys[both]) <= tolerance):
                return name
    return None


def residual_vs_speed(test: ShotTable, predicted: dict):
    """Per output: each model's median residual (predicted - measured) against club speed, with its IQR band."""
    speed = test.delivery["club_speed"] / MPH
    edges = np.arange(math.floor(np.nanmin(speed) / 5) * 5, np.nanmax(speed) + 5.0, 5.0)
    keys = ("ball_speed [%]", "launch angle [deg]", "launch direction [deg]", "spin [%]", "spin axis [deg]")
    figure = _figure(16, 4.4)
    axes = figure.subplots(1, len(keys))
    colours = [f"C{i}" for i in range(10)]
    hidden: dict[str, dict[str, list[str]]] = {}  # name -> the curve it lies on -> the panels where it does
    for axis, key in zip(axes, keys):
        drawn: list = []
        for index, (name, values) in enumerate(predicted.items()):
            error = np.asarray(shot_errors(values, test)[key], dtype=float)
            centre, median, lower, upper = _binned(speed, error, edges)
            if centre.size:
                colour = colours[index % len(colours)]
                # within 1 % of the curve's span: at this figure's size the two lines are drawn on the same pixels
                under = _lies_on(drawn, centre, median, 0.01 * (np.nanmax(median) - np.nanmin(median)) + 1e-12)
                drawn.append((name, centre, median))
                if under:
                    hidden.setdefault(name, {}).setdefault(under, []).append(key.split(" [")[0])
                axis.plot(centre, median, "--o" if under else "-o", ms=5 if under else 3, mfc="none" if under else
                          colour, color=colour, label=name)
                axis.fill_between(centre, lower, upper, color=colour, alpha=0.08)
        axis.axhline(0.0, color="k", lw=0.6)
        axis.set_xlabel("club speed [mph]")
        axis.set_ylabel(key)
        axis.set_title(f"predicted - measured: {key}", fontsize=9)
        axis.grid(alpha=0.3)
    # the one legend (first panel) says every panel where a curve lies on another's (drawn dashed, open markers)
    for line in axes[0].get_lines():
        notes = hidden.get(str(line.get_label()))
        if notes:
            where = "; ".join(f"{other} in {', '.join(panels)}" for other, panels in notes.items())
            line.set_label(f"{line.get_label()} (on {where})")
    if axes[0].get_legend_handles_labels()[0]:  # below the panels, where it hides no curve
        figure.legend(*axes[0].get_legend_handles_labels(), loc="outside lower center", ncol=4, fontsize=7,
                      frameon=False)
    figure.suptitle(f"{test.name}: residual against club speed on the held-out shots (lines: median per 5 mph; "
                    f"bands: 25-75 %; bins of {_least(test.size)} shots or more)", fontsize=10)
    return figure


def spin_axis_vs_face_to_path(test: ShotTable, predicted: dict):
    """Measured spin axis against face to path (density), each model's median predicted spin axis over it."""
    f2p = (test.delivery["face_angle"] - test.delivery["path"]) * RAD_TO_DEG
    axis_measured = test.measured["spin_axis"] * RAD_TO_DEG
    keep = np.isfinite(f2p) & np.isfinite(axis_measured)
    figure = _figure(7.5, 5.5)
    axis = figure.subplots()
    low, high = (np.percentile(f2p[keep], [0.5, 99.5]) if keep.any() else (-1.0, 1.0))
    limit = np.percentile(np.abs(axis_measured[keep]), 99.5) if keep.any() else 1.0
    if keep.any():
        image = axis.hexbin(f2p[keep], axis_measured[keep], gridsize=45, extent=(low, high, -limit, limit), mincnt=1,
                            bins="log", cmap="Greys")
        figure.colorbar(image, ax=axis, label="measured shots per hexagon")
    # bins of equal counts of shots: the medians are as sure at the tails as at the centre
    edges = np.unique(np.percentile(f2p[keep], np.linspace(0, 100, 21))) if keep.any() else np.array([low, high])
    for index, (name, values) in enumerate(predicted.items()):
        centre, median, _, _ = _binned(f2p, values["spin_axis"] * RAD_TO_DEG, edges)
        if centre.size:
            axis.plot(centre, median, "-", color=f"C{index % 10}", lw=1.5, label=f"{name} (median)")
    centre, median, _, _ = _binned(f2p, axis_measured, edges)
    if centre.size:
        axis.plot(centre, median, "k--", lw=2, label="measured (median)")
    axis.set_xlim(low, high)
    axis.set_ylim(-limit, limit)
    axis.set_xlabel("face to path [deg] (face angle - club path; open positive)")
    axis.set_ylabel("spin axis [deg] (tilted right positive)")
    axis.grid(alpha=0.3)
    if axis.get_legend_handles_labels()[0]:
        axis.legend(fontsize=7)
    axis.set_title(f"{test.name}: spin axis against face to path, held-out shots (lines: medians over 20 bins of "
                   "equal shot counts)", fontsize=9)
    return figure


def _ellipse(x: np.ndarray, y: np.ndarray):
    """Points of the 95 % ellipse of a bivariate normal with the sample mean and covariance of (x, y)."""
    keep = np.isfinite(x) & np.isfinite(y)
    if keep.sum() < 3:
        return None
    mean = np.array([x[keep].mean(), y[keep].mean()])
    values, vectors = np.linalg.eigh(np.cov(np.stack([x[keep], y[keep]])))
    angle = np.linspace(0, 2 * np.pi, 100)
    circle = np.stack([np.cos(angle), np.sin(angle)])
    return mean[:, None] + vectors @ (np.sqrt(np.maximum(values, 0.0) * CHI2_95)[:, None] * circle)


def dispersion(test: ShotTable, predicted: dict):
    """Per club: carry against side of the monitor's launch and of each model's launch, flown in standard air
    (15 degC, 1013.25 hPa, 50 %, still), with 95 % ellipses. Up to :data:`FLOWN` shots per club."""
    clubs = list(dict.fromkeys(test.clubs))
    figure = _figure(max(9.0, 7.5 * len(clubs)), 6.5)
    axes = np.atleast_1d(figure.subplots(1, len(clubs)))
    launches = {"monitor's launch (measured)": test.measured, **predicted}
    for axis, club in zip(axes, clubs):
        rows = np.flatnonzero(np.array(test.clubs) == club)
        rows = rows[np.linspace(0, rows.size - 1, min(FLOWN, rows.size)).round().astype(int)]
        rings: list = []  # (name, side, carry) of each ellipse drawn, to say which lies on which
        for index, (name, values) in enumerate(launches.items()):
            speed, launch, spin = (values[k][rows] for k in ("ball_speed", "vertical_launch_angle", "spin_rate"))
            tilt = np.nan_to_num(values["spin_axis"][rows])
            direction = np.nan_to_num(values["horizontal_launch_angle"][rows])
            ok = np.isfinite(speed) & np.isfinite(launch) & np.isfinite(spin) & (launch > 0) & (spin > 0)
            if not ok.any():
                continue
            import warnings

            with warnings.catch_warnings():  # mishits' unusual launches: flown as given, said in the caption
                warnings.simplefilter("ignore")
                flown = fly(speed[ok], launch[ok], spin[ok], tilt[ok], direction[ok])
            carry = flown["carry_distance"].values
            side = flown["offline_distance"].values
            measured = index == 0
            colour = "k" if measured else f"C{(index - 1) % 10}"
            if measured:
                axis.scatter(side, carry, s=3, color="0.6", alpha=0.4)
            ring = _ellipse(side, carry)
            if ring is not None:
                under = _lies_on(rings, ring[0], ring[1], 0.5)  # within half a metre: the same ellipse drawn
                rings.append((name, ring[0], ring[1]))
                axis.plot(ring[0], ring[1], "--" if measured or under else "-", color=colour,
                          lw=2 if measured else 1.2, label=f"{name} ({int(ok.sum())} shots)"
                          + (f", on {under}'s ellipse" if under else ""))
        axis.set_xlabel("side (offline) [m], right positive")
        axis.set_ylabel("carry [m]")
        axis.grid(alpha=0.3)
        if axis.get_legend_handles_labels()[0]:
            axis.legend(fontsize=7)
        axis.set_title(f"{club}: 95 % ellipses of carry and side (grey dots: the monitor's launch flown)",
                       fontsize=9)
    figure.suptitle(f"{test.name}: dispersion of the held-out shots, each launch flown by impactlab's flight model\n"
                    "in standard air (15 degC, 1013.25 hPa, 50 % humidity, no wind)", fontsize=10)
    return figure


def _table_html(card: xr.Dataset) -> str:
    out = []
    models = [str(m) for m in card["model"].values]
    for output in card["output"].values:
        out.append(f"<h3>{html.escape(str(output))}</h3><table><tr><th>model</th><th>kind</th><th>n</th>"
                   "<th>median |e|</th><th>p90 |e|</th><th>bias (median e)</th><th>RMS</th></tr>")
        for model in models:
            n, median, p90, bias, rms = card["error"].sel(model=model, output=output).values
            kind = str(card["kind"].sel(model=model).values)
            cells = "".join(f"<td>{'-' if not math.isfinite(v) else f'{v:.2f}'}</td>" for v in (median, p90, bias, rms))
            out.append(f"<tr class='{kind}'><td>{html.escape(model)}</td><td>{kind}</td><td>{int(n)}</td>{cells}</tr>")
        floor = float(card["floor"].sel(output=output))
        source = str(card["floor_source"].sel(output=output).values)
        out.append(f"<tr class='floor'><td>instrument floor</td><td>floor</td><td></td>"
                   f"<td>{'-' if not math.isfinite(floor) else f'{floor:.2f}'}</td><td></td><td></td><td></td></tr>"
                   "</table>"
                   f"<p class='source'>Instrument floor: {html.escape(source)}</p>")
    for variable, dimension, counts, title in (
            ("error_by_speed", "speed_band", "rows_in_speed_band", "median |error| by club-speed band"),
            ("error_by_strike", "strike_zone", "rows_in_strike_zone", "median |error| by strike zone"),
            ("error_by_ball", "ball_setting", "rows_in_ball_setting",
             "median |error| by the monitor's ball setting (every model runs the same ball)")):
        if variable not in card:
            continue
        present = [(str(b), int(c)) for b, c in zip(card[dimension].values, card[counts].values) if c > 0]
        if dimension == "ball_setting" and len(present) < 2:
            continue  # one ball setting or none: the overall table is its breakdown
        if not present:
            out.append(f"<h3>{title}</h3><p>No held-out row has one.</p>")
            continue
        out.append(f"<h3>{title}</h3><table><tr><th>output</th><th>model</th>"
                   + "".join(f"<th>{html.escape(b)} ({c})</th>" for b, c in present) + "</tr>")
        for output in card["output"].values:
            for model in models:
                medians = card[variable].sel(model=model, output=output, statistic="median_abs")
                out.append(f"<tr><td>{html.escape(str(output))}</td><td>{html.escape(model)}</td>" + "".join(
                    f"<td>{'-' if not math.isfinite(v := float(medians.sel({dimension: b}))) else f'{v:.2f}'}</td>"
                    for b, _ in present) + "</tr>")
        out.append("</table>")
    return "\n".join(out)


STYLE = ("body{font-family:sans-serif;margin:2em;max-width:1600px} table{border-collapse:collapse;margin:0.5em 0 1.5em}"
         " td,th{border:1px solid #bbb;padding:2px 8px;text-align:right} td:first-child,th:first-child{text-align:left}"
         " tr.baseline{background:#eef} tr.fit{background:#efe} tr.floor{background:#fee} img{max-width:100%}"
         " p.source{font-size:85%;max-width:60em;margin-top:-1em}"
         " figure{margin:1.5em 0} figcaption{font-size:90%;color:#333}")


def report_html(table: ShotTable, split, card: xr.Dataset, predicted: dict) -> str:
    """The report page (HTML text): scorecard tables and the figures of the held-out rows, embedded."""
    test = table.subset(split.test)
    figures = []
    for field, label, factor in QUANTITIES:
        if np.isfinite(test.measured[field]).any():
            figures.append((f"Predicted against measured {label}",
                            predicted_measured(test, predicted, field, label, factor)))
    figures.append(("Residual against club speed", residual_vs_speed(test, predicted)))
    figures.append(("Spin axis against face to path", spin_axis_vs_face_to_path(test, predicted)))
    figures.append(("Dispersion per club (the monitor's launch and each model's, flown by impactlab; the "
                    "monitor's own carry is not read from this file's layout yet)", dispersion(test, predicted)))
    parts = [f"<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'><title>impactlab scorecard: "
             f"{html.escape(table.name)}</title><style>{STYLE}</style></head><body>",
             f"<h1>Scorecard of {html.escape(table.name)}</h1>",
             f"<p>{html.escape(table.source)}</p><p>{html.escape(card.attrs['split'])}.</p>",
             f"<p>Bias = {html.escape(card.attrs['bias'])}. Errors: {html.escape(card.attrs['errors'])}.</p>"]
    if card.attrs.get("baseline_coefficients"):
        parts.append(f"<p>Baselines fitted on the training rows: {html.escape(card.attrs['baseline_coefficients'])}"
                     "</p>")
    for key in ("notes", "head_cor"):
        if card.attrs.get(key):
            parts.append(f"<p><strong>Note:</strong> {html.escape(card.attrs[key])}</p>")
    parts.append("<h2>Scorecard (held-out rows)</h2>")
    parts.append(_table_html(card))
    parts.append("<h2>Figures (held-out rows)</h2>")
    for index, (caption, figure) in enumerate(figures):
        parts.append(f"<figure><img id='figure-{index}' alt='{html.escape(caption)}' "
                     f"src='data:image/png;base64,{_png(figure)}'><figcaption>Figure {index + 1}. "
                     f"{html.escape(caption)}</figcaption></figure>")
    parts.append("</body></html>")
    return "\n".join(parts)


def write_report(path: str | os.PathLike[str], table: ShotTable, split, card: xr.Dataset, predicted: dict) -> Path:
    """Write :func:`report_html` to ``path`` (atomically: an existing file is replaced whole or not at all)."""
    return write_atomically(path, report_html(table, split, card, predicted).encode("utf-8"))
