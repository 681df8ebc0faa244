"""Every figure a student sees says what its axes are and in which unit, and its texts are legible.

Loops over the figures of every widget panel of the registry (the transducer panel once per
principle) and the
stand-alone figure builders the notebooks call, draws each one (Agg), and checks every visible
axis that shows tick labels: it must have a label with a unit in square brackets, e.g.
``"x [um]"``, or say that the quantity is ``"(dimensionless)"``. Axes without tick labels (shared
axes, the block diagram) need no label. Titles and axis labels of different axes must not overlap,
and no axis may be left empty.
"""
import re

import matplotlib
import numpy as np
import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from afmsmiler import data
from afmsmiler.ui.registry import PANELS

matplotlib.use("Agg")

UNIT = re.compile(r"\[[^\]]+\]|\(dimensionless\)")
DATA = data.path("spot3-0192.jpk-force")


def _cantilever_panel(**values):
    from afmsmiler.ui.cantilever import CantileverPanel
    panel = CantileverPanel(scene=False)
    panel.set(**values)
    return panel.fig


def _mode_shapes():
    from afmsmiler.cantilever import Cantilever
    from afmsmiler.plots.cantilever import mode_shapes_figure
    lever = Cantilever.from_material("silicon", length=450e-6, width=50e-6, thickness=2e-6)
    return mode_shapes_figure(lever)[0]


def _transducer_panel(principle):
    from afmsmiler.ui.transducers import TransducerPanel
    return TransducerPanel(principle=principle, scene=False).fig


def _contact_panel():
    from afmsmiler.ui.contact import ContactPanel
    return ContactPanel(scene=False).fig


def _contact_figures():
    from afmsmiler.contact import Parabolic, approach_retract, fit_curve, load_curve
    from afmsmiler.plots.contact import cycles_figure, fit_figure, tip_geometries_figure
    tip, ramp = Parabolic(50e-9), np.linspace(-150e-9, 40e-9, 200)
    cycles = {m: approach_retract(ramp, 0.1, tip, 20e6, 0.3, adhesion=m, work_of_adhesion=0.03)
              for m in ("dmt", "jkr")}
    curve = load_curve(DATA)
    result = fit_curve(curve.tip_position, curve.force, Parabolic(40e-9), 0.0)
    return [tip_geometries_figure(), cycles_figure(cycles), fit_figure(curve, result)]


def _controller_panel():
    from afmsmiler.ui.controller import ControllerPanel
    return ControllerPanel().fig


def _controller_figures():
    from afmsmiler import samples
    from afmsmiler.controller import PRESETS, scan_image
    from afmsmiler.controller.defaults import line_profile
    from afmsmiler.plots.controller import fig4_figure, image_figure, polygon_figure
    line = line_profile("real line")
    image = samples.particles((32, 32), pixel_size=32e-9)
    scan = scan_image(PRESETS["c_fast_scan"].loop, image.heights, image.pixel_size, speed=1e-3,
                      setpoint=10e-9)
    return [polygon_figure(line.x, line.heights, speed=1e-3, n_show=14,
                           fig=Figure(figsize=(10, 3.2))),
            fig4_figure(),
            image_figure(scan, image.heights)]


def _principles():
    from afmsmiler.transducers import PRINCIPLES
    return list(PRINCIPLES)


FIGURES = {
    # every panel of the registry at its defaults, so a new panel is checked too
    **{f"{e.key} panel": (lambda e=e: [e.make().fig]) for e in PANELS},
    "cantilever panel, pulled down, section mid-way":
        lambda: [_cantilever_panel(force=-300.0, section=0.5)],
    "cantilever panel, no force": lambda: [_cantilever_panel(force=0.0)],
    "mode shapes": lambda: [_mode_shapes()],
    **{f"transducer panel: {k}": (lambda k=k: [_transducer_panel(k)]) for k in _principles()[1:]},
    "contact figures": _contact_figures,
    "controller figures": _controller_figures,
}


def _all_axes(fig):
    for ax in fig.axes:
        yield ax
        yield from ax.child_axes  # secondary axes (e.g. strain over stress)


def _shows_ticks(axis):
    return axis.get_visible() and any(t.get_visible() and t.get_text().strip()
                                      for t in axis.get_ticklabels())


def _texts(ax):
    return [t for t in (ax.title, ax._left_title, ax._right_title, ax.xaxis.label, ax.yaxis.label)
            if t.get_visible() and t.get_text().strip()]


# Building a figure takes about a second for these; `make unit` checks each panel once in its
# default state (one transducer principle, the first) and the rest run under `make test`.
SLOW = {f"transducer panel: {k}" for k in _principles()[1:]} | {
    f"{e.key} panel" for e in PANELS if e.module in "efgh"} | {
    "controller figures", "contact figures", "cantilever panel, no force",
    "cantilever panel, pulled down, section mid-way"}


@pytest.fixture(scope="module", ids=list(FIGURES),
                params=[pytest.param(k, marks=pytest.mark.slow) if k in SLOW else k
                        for k in FIGURES])
def drawn(request):
    figs = FIGURES[request.param]()
    for fig in figs:
        FigureCanvasAgg(fig).draw()  # a pyplot-free Figure has no renderer of its own
    return figs


def test_every_axis_with_ticks_has_a_label_with_a_unit(drawn):
    missing = []
    for fig in drawn:
        for ax in _all_axes(fig):
            if not ax.axison:
                continue
            for name, axis in (("x", ax.xaxis), ("y", ax.yaxis)):
                label = axis.label.get_text() if axis.label.get_visible() else ""
                if _shows_ticks(axis) and not UNIT.search(label):
                    missing.append(f"{ax.get_title()!r}: {name} label {label!r}")
    assert not missing, "axes without a unit: " + "; ".join(missing)


def test_no_title_or_label_overlaps_another_axes_texts(drawn):
    for fig in drawn:
        renderer = fig.canvas.get_renderer()
        boxes = [(id(ax), t.get_text(), t.get_window_extent(renderer))
                 for ax in fig.axes for t in _texts(ax)]
        for i, (a, ta, ba) in enumerate(boxes):
            for b, tb, bb in boxes[i + 1:]:
                if a != b:
                    assert not ba.overlaps(bb), f"{ta!r} overlaps {tb!r}"


def test_tick_labels_are_readable_numbers(drawn):
    """No axis shows values so close to zero that matplotlib writes an offset like 1e-16."""
    for fig in drawn:
        for ax in _all_axes(fig):
            for axis in (ax.xaxis, ax.yaxis):
                offset = axis.get_offset_text().get_text()
                m = re.search(r"1e-(\d+)", offset.replace("\u2212", "-"))
                assert not (m and int(m.group(1)) > 9), f"{ax.get_title()!r}: offset {offset}"


def test_no_axes_is_left_empty(drawn):
    for fig in drawn:
        for ax in fig.axes:
            if ax.axison:
                assert ax.lines or ax.collections or ax.images or ax.patches, ax.get_title()
