"""The live figure's description of a matplotlib figure, checked against matplotlib's own artists.

:func:`afmsmiler.plots.live.describe` is what the browser draws; every number in it must be the one
the figure's artists hold (the panels' tests check those against the models), and what it cannot
show must fail loudly instead of vanishing from the student's screen.
"""
import hashlib
import json
import re

import matplotlib
import numpy as np
import pytest
from matplotlib.figure import Figure
from matplotlib.ticker import FixedLocator, FuncFormatter

from afmsmiler.plots import live
from afmsmiler.plots.live import LiveFigure, describe, static_html


def _series(d, axes=0):
    return [(d.values(s["x"]), d.values(s["y"])) for s in d.frame["axes"][axes]["series"]]


def test_lines_arrive_as_float32_with_their_nan_gaps_and_styles():
    fig = Figure(figsize=(4, 3))
    ax = fig.add_subplot()
    x = np.linspace(0.0, 1.0, 11)
    y = np.sin(x)
    y[4] = np.nan  # a gap
    ax.plot(x, y, "--", color="C3", lw=2, label="curve")
    ax.plot([0.5], [0.2], "o", ms=6, color="k")
    d = describe(fig)
    (x0, y0), (x1, y1) = _series(d)
    np.testing.assert_array_equal(x0, x.astype(np.float32))
    np.testing.assert_array_equal(np.isnan(y0), np.isnan(y))
    np.testing.assert_array_equal(y0[~np.isnan(y)], y[~np.isnan(y)].astype(np.float32))
    line, marker = d.layout["axes"][0]["series"]
    assert line["color"] == matplotlib.colors.to_hex("C3", keep_alpha=True)
    assert line["line"] and line["marker"] is None
    assert line["width"] == pytest.approx(2 * 100 / 72)  # points -> px at 100 dpi
    # matplotlib's dash pattern for "--", in points scaled by the width, then in px
    assert line["dash"] == pytest.approx([3.7 * 2 * 100 / 72, 1.6 * 2 * 100 / 72])
    assert marker["marker"] == "o" and marker["filled"]
    # labels travel with the frame (they change with the data); "_child1" is matplotlib's "none"
    assert [s["label"] for s in d.frame["axes"][0]["series"]] == ["curve", ""]
    assert d.layout["width"] == 400 and d.layout["height"] == 300


def test_a_line_with_markers_is_a_line_and_its_markers_on_the_same_data():
    fig = Figure()
    ax = fig.add_subplot()
    ax.plot([0, 1, 2], [1, 0, 1], marker=".", color="C2")
    d = describe(fig)
    a, b = d.frame["axes"][0]["series"]
    assert a == b  # the same place in the buffer, drawn twice
    kinds = [(s["line"], s["marker"]) for s in d.layout["axes"][0]["series"]]
    assert kinds == [(True, None), (False, ".")]


def test_limits_labels_titles_and_texts_are_the_artists_own():
    fig = Figure()
    ax = fig.add_subplot()
    ax.plot([0, 1], [0, 2])
    ax.set(xlim=(-1, 3), ylim=(0.5, 7.5), xlabel="x [um]", ylabel="F [nN]", title="two\nlines")
    ax.yaxis.label.set_color("C4")
    ax.text(0.02, 0.95, "off scale", transform=ax.transAxes, va="top", color="C3")
    ax.text(1.0, 2.0, "here", ha="right")
    fig.suptitle("suptitle")
    f = describe(fig).frame
    a = f["axes"][0]
    assert a["axes"]["x"]["lim"] == [-1, 3] and a["axes"]["y"]["lim"] == [0.5, 7.5]
    assert a["axes"]["x"]["label"] == "x [um]" and a["axes"]["y"]["label"] == "F [nN]"
    assert a["axes"]["y"]["color"] == matplotlib.colors.to_hex("C4", keep_alpha=True)
    assert a["title"]["text"] == "two\nlines" and f["suptitle"] == "suptitle"
    t_axes, t_data = a["texts"]
    assert (t_axes["coords"], t_axes["x"], t_axes["y"], t_axes["va"]) == ("axes", 0.02, 0.95, "top")
    assert (t_data["coords"], t_data["x"], t_data["y"], t_data["ha"]) == ("data", 1.0, 2.0, "right")


def test_reference_lines_and_spans_keep_their_place():
    fig = Figure()
    ax = fig.add_subplot()
    ax.plot([0, 1], [0, 1])
    ax.axvline(0.25, color="0.6", ls=":")
    ax.axhline(0.5, xmin=0.1, xmax=0.9)
    ax.axvspan(-1e30, 0.0, color="C2", alpha=0.1)
    ax.axhspan(0.2, 0.4, color="C3", alpha=0.5)
    f = describe(fig).frame["axes"][0]
    v, h = f["refs"]
    assert (v["kind"], v["at"], v["from"], v["to"]) == ("v", 0.25, 0.0, 1.0) and v["dash"]
    assert (h["kind"], h["at"], h["from"], h["to"]) == ("h", 0.5, 0.1, 0.9) and h["dash"] is None
    sv, sh = f["spans"]
    assert (sv["kind"], sv["lo"], sv["hi"]) == ("v", -1e30, 0.0)
    assert (sh["kind"], sh["lo"], sh["hi"]) == ("h", 0.2, 0.4)
    assert sh["color"] == matplotlib.colors.to_hex((*matplotlib.colors.to_rgb("C3"), 0.5),
                                                   keep_alpha=True)


def test_twin_and_secondary_axes():
    fig = Figure()
    ax = fig.add_subplot()
    ax.plot([0, 1], [0, 1])
    twin = ax.twinx()
    twin.plot([0, 1], [10, 30], color="C1")
    twin.set_ylim(5, 35)
    twin.set_ylabel("right [mV]")
    e = 169.0  # a stress/strain axis: strain [1e-6] = stress [MPa] / E [GPa] * 1e3
    sec = ax.secondary_xaxis("top", functions=(lambda s: s / e * 1e3, lambda s: s * e / 1e3))
    sec.set_xlabel("strain [microstrain]")
    ax.set_xlim(-2, 2)
    d = describe(fig)
    la, fa = d.layout["axes"], d.frame["axes"]
    assert len(la) == 1  # the twin draws into its host
    assert la[0]["y2"]["visible"] and fa[0]["axes"]["y2"]["lim"] == [5, 35]
    assert fa[0]["axes"]["y2"]["label"] == "right [mV]"
    assert [s["axis"] for s in la[0]["series"]] == ["y", "y2"]
    x2 = fa[0]["axes"]["x2"]
    assert x2["label"] == "strain [microstrain]"
    assert x2["lim"] == pytest.approx([-2 / e * 1e3, 2 / e * 1e3])
    twin.set_visible(False)
    d = describe(fig)
    assert not d.layout["axes"][0]["y2"]["visible"] and len(d.frame["axes"][0]["series"]) == 1


def test_a_curved_secondary_axis_is_refused():
    fig = Figure()
    ax = fig.add_subplot()
    ax.set_xlim(1, 10)
    ax.secondary_xaxis("top", functions=(np.log10, lambda v: 10 ** v))
    with pytest.raises(NotImplementedError, match="linear secondary"):
        describe(fig)


def test_log_symlog_and_fixed_ticks():
    fig = Figure()
    a, b = fig.subplots(1, 2)
    a.loglog([1, 10, 100], [1e-3, 1e-4, 1e-5])
    b.plot([-1, 1], [0, 1])
    b.set_xscale("symlog", linthresh=0.01)
    b.xaxis.set_major_locator(FixedLocator([-1.0, 0.0, 1.0, 5.0]))
    b.xaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}!"))
    b.set_xlim(-2, 2)
    d = describe(fig)
    assert d.layout["axes"][0]["x"]["scale"] == "log" and d.layout["axes"][0]["y"]["scale"] == "log"
    assert d.layout["axes"][1]["x"]["scale"] == "symlog"
    x = d.frame["axes"][1]["axes"]["x"]
    assert x["linthresh"] == 0.01
    assert x["ticks"] == [-1.0, 0.0, 1.0] and x["ticklabels"] == ["-1!", "0!", "1!"]  # in range


def test_grid_spans_ratios_legends_and_equal_aspect():
    fig = Figure()
    gs = fig.add_gridspec(2, 3, width_ratios=[1, 2, 1])
    a = fig.add_subplot(gs[0, :2])
    b = fig.add_subplot(gs[1, :2])
    c = fig.add_subplot(gs[:, 2])
    la, = a.plot([0, 1], [0, 1], label="trace")
    lb, = a.plot([0, 1], [1, 0], ls="--", label="retrace")
    b.plot([0, 1], [0, 1])
    c.plot([0, 1], [0, 1])
    c.set_aspect("equal")
    a.legend()
    fig.legend(handles=[la, lb], loc="outside upper left")
    d = describe(fig)
    pos = [(x["row"], x["rowspan"], x["col"], x["colspan"]) for x in d.layout["axes"]]
    assert pos == [(0, 1, 0, 2), (1, 1, 0, 2), (0, 2, 2, 1)]
    assert d.layout["col_ratios"] == [1, 2, 1] and d.layout["row_ratios"] == [1, 1]
    assert [x["aspect"] for x in d.layout["axes"]] == [None, None, "equal"]
    entries = d.frame["axes"][0]["legend"]
    assert [(e["label"], e["dash"]) for e in entries] == [("trace", False), ("retrace", True)]
    assert [e["label"] for e in d.frame["legend"]] == ["trace", "retrace"]


def test_images_carry_their_values_extent_and_matplotlibs_colour_map():
    fig = Figure()
    ax = fig.add_subplot()
    z = np.arange(12.0).reshape(3, 4)
    z[2, 1] = np.nan  # a pixel not scanned yet
    im = ax.imshow(z, origin="lower", extent=(0, 4, 0, 3), cmap="afmhot", vmin=0, vmax=11)
    fig.colorbar(im, ax=ax, label="height [nm]")
    d = describe(fig)
    (image,) = d.frame["axes"][0]["images"]
    values = d.values(image["data"]).reshape(image["shape"])
    np.testing.assert_array_equal(np.isnan(values), np.isnan(z))
    np.testing.assert_array_equal(values[~np.isnan(z)], z[~np.isnan(z)])
    assert image["extent"] == [0, 4, 0, 3] and image["origin"] == "lower"
    assert (image["vmin"], image["vmax"]) == (0, 11)
    lut = np.frombuffer(__import__("base64").b64decode(d.layout["luts"]["afmhot"]), np.uint8)
    expected = matplotlib.colormaps["afmhot"](np.linspace(0, 1, 256))[:, :3] * 255
    np.testing.assert_allclose(lut.reshape(256, 3), expected, atol=0.5)
    cb = d.frame["axes"][0]["colorbar"]
    assert cb["label"] == "height [nm]" and (cb["vmin"], cb["vmax"]) == (0, 11)


def test_reference_lines_stack_over_or_under_the_curves_as_matplotlib_draws_them():
    fig = Figure()
    ax = fig.add_subplot()
    ax.axhline(0.0)  # before the curve: under it
    ax.plot([0, 1], [0, 1])
    ax.axvline(0.5)  # after it: over it
    ax.axvline(0.7, zorder=1)  # a lower zorder: under it whatever the order
    refs = describe(fig).frame["axes"][0]["refs"]
    assert [(r["at"], r["over"]) for r in refs] == [(0.0, False), (0.5, True), (0.7, False)]


def test_custom_dashes_reversed_limits_and_hidden_axes():
    fig = Figure()
    ax = fig.add_subplot()
    ax.plot([0, 1], [0, 1], ls=(0, (5, 1)), lw=1)
    ax.set_xlim(1, 0)
    ax.axis("off")
    d = describe(fig)
    assert d.layout["axes"][0]["series"][0]["dash"] == pytest.approx([5 * 100 / 72, 100 / 72])
    assert d.frame["axes"][0]["axes"]["x"]["lim"] == [1, 0]  # the browser draws it reversed
    assert not d.layout["axes"][0]["x"]["show"] and not d.layout["axes"][0]["y"]["show"]


@pytest.mark.parametrize("make, match", [
    (lambda ax: ax.plot([0, 1], [0, 1], "*"), "markers"),
    (lambda ax: ax.set_title("left", loc="left"), "centred titles"),
    (lambda ax: ax.text(0.5, 0.5, "up", rotation=90), "unrotated"),
    (lambda ax: ax.twiny().plot([0, 100], [0, 1]), "shares its place"),
    (lambda ax: ax.fill_between([0, 1], [0, 1]), "collections"),
    (lambda ax: ax.inset_axes([0.5, 0.5, 0.4, 0.4]), "inset"),
    (lambda ax: ax.imshow(np.zeros((2, 2, 3))), "2-D height maps"),
    (lambda ax: ax.set_xscale("logit"), "logit"),
    (lambda ax: ax.text(0.5, 0.5, "f", transform=ax.figure.transFigure), "transform"),
])
def test_what_cannot_be_shown_is_refused_by_name(make, match):
    fig = Figure()
    ax = fig.add_subplot()
    ax.plot([0.1, 0.9], [0.1, 0.9])
    make(ax)
    with pytest.raises(NotImplementedError, match=match):
        describe(fig)


def test_bad_figures_are_refused_before_any_work(monkeypatch):
    with pytest.raises(TypeError, match="fig"):
        describe("a figure")
    with pytest.raises(ValueError, match="at least one axes"):
        describe(Figure())
    monkeypatch.setattr(live, "MAX_VALUES", 100)
    fig = Figure()
    fig.add_subplot().plot(np.arange(60), np.arange(60))
    with pytest.raises(ValueError, match="at most 100 values, got 120"):
        describe(fig)


def test_sync_sends_the_state_the_artists_hold_in_one_message(monkeypatch):
    fig = Figure()
    ax = fig.add_subplot()
    line, = ax.plot([0, 1], [0, 1])
    w = LiveFigure(fig)
    messages = []
    monkeypatch.setattr(w, "send_state", lambda key=None: messages.append(set(key or ())))
    line.set_data([0, 1, 2], [3, 4, 5])
    ax.set_ylim(2, 6)
    w.sync()
    assert len(messages) == 1 and messages[0] == {"_frame", "_buffer"}  # the layout is unchanged
    assert w._frame["seq"] == w.frames_sent == 2
    got = np.frombuffer(w._buffer, "<f4")
    np.testing.assert_array_equal(got, [0, 1, 2, 3, 4, 5])
    assert w._frame["axes"][0]["axes"]["y"]["lim"] == [2, 6]
    json.dumps(w._layout, allow_nan=False), json.dumps(w._frame, allow_nan=False)  # valid JSON
    w.sync()  # nothing changed since: no message, the browser draws nothing
    assert len(messages) == 1 and w.frames_sent == 2
    line.set_ydata([3, 4, 6])
    w.sync()
    assert len(messages) == 2 and w._frame["seq"] == 3


def test_static_html_is_self_contained():
    fig = Figure()
    ax = fig.add_subplot()
    ax.plot([0, 1], [0, 1], label="</script><b>")
    ax.legend()
    page = static_html(fig)
    assert page.count("</script>") == 1  # a label cannot close the script early
    assert not re.search(r"""(src|href)\s*=\s*["']?https?:""", page)  # no network
    assert "drawStatic(" in page and "uPlot" in page


def test_the_shipped_uplot_files_are_the_ones_the_vendoring_script_recorded():
    manifest = json.loads((live.STATIC / "uPlot.json").read_text())
    assert manifest["package"] == "uplot" and manifest["licence"] == "MIT"
    for name, digest in manifest["files"].items():
        assert hashlib.sha256((live.STATIC / name).read_bytes()).hexdigest() == digest, name
    assert "MIT License" in (live.STATIC / "uPlot.LICENSE").read_text()
    assert f"uplot-{manifest['version']}.tgz" in manifest["source"]


def _colour_bar_figure(quiet: bool):
    """A figure whose image's limits changed after a first draw: by set_clim or by matplotlib."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    fig = Figure(figsize=(4, 3))
    ax = fig.add_subplot()
    im = ax.imshow(np.random.default_rng(0).random((5, 5)))
    bar = fig.colorbar(im, ax=ax, label="height [nm]")
    FigureCanvasAgg(fig).draw()
    im.set_data(np.random.default_rng(1).random((5, 5)) * 7.0)
    calls = []
    bar.ax.callbacks.connect("ylim_changed", lambda _ax: calls.append(1))
    if quiet:
        live.set_clim(im, -1.0, 8.0)
    else:
        im.set_clim(-1.0, 8.0)
    frame = describe(fig).frame["axes"][0]["colorbar"]
    redrawn = bool(calls)
    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    return np.asarray(canvas.buffer_rgba()).copy(), frame, redrawn, im


def test_set_clim_leaves_the_colour_bar_to_the_browser_and_to_the_next_raster():
    # issue 24: the force-volume panel spent 21 ms per move redrawing colour bars the browser
    # never showed; set_clim sends the same limits and an Agg draw gives the same pixels
    quiet, quiet_frame, quiet_redrawn, im = _colour_bar_figure(True)
    full, full_frame, full_redrawn, _ = _colour_bar_figure(False)
    assert quiet_frame == full_frame == {"label": "height [nm]", "cmap": "viridis",
                                         "vmin": -1.0, "vmax": 8.0}
    assert full_redrawn and not quiet_redrawn  # no colour-bar work before a raster
    np.testing.assert_array_equal(quiet, full)
    assert im.get_clim() == (-1.0, 8.0)
    live.set_clim(Figure().add_subplot().imshow(np.eye(2)), 0.0, 2.0)  # no colour bar: fine


def test_set_clim_names_what_is_not_an_image():
    with pytest.raises(TypeError, match="image"):
        live.set_clim(np.eye(2), 0.0, 1.0)
