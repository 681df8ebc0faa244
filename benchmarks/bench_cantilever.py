"""Module (a): one slider update of the cantilever panel (model + plot data + 3D scene update).

Target (issue 2): well under 30 ms per update. Split into its parts:

- model: build the Cantilever from slider values and run ``Cantilever.bending`` once (deflection,
  slope and the 121 x 9 stress field, a 41-point section, f1..f3 and their mode shapes), then
  convert it to the units shown;
- plots: move the line data of the four panels in place (``CantileverFigure.update``; the pixels
  are drawn by the browser from the data the panel sends, see bench_browser.py for key press to
  pixels; the kernel's part, describing the artists for the browser, is timed here for information);
- scene: rebuild the beam mesh (121 x 9) with vertex colors from the same result and send it,
  move tip and arrow (``CantileverScene.update``, into a running meshcat server);
- the whole ``CantileverPanel.update``, and its worst case, when every update moves the color
  limit across a round number so that the legend texture is re-rendered too.

Peer: the same update done naively, rebuilding the figure and all scene objects instead of
updating them in place.
"""
import contextlib
import io
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))

from _timing import best_time, report  # noqa: E402

from matplotlib.backends.backend_agg import FigureCanvasAgg  # noqa: E402

from afmsmiler.plots.live import describe  # noqa: E402

from afmsmiler.cantilever import PARAMETERS, Cantilever  # noqa: E402
from afmsmiler.plots.cantilever import CantileverFigure, cantilever_curves  # noqa: E402
from afmsmiler.scenes.cantilever import CantileverScene  # noqa: E402
from afmsmiler.ui.cantilever import CantileverPanel  # noqa: E402

TARGET = 30e-3


def main():
    with contextlib.redirect_stdout(io.StringIO()):  # its first redraw prints outside Jupyter
        panel = CantileverPanel(scene=True)
    panel.redraw = lambda: None  # pixels are drawn by the front end, after the callback
    values = panel.values()
    state = {"i": 0}

    def next_values():  # a slider being dragged: the force changes every call
        state["i"] += 1
        return {**values, "force": 50.0 + (state["i"] % 100)}

    def si(v):
        return {k: PARAMETERS[k].to_si(x) for k, x in v.items() if k in PARAMETERS}

    def bending(v):
        s = si(v)
        lever = Cantilever(s["length"], s["width"], s["thickness"], s["youngs_modulus"],
                           s["density"])
        return lever.bending(s["force"], section=s["section"], n_length=121, n_thickness=9,
                             n_section=41, modes=3)

    def model():
        b = bending(next_values())
        return b, cantilever_curves(b)

    result, curves = model()
    t_model = best_time(model)
    t_plots = best_time(lambda: panel.figure.update(curves))
    t_scene = best_time(lambda: panel.scene.update(bending(next_values())))
    t_panel = best_time(lambda: panel.update(**next_values()))

    def crossing():  # worst case: every update crosses a round color limit (1 <-> 2 MPa)
        state["i"] += 1
        panel.update(**{**values, "force": 70.0 if state["i"] % 2 else 80.0})

    t_cross = best_time(crossing)
    t_describe = best_time(lambda: describe(panel.fig))
    canvas = FigureCanvasAgg(panel.fig)
    t_draw = best_time(canvas.draw, repeat=3)

    def naive():
        b = bending(next_values())
        CantileverFigure(cantilever_curves(b))
        panel.scene.root["bench_naive"].delete()
        CantileverScene(b, vis=panel.scene.root, path="bench_naive", camera=False)

    t_naive = best_time(naive, repeat=3)
    print("one slider update of CantileverPanel (3D view over the comm; the figure is sent as data,"
          " not rasterised; the browser's drawing is in bench_browser.py)")
    report([
        ("model: Cantilever.bending once (121 x 9 + 41 pts, 3 modes)", t_model, None, None),
        ("plots: CantileverFigure.update (line data in place)", t_plots, None, None),
        ("scene: CantileverScene.update (121 x 9 mesh, tip, arrow)", t_scene, None, None),
        ("whole CantileverPanel.update (model + plots + scene)", t_panel, TARGET, t_naive),
        ("  same, each update re-rendering the legend texture", t_cross, TARGET, t_naive),
        ("(info) of which: the figure described for the browser", t_describe, None, None),
        ("(info) what a move cost before: Agg rasterising the figure", t_draw, None, None),
    ])
    print(f"peer = naive update rebuilding figure and scene objects: {t_naive * 1e3:.1f} ms")


if __name__ == "__main__":
    main()
