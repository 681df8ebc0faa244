"""Module (b): one slider update of the transducer panel (model + plot data + 3D scale model).

The issue names no speed target or peer; one panel update should stay at a few ms (target used
here: 5 ms). Split into its parts, for the slowest of the eleven principles and their mean:

- model: build the model from slider values, sample its chain over the input range (201 points),
  the small-signal sensitivity, the frequency response (400 points) and the resolution;
- plots: move the line data of the three panels in place (``TransducerFigure.update``; the pixels
  are drawn by the browser from the data the panel sends, see bench_browser.py for key press to
  pixels; the kernel's part, describing the artists for the browser, is timed here for information);
- scene: redraw the bent lever and move the principle's parts (``TransducerScene.update``, into a
  running meshcat server);
- the whole ``TransducerPanel.update``.

Peer: the same update done naively, building a new figure (and drawing it) on every call.
"""
import contextlib
import io
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))

from _timing import best_time, report  # noqa: E402

from matplotlib.backends.backend_agg import FigureCanvasAgg  # noqa: E402

from afmsmiler.plots.live import describe  # noqa: E402

from afmsmiler.plots.transducers import (TransducerFigure, chain_curves,  # noqa: E402
                                         frequency_grid)
from afmsmiler.transducers import PRINCIPLES  # noqa: E402
from afmsmiler.ui.transducers import TransducerPanel, to_si  # noqa: E402
from afmsmiler.ui.controls import medium  # noqa: E402

TARGET = 5e-3


def main():
    with contextlib.redirect_stdout(io.StringIO()):
        panel = TransducerPanel(scene=True)
    panel.redraw = lambda: None  # pixels are drawn by the front end, after the callback
    rows = {"model": [], "water": [], "plots": [], "scene": [], "panel": [], "naive": []}
    for key, cls in PRINCIPLES.items():
        panel.set(principle=key)
        values = panel.values()
        q = cls().input_quantity()
        state = {"i": 0}

        def next_input():  # a slider being dragged: the input changes every call
            state["i"] += 1
            return q.default * q.scale * (0.5 + (state["i"] % 100) / 100)

        table = cls.parameter_table()

        def model(fluid=medium(values["fluid"])):
            m = cls(fluid=fluid, **{n: to_si(table[n], v) for n, v in values.items()
                                    if n not in ("principle", "mode", "fluid", "input")})
            op = m.operate(q.to_si(next_input()), frequencies=frequency_grid(m),
                           bandwidth=1e3)
            return op, chain_curves(op)

        op, curves = model()
        rows["model"].append(best_time(model, repeat=3, min_time=0.05))
        rows["water"].append(best_time(lambda: model("water"), repeat=3, min_time=0.05))
        rows["plots"].append(best_time(lambda: panel.figure.update(curves), repeat=3,
                                       min_time=0.05))
        rows["scene"].append(best_time(lambda: panel.scene.update(op),
                                       repeat=3, min_time=0.05))
        rows["panel"].append(best_time(lambda: panel.set(input=next_input()), repeat=3,
                                       min_time=0.05))

        def naive():
            fig = TransducerFigure(chain_curves(op))
            FigureCanvasAgg(fig.fig).draw()

        rows["naive"].append(best_time(naive, repeat=3, number=3))
    t_describe = best_time(lambda: describe(panel.fig), repeat=3, min_time=0.05)
    canvas = FigureCanvasAgg(panel.fig)
    t_draw = best_time(canvas.draw, repeat=3, number=3)
    keys = list(PRINCIPLES)
    worst = {name: (max(t), keys[t.index(max(t))]) for name, t in rows.items()}
    mean = {name: sum(t) / len(t) for name, t in rows.items()}
    report([
        ("model (chain, sensitivity, response, noise), mean", mean["model"], None, None),
        (f"model, slowest ({worst['model'][1]})", worst["model"][0], None, None),
        ("model with the lever in water (Sader's f_R and Q), mean", mean["water"], None, None),
        ("plots: update line data in place, mean", mean["plots"], None, None),
        ("scene: update in place (meshcat), mean", mean["scene"], None, None),
        (f"scene, slowest ({worst['scene'][1]})", worst["scene"][0], None, None),
        ("TransducerPanel.update (all of it), mean", mean["panel"], TARGET, mean["naive"]),
        (f"TransducerPanel.update, slowest ({worst['panel'][1]})", worst["panel"][0], TARGET,
         None),
        ("(info) of which: the figure described for the browser", t_describe, None, None),
        ("(info) what a move cost before: Agg draw of the figure", t_draw, None, None),
        ("(peer) new figure + Agg draw per update, mean", mean["naive"], None, None),
    ])


if __name__ == "__main__":
    main()
