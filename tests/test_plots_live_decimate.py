"""A live figure sends a long line as its per-pixel-column extremes, drawn as the full line is.

:func:`afmsmiler.plots.live.decimate` (issue 24: Q control sent 20,804 points, 166 kB, a frame to
axes 500 px wide). Each test compares what :func:`~afmsmiler.plots.live.describe` sends with the
artists' full data, column by column of the axis as the browser places it: the first and last
points are kept, every full point lies within the envelope (min..max) of the points sent in its
column, and each column's extremes are sent, so the canvas lights the same pixels.
"""
import math

import numpy as np
import pytest
from matplotlib.figure import Figure

from afmsmiler.plots.live import _positions, decimate, describe


def _columns_of(x, lim, columns, scale="linear", linthresh=1.0):
    pos = _positions(x, lim, scale, linthresh)
    col = np.full(x.size, -2)
    ok = np.isfinite(pos)
    col[ok] = np.clip(np.floor(pos[ok] * columns), -1, columns)
    return col


def _check_envelope(x, y, xs, ys, lim, columns, scale="linear", linthresh=1.0):
    """Every column's full points lie within, and reach, the envelope of the points sent.

    The full line is placed as the browser would place it, from float32.
    """
    x = np.asarray(x, dtype=np.float32).astype(float)
    y = np.asarray(y, dtype=np.float32).astype(float)
    full, sent = _columns_of(x, lim, columns, scale, linthresh), \
        _columns_of(xs, lim, columns, scale, linthresh)
    ok, oks = np.isfinite(y) & (full != -2), np.isfinite(ys) & (sent != -2)
    for c in np.unique(full[ok]):
        yf, ysent = y[ok & (full == c)], ys[oks & (sent == c)]
        assert ysent.size, f"column {c}: no point sent"
        assert ysent.min() == pytest.approx(yf.min(), rel=1e-6, abs=1e-30), c
        assert ysent.max() == pytest.approx(yf.max(), rel=1e-6, abs=1e-30), c


def _sent(fig, axes=0, series=0):
    d = describe(fig)
    s = d.frame["axes"][axes]["series"][series]
    return d.values(s["x"]).astype(float), d.values(s["y"]).astype(float)


def _columns(fig, ax):
    return math.ceil(fig.get_size_inches()[0] * 100 * ax.get_subplotspec().colspan.stop
                     / ax.get_subplotspec().get_gridspec().get_geometry()[1]
                     - fig.get_size_inches()[0] * 100 * ax.get_subplotspec().colspan.start
                     / ax.get_subplotspec().get_gridspec().get_geometry()[1])


def test_a_ring_down_of_20000_points_is_sent_as_its_column_extremes():
    fig = Figure(figsize=(10, 4))
    ax = fig.add_subplot(1, 2, 2)
    t = np.linspace(0.0, 300.0, 20_000)
    y = np.exp(-t / 80) * np.cos(2 * np.pi * t)
    line, = ax.plot(t, y)
    ax.set_xlim(0.0, 300.0)
    xs, ys = _sent(fig)
    columns = _columns(fig, ax)
    assert columns == 500
    assert xs.size <= 4 * (columns + 2) < t.size / 4  # a fifth of the points, or fewer
    assert (xs[0], ys[0]) == (np.float32(t[0]), np.float32(y[0]))
    assert (xs[-1], ys[-1]) == (np.float32(t[-1]), np.float32(y[-1]))
    assert np.all(np.diff(xs) > 0)  # a subset, in the line's order
    assert set(xs.tolist()) <= set(t.astype(np.float32).tolist())
    _check_envelope(t, y, xs, ys, (0.0, 300.0), columns)
    np.testing.assert_array_equal(line.get_ydata(), y)  # the artist keeps the full data


def test_gaps_log_axes_points_off_the_view_and_loops_are_drawn_alike():
    rng = np.random.default_rng(24)
    n = 30_000
    # a log x axis, NaN gaps and points beyond the limits on both sides
    x = np.logspace(-3, 3, n)
    y = np.exp(rng.normal(size=n).cumsum() / 50)
    y[1000:1200] = np.nan
    y[5000] = np.nan
    fig = Figure(figsize=(6, 4))
    ax = fig.add_subplot()
    ax.plot(x, y)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlim(1e-2, 1e2)
    xs, ys = _sent(fig)
    assert xs.size < n / 5
    _check_envelope(x, y, xs, ys, (1e-2, 1e2), 600, "log")
    # each gap is still a gap: a NaN sent between the points around it
    for lo, hi in ((999, 1200), (4999, 5001)):
        between = (xs > np.float32(x[lo])) & (xs < np.float32(x[hi]))
        assert np.isnan(ys[between]).any(), (lo, hi)
    assert xs[0] == np.float32(x[0]) and xs[-1] == np.float32(x[-1])  # off the view: kept
    # trace and retrace (x goes there and back): each pass keeps its own extremes
    x2 = np.r_[np.linspace(0, 1, n), np.linspace(1, 0, n)]
    y2 = np.r_[np.sin(300 * x2[:n]), 0.5 * np.cos(300 * x2[n:])]
    keep = decimate(x2, y2, lim=(0.0, 1.0), columns=400)
    assert keep.size < x2.size / 10 and keep[0] == 0 and keep[-1] == x2.size - 1
    for half in (slice(0, n), slice(n, 2 * n)):
        k = keep[(keep >= half.start) & (keep < half.stop)]
        _check_envelope(x2[half], y2[half], x2[k], y2[k], (0.0, 1.0), 400)


def test_short_lines_and_markers_are_sent_whole():
    fig = Figure(figsize=(4, 3))
    ax = fig.add_subplot()
    x = np.linspace(0, 1, 1000)  # 2.5 points per column of 400: nothing to gain
    ax.plot(x, np.sin(50 * x))
    xm = np.linspace(0, 1, 20_000)
    ax.plot(xm, np.cos(50 * xm), ".", ms=1)  # markers: every one is drawn
    d = describe(fig)
    assert [len(d.values(s["x"])) for s in d.frame["axes"][0]["series"]] == [1000, 20_000]


def test_the_q_control_panel_sends_a_quarter_of_its_points_drawn_alike():
    from afmsmiler.ui.haptic import QControlPanel
    p = QControlPanel()
    d = describe(p.fig)
    sent = full = 0
    for i, ax in enumerate(a for a in p.fig.axes if a.get_subplotspec() is not None):
        series = d.frame["axes"][i]["series"]
        assert len(series) == len(ax.lines)
        for s, line in zip(series, ax.lines):
            x, y = np.asarray(line.get_xdata(), float), np.asarray(line.get_ydata(), float)
            xs, ys = d.values(s["x"]).astype(float), d.values(s["y"]).astype(float)
            sent, full = sent + xs.size, full + x.size
            _check_envelope(x, y, xs, ys, ax.get_xlim(), _columns(p.fig, ax),
                            ax.get_xscale())
    assert full > 20_000 and sent < full / 3


@pytest.mark.parametrize("kwargs, message", [
    (dict(x=[0.0, 1.0], y=[0.0]), "x and y must have one length, got 2 and 1"),
    (dict(lim=(1.0, 1.0)), "lim must be two distinct finite numbers"),
    (dict(lim=(0.0, float("nan"))), "lim must be a finite"),
    (dict(columns=0), "columns must be an integer"),
    (dict(xscale="logit"), "xscale must be one of"),
])
def test_decimate_names_what_it_cannot_take(kwargs, message):
    args = dict(x=[0.0, 1.0], y=[0.0, 1.0], lim=(0.0, 1.0), columns=10)
    args.update(kwargs)
    with pytest.raises(ValueError, match=message):
        decimate(**args)
