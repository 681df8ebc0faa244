"""Issue 9: slider key press -> changed pixels of each live panel's figure, in a real browser.

Headless Debian Chromium (Playwright, ``/usr/bin/chromium``) against JupyterLab and voila
serving copies of the course notebooks, driven by ``tests/browser.py``: Run All (voila runs
the notebook itself), then per panel one warm-up press and ``PRESSES`` timed presses of the
panel's slider key. A press is timed from its ``keydown`` (``performance.now()`` in a
capture-phase listener) to the first animation frame at which the pixels of the panel's figure
canvases differ (read once the figure's DOM changed, as the floor's text is: reading every
canvas on every frame cost the page 3-6 ms a frame); one that changes nothing within 5 s counts
as failed. Then four drags, there and back (one drag was one sample of a figure that moved by
half from one drag to the next): 15 presses sent without waiting each, and the frames painted: a
live figure records each frame's ``data-seq`` once the rendering update of the animation frame
that drew it has run, so only frames that were painted count (the old count, read in an
animation-frame callback that ran before the figure's catch-up draw, counted frames never
painted), each dated by the animation frame that drew it; the figure's pixels are read once the
drag is over (whether they changed), not during it, where the reads cost the page's main thread
time a student's page does not spend and the floor's drag does not either. The kernel coalesces
the moves that queue while it runs the model, so it may send fewer than 15 frames; the drag is
met when every frame it sent was painted once, the last one is the kernel's last and the pixels
changed; its last frame after the last key is the median of the four. A panel that shows a
coarse answer during a drag and the full one once the slider rests (``full_delay``) also gives
when the coarse answer of the drag's last position was painted (the frame the panel names,
``last_quick_frame``). Then four drags of the
same 15 presses at ``KEY_RATE`` keys a second (``BENCH_BROWSER_KEY_RATE``, default 30; 0: none),
as a held key repeats, the floor's too: the presses above follow each other as soon as the
browser took one, which keeps the page's input queue full so that it handles hardly any message
from the kernel until the keys stop.

JupyterLab runs with its own settings for a notebook's cells, as ``make lab`` serves a student
(JupyterLab 4.6: cells out of view are not rendered, ``contentVisibility``), not with the
browser tests' setting that keeps every cell rendered (``tests.browser.Server``'s
``windowing``).

Beside each panel's latency (JupyterLab) its kernel step: the median time the panel's ``update``
took in the kernel for the timed presses (``Panel.update_seconds``, read back with
``tests.browser.kernel_eval``), so a slow model shows itself, and the CPU time of the kernel's
thread in it (``Panel.update_cpu_seconds``): the step less its waits, so a model slowed by a
busy machine (on 2 cores the browser draws while the kernel computes) shows itself too; and
for the drag the moves the kernel received, the panel updates they became and the frames it
sent.

Peer (the floor), measured in the same run and the same server: an ipywidgets IntSlider whose
observer sets a Label's value, key press -> the label's text changed (the next animation frame
after a MutationObserver saw it): browser -> kernel -> browser, which no figure drawn from the
kernel can beat. The floor is dragged too, as a panel is (15 presses sent without waiting, four
drags): its label's last change after the last key is what ipywidgets' slider allows any
answer from the kernel (it sends a move only once the kernel answered the one before), so each
panel's drag is also given as a ratio to it. Target (issues 9, 24): each panel's median within
1.5x the floor, every frame the kernel sent in a drag painted once and the drag's last frame
within 2x the floor of its last key. ``BENCH_BROWSER_PRESSES`` (default 20),
``BENCH_BROWSER_WHERE`` (default ``lab,voila``) and ``BENCH_BROWSER_PANELS`` (default every
panel of the registry, ``afmsmiler.ui.registry.PANELS``, then the sliders of :data:`EXTRA`;
``key:slider`` moves another slider of a panel; a panel with no slider that redraws at once is
moved but not timed) change the run. Prints a reason and exits 0 when the browser cannot run.

The floor on the panel's own page, beside it: the bench's copy of each course notebook ends with
the floor's cell and a live figure's that runs no model (:func:`tests.browser.append_cell`,
:data:`tests.browser.FLOOR_CODE`, :data:`tests.browser.NULL_FIGURE_CODE`). Once the notebook ran,
before the panel is timed, its floor is pressed ``PRESSES`` times and dragged ``DRAGS`` times
(no paced drags), and, once per page, so is the null figure: the page's own round trip to a
label and to a figure that costs the kernel nothing, beside each panel's (the floor notebook's
presses fall in two groups an animation frame apart, about 21 and 33 ms here, and which one a
run's presses favour moves every ratio; a page's floor and its null figure move with the
panel's page). The targets stay the issue's: against the floor notebook.
"""
import dataclasses
import os
import statistics
import sys
import time
import traceback
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # the checkout, for tests/

from tests import browser as B  # noqa: E402
from afmsmiler.ui.modes import ForceVolumePanel, TappingPanel  # noqa: E402

PRESSES = int(os.environ.get("BENCH_BROWSER_PRESSES", "20"))
WHERE = [w for w in os.environ.get("BENCH_BROWSER_WHERE", "lab,voila").split(",") if w]
#: Sliders timed beside each registry slider (issue 24's table: tapping's free amplitude,
#: force volume's peak force), as ``key:slider``.
EXTRA = ("tapping:free_amplitude", "force_volume:peak_force")
PANELS = [p for p in os.environ.get("BENCH_BROWSER_PANELS",
                                    ",".join((*B.PANELS, *EXTRA))).split(",") if p]
DRAG = 15
#: Drags per panel, there and back (the floor's too): their median is the panel's figure.
DRAGS = 4
TARGET_RATIO = 1.5
#: Seconds the force-volume panel's slider rests before its full map begins.
FV_DELAY = ForceVolumePanel.full_delay
#: Seconds the tapping panel's slider rests before its full curve begins.
TAPPING_DELAY = TappingPanel.full_delay
#: Issue 24: a drag's last frame within this many floors of its last key.
DRAG_RATIO = 2.0
#: Keys a second of the paced drags (``BENCH_BROWSER_KEY_RATE``; 0: none): a held key repeats
#: some 30 times a second. The drags above send each key as soon as the browser took the one
#: before, which keeps the page's input queue full: it then handles hardly any message from the
#: kernel until the keys stop, which a student's held key or mouse drag does not do.
KEY_RATE = float(os.environ.get("BENCH_BROWSER_KEY_RATE", "30"))
if not 0 <= KEY_RATE <= 1000:
    raise SystemExit(f"BENCH_BROWSER_KEY_RATE must be 0 (no paced drags) to 1000 keys a second, "
                     f"got {KEY_RATE:g}")


def _ms(t):
    return "      -" if t is None else f"{t * 1e3:7.1f}"


#: The floor's drag times (s from the last key to the label's last change) of each kind.
_RUNS = {"drag": "drags", "paced": "paced_drags"}


def _floor(where, server, page):
    if where == "lab":
        B.open_lab(page, server, B.FLOOR_NOTEBOOK)
        B.run_all(page)
    else:
        B.open_voila(page, server, B.FLOOR_NOTEBOOK, B.FLOOR_SLIDER)
    return _page_floor(page, paced=True)


def _page_floor(page, *, paced: bool = False):
    """The floor's cell on the open page (the floor notebook's, or the one at the end of a
    panel's notebook, :data:`tests.browser.FLOOR_CODE`): ``PRESSES`` presses and ``DRAGS`` drags
    of its slider, and as many paced ones with ``paced``; the presses' :func:`tests.browser.summary`
    with their ``times`` and each kind's drags and median (``drags``, ``drag_after``, ...)."""
    slider = B.find_slider(page, B.FLOOR_SLIDER)
    B.mark_text(page, slider)
    B.press_text(page, slider, "ArrowRight", 2)  # warm-up
    times = B.press_text(page, slider, "ArrowRight", PRESSES)
    stats = B.summary(times)
    stats["times"] = [t for t in times if t is not None]
    for label, rate in (("drag", 0.0), ("paced", KEY_RATE)):
        if label == "paced" and not (paced and rate):
            continue
        runs = [_floor_drag(page, slider, key, 1.0 / rate if rate else 0.0)
                for key in ("ArrowRight", "ArrowLeft") * (DRAGS // 2)]
        runs = [d for d in runs if d is not None]
        stats[_RUNS[label]] = runs
        stats[f"{label}_after"] = statistics.median(runs) if runs else None
    return stats


def _pool(floor, again):
    """The floor of the whole run: the presses and drags of its start and its end together
    (one sample of a shared machine moved by half from one run to the next); ``floor`` is
    updated in place, so every panel's ratio is taken against it."""
    times = floor["times"] + again["times"]
    floor.update(times=times, median=statistics.median(times) if times else None)
    for label in ("drag", "paced"):
        runs = floor.get(_RUNS[label], []) + again.get(_RUNS[label], [])
        floor[_RUNS[label]] = runs
        floor[f"{label}_after"] = statistics.median(runs) if runs else None


#: The floor's drag: the label's changes dated at the animation frame after each (as a press of
#: the floor is), and the keys at their keydown; resolves once 0.6 s passed without either.
_TEXT_DRAG_JS = r"""
([n]) => { window.__afmTextDrag = new Promise(resolve => {
  const label = document.querySelector('[data-afm-panel]');
  const st = {keys: [], changes: []};
  const obs = new MutationObserver(() => requestAnimationFrame(ts => st.changes.push(ts)));
  obs.observe(label, {subtree: true, childList: true, characterData: true});
  const onKey = () => st.keys.push(performance.now());
  window.addEventListener('keydown', onKey, true);
  const start = performance.now();
  const tick = () => {
    const now = performance.now();
    const last = Math.max(start, ...st.keys, ...st.changes);
    if ((st.keys.length >= n && now - last > 600) || now - start > 20000) {
      obs.disconnect();
      window.removeEventListener('keydown', onKey, true);
      resolve(st);
    } else setTimeout(tick, 50);
  };
  tick();
}); }
"""


def _floor_drag(page, slider, key, interval=0.0):
    """The floor dragged as a panel is: ``DRAG`` presses sent without waiting (or ``interval``
    s apart, :func:`tests.browser.press_keys`); s from the last key to the label's last change
    (None if it never changed after it)."""
    page.evaluate(_TEXT_DRAG_JS, [DRAG])
    slider.focus()
    B.press_keys(page, key, DRAG, interval)
    st = page.evaluate("() => window.__afmTextDrag")
    if not st["keys"] or not st["changes"] or st["changes"][-1] < st["keys"][-1]:
        return None
    return (st["changes"][-1] - st["keys"][-1]) / 1e3


def _null_figure(page, selector):
    """The live figure without a model on the panel's page (the null figure's cell at the end of
    its notebook, :data:`tests.browser.NULL_FIGURE_CODE`): its presses and fast drags, timed as a
    panel's are; ``{"median": s, "drag_after": s}``."""
    slider = B.find_slider(page, B.NULL_FIGURE_SLIDER)
    B.focus_panel(page, slider, selector)
    B.press(page, slider, "ArrowRight", 2, selector=selector)  # warm-up
    times = B.press(page, slider, "ArrowRight", PRESSES, selector=selector)
    stats = B.summary(times)
    runs = []
    for key in ("ArrowRight", "ArrowLeft") * (DRAGS // 2):
        drag = B.drag(page, slider, key, DRAG, selector=selector)
        B.settle(page, selector, quiet=0.5, timeout=5)
        if drag.painted_once and drag.after_last_key_s is not None:
            runs.append(drag.after_last_key_s)
    stats["drag_after"] = statistics.median(runs) if runs else None
    return stats


def _entry(name):
    """The registry's entry of ``name`` (``key`` or ``key:slider``: that slider moved instead)."""
    key, _, slider = name.partition(":")
    e = B.PANELS[key]
    return dataclasses.replace(e, slider=slider) if slider else e


def _panel(where, server, page, name, selector):
    e = _entry(name)
    notebook, description = e.notebook, e.slider_selector
    t0 = time.monotonic()
    if where == "lab":
        B.open_lab(page, server, notebook)
        B.run_all(page)
    else:
        B.open_voila(page, server, notebook, description)
    ready = time.monotonic() - t0
    page_floor = _page_floor(page)
    null = None
    if (where, notebook) not in _NULL_DONE:  # once per page
        _NULL_DONE.add((where, notebook))
        null = _null_figure(page, selector)
    slider = B.find_control(page, e)
    selector = f"{e.selector} {selector}"
    B.focus_panel(page, slider, selector)
    key, back = B.keys(slider)
    B.press(page, slider, key, 1, selector=selector)  # warm-up
    detail = B.press_detail(page, slider, key, PRESSES, selector=selector)
    stats = B.summary([d["dt"] for d in detail])
    readouts = [d["readout"] for d in detail if d["readout"] is not None]
    stats["readout"] = statistics.median(readouts) if readouts else None
    if where == "lab":
        step, cpu = B.kernel_eval(
            page, f"import statistics as _st; "
                  f"print(_st.median(list({e.variable}.update_seconds)[-{PRESSES}:]), "
                  f"_st.median(list({e.variable}.update_cpu_seconds)[-{PRESSES}:]))").split()
        stats["step"], stats["step_cpu"] = float(step), float(cpu)
    stats["ready"] = ready
    stats["page_floor"] = page_floor
    stats["null"] = null
    for label, rate in (("drag", 0.0), ("paced", KEY_RATE)):
        if label == "paced" and not rate:
            continue
        drags = []
        quick = []  # a quick answer's frame of the drag's last position, after the last key
        for way in (key, back) * (DRAGS // 2):  # there and back, as the floor is dragged
            counters = _counters(page, e.variable) if where == "lab" else None
            drag = B.drag(page, slider, way, DRAG, selector=selector,
                          interval=1.0 / rate if rate else 0.0)
            B.settle(page, selector, quiet=0.5, timeout=5)
            kernel = None
            if counters is not None:
                after = _counters(page, e.variable)
                kernel = {k: after[k] - counters[k] for k in ("moves", "runs", "frames")}
                kernel["last"] = after["frames"]
                if after["quick"] is not None and after["quick"] != counters["quick"]:
                    quick.append(drag.painted_at_s(after["quick"]))
            drags.append((drag, kernel))
        afters = [d.after_last_key_s for d, _ in drags if d.after_last_key_s is not None]
        stats[f"{label}_runs"] = drags
        stats[f"{label}_after"] = statistics.median(afters) if afters else None
        quick = [t for t in quick if t is not None]
        stats[f"{label}_quick"] = statistics.median(quick) if quick else None
    stats["shown"] = B.slider_value(slider)
    if where == "lab":
        stats["kernel"] = B.kernel_eval(
            page, f"print(repr({e.variable}.values()[{e.slider!r}]))").strip()
    return stats


#: The pages (where, notebook) whose null figure was timed.
_NULL_DONE = set()


def _counters(page, variable):
    """The kernel's counts for a panel: moves received, updates run, frames sent, and the frame
    of its last quick answer (None for a panel that gives none)."""
    text = B.kernel_eval(page, f"print({variable}.moves_received, {variable}.updates, "
                               f"{variable}.live.frames_sent, "
                               f"getattr({variable}, 'last_quick_frame', None))")
    moves, runs, frames, quick = text.split()
    return {"moves": int(moves), "runs": int(runs), "frames": int(frames),
            "quick": None if quick == "None" else int(quick)}


def _row(where, name, s, floor):
    ratio = ""
    if s.get("median") is not None and floor and floor.get("median"):
        r = s["median"] / floor["median"]
        ratio = f"{r:6.1f}x {'OK' if r <= TARGET_RATIO else 'MISSED'}"
    drags = s.get("drag_runs") or []  # the floor's drags are times only (its own line)
    drawn = _drag_text(drags, s.get("drag_after"), floor, "drag", s.get("drag_quick"))
    kernel = ""
    for drag, _ in drags + (s.get("paced_runs") or []):
        if drag.jumped_back:
            back = drag.jumped_back
            kernel += (f"(slider jumped back {len(back)} times, e.g. {', '.join(back[:3])}; "
                       f"{'never settled' if drag.timed_out else 'settled'}) ")
    if "kernel" in s:
        kernel += f"slider {s['shown']} / kernel {s['kernel']}"
    elif "shown" in s:
        kernel += f"slider {s['shown']}"
    print(f"{where:<6s}{name:<24s}{_ms(s.get('median'))} ms {_ms(s.get('worst'))} ms "
          f"{s['failed']:3d}/{s['n']:<3d} {ratio:<13s} {_ms(s.get('step'))} ms "
          f"{_ms(s.get('step_cpu'))} ms "
          f"{_ms(s.get('readout'))} ms  {drawn:<60s} {kernel}", flush=True)
    pf = s.get("page_floor")
    if pf and pf.get("median") and s.get("median"):
        text = (f"on its page: the floor {pf['median'] * 1e3:.1f} ms (its label's last change "
                f"{(pf.get('drag_after') or 0) * 1e3:.0f} ms after a drag's last key); the "
                f"panel's press {s['median'] / pf['median']:.2f}x it")
        if s.get("drag_after") is not None:
            text += (f", its drag's last frame {s['drag_after'] / pf['median']:.1f}x it"
                     + (f" and {s['drag_after'] / pf['drag_after']:.1f}x its drag"
                        if pf.get("drag_after") else ""))
        print(f"{where:<6s}{'  page floor':<24s}{text}", flush=True)
        nf = s.get("null")
        if nf and nf.get("median"):
            text = (f"a live figure without a model on this page: press {nf['median'] * 1e3:.1f} "
                    f"ms ({nf['median'] / pf['median']:.2f}x the page floor")
            if floor and floor.get("median"):
                text += f", {nf['median'] / floor['median']:.2f}x the floor"
            text += ")"
            if nf.get("drag_after") is not None:
                text += (f", its drag's last frame {nf['drag_after'] * 1e3:.0f} ms after the "
                         f"last key ({nf['drag_after'] / pf['median']:.1f}x the page floor"
                         + (f", {nf['drag_after'] / floor['median']:.1f}x the floor"
                            if floor and floor.get("median") else "") + ")")
            print(f"{where:<6s}{'  null figure':<24s}{text}", flush=True)
    if s.get("paced_runs"):
        paced = _drag_text(s["paced_runs"], s.get("paced_after"), floor, "paced",
                           s.get("paced_quick"))
        print(f"{where:<6s}{'  paced, ' + f'{KEY_RATE:g} keys/s':<24s}{paced}", flush=True)


def _drag_text(drags, after, floor, label, quick=None):
    """A panel's drags (``label`` "drag" or "paced") as its row shows them: painted/sent per
    drag, and the last frame after the last key against the floor's press and the floor's own
    drags of the same kind; for a panel that shows a quick answer until the slider rests, also
    when the quick answer of the last position was painted (``quick``, s after the last key)."""
    if not drags:
        return ""
    ok = True
    counts = []
    for drag, k in drags:  # every frame the kernel sent, painted once, the last one last
        ok = ok and drag.painted_once and drag.received > 0 and drag.changed is True
        if k is not None:
            ok = ok and drag.painted == k["frames"] and drag.last_painted[:1] == [k["last"]]
            counts.append(f"{drag.painted}/{k['frames']} ({k['moves']}->{k['runs']})")
        else:
            counts.append(f"{drag.painted}/{drag.received}")
    text = f"painted/sent (moves->updates) {', '.join(counts)} {'OK' if ok else 'MISSED'}"
    if after is not None and floor and floor.get("median"):
        r = after / floor["median"]
        each = "/".join(f"{d.after_last_key_s * 1e3:.0f}" if d.after_last_key_s is not None
                        else "-" for d, _ in drags)
        text += (f"; last {after * 1e3:.0f} ms after the last key (median of {each}; "
                 f"{r:.1f}x {'OK' if r <= DRAG_RATIO else 'MISSED'}")
        if floor.get(f"{label}_after"):
            text += (f"; {after / floor[f'{label}_after']:.1f}x the floor's "
                     f"{'drag' if label == 'drag' else 'paced drag'}")
        text += ")"
        if quick is not None:  # a panel that shows a coarse answer until the slider rests
            text += (f"; its last position shown coarse {quick * 1e3:.0f} ms after the last key "
                     f"({quick / floor['median']:.1f}x the floor)")
    return text


def main():
    reason = B.unavailable()
    if reason:
        print(f"browser benchmark not run: {reason}")
        return
    selector = B.figure_selector()
    root = B.notebook_root(prefix="afm-bench-browser-")
    for notebook in sorted({_entry(name).notebook for name in PANELS}):
        # the floor and a live figure without a model on each panel's own page
        for code in (B.FLOOR_CODE, B.NULL_FIGURE_CODE):
            B.append_cell(root / "notebooks" / notebook, code)
    print(f"key press -> changed pixels in headless {B.CHROMIUM}, {PRESSES} presses per panel "
          f"(after one warm-up); figure element {selector!r}")
    print(f"target: median <= {TARGET_RATIO}x the floor (slider -> kernel -> label text, same "
          f"run), every frame the kernel sent in a {DRAG}-press drag painted once, its last "
          f"frame within {DRAG_RATIO}x the floor of its last key (force volume's last frame is "
          f"its full map, begun once the slider rested {FV_DELAY * 1e3:.0f} ms, and tapping's "
          f"after a move of the lever its full curve, begun once it rested "
          f"{TAPPING_DELAY * 1e3:.0f} ms, each from the page's paint of the coarse one)")
    print(f"{'where':<6s}{'panel':<24s}{'median':>10s} {'worst':>10s} {'failed':>7s} "
          f"{'median/floor':<13s} {'step':>10s} {'step cpu':>10s} {'readouts':>10s}  "
          f"{'drag: frames painted':<36s} value after the drag")
    print("(step: median time of the panel's update in the kernel, lab only; step cpu: the CPU "
          "time of the kernel's thread in it, the step less its waits for a CPU other processes "
          "held (the browser drawing, the server) or for another thread; readouts: median "
          "key press -> the panel's own text readouts changed, the kernel's answer without the "
          "figure, - when the pixels changed first; drag: frames painted (each counted after its "
          "paint) of the frames the kernel sent, and the moves it received -> the "
          "panel updates they became)")
    results = {}
    with B.browser() as b:
        for where in WHERE:
            server = None
            page = B.new_page(b)
            try:
                # JupyterLab's own windowing, as `make lab` serves a student (the tests keep
                # every cell rendered)
                server = B.Server(where, root, windowing=None).start()
                floor = None
                try:
                    floor = _floor(where, server, page)
                    _row(where, "floor", floor, None)
                    for label, what in (("drag", "floor drag"),
                                        ("paced", f"floor, {KEY_RATE:g} keys/s")):
                        if floor.get(f"{label}_after") is not None:
                            print(f"{where:<6s}{what:<24s}its label's last change "
                                  f"{floor[f'{label}_after'] * 1e3:.0f} ms after the last of "
                                  f"{DRAG} keys ({floor[f'{label}_after'] / floor['median']:.1f}x "
                                  f"the floor; median of {DRAGS} drags)", flush=True)
                except Exception as exc:
                    print(f"{where:<6s}{'floor':<24s}failed: {type(exc).__name__}: {exc}")
                for name in PANELS:
                    if not _entry(name).figure:
                        print(f"{where:<6s}{name:<24s}not timed: its slider applies to the next "
                              f"scan, the figure does not move")
                        continue
                    try:
                        s = _panel(where, server, page, name, selector)
                        results[where, name] = (s, floor)
                        _row(where, name, s, floor)
                    except Exception as exc:
                        print(f"{where:<6s}{name:<24s}failed: {type(exc).__name__}: "
                              f"{str(exc).splitlines()[0] if str(exc) else ''}", flush=True)
                        traceback.print_exc(limit=2, file=sys.stdout)
                    if where == "voila":
                        page.goto("about:blank")  # voila ends that notebook's kernel
                if floor is not None:
                    try:
                        again = _floor(where, server, page)
                        _row(where, "floor, at the end", again, None)
                        _pool(floor, again)
                        _summary(where, results, floor)
                    except Exception as exc:
                        print(f"{where:<6s}{'floor, at the end':<24s}failed: "
                              f"{type(exc).__name__}: {exc}")
            except Exception as exc:
                print(f"{where}: could not run: {type(exc).__name__}: {exc}")
            finally:
                page.close()
                if server is not None:
                    server.stop()
    ratios = [s["median"] / f["median"] for s, f in results.values()
              if s.get("median") and f and f.get("median")]
    if ratios:
        print(f"median/floor over the panels: best {min(ratios):.1f}x, "
              f"median {statistics.median(ratios):.1f}x, worst {max(ratios):.1f}x "
              f"(target <= {TARGET_RATIO}x)")


def _summary(where, results, floor):
    """Each panel against the floor of the whole run (:func:`_pool`)."""
    q = statistics.quantiles(floor["times"], n=4) if len(floor["times"]) >= 2 else [0, 0, 0]
    # the floor's presses fall in two groups an animation frame (16.7 ms at 60 Hz) apart: its
    # median, and so every ratio, moves by up to half of that between runs
    print(f"{where}: against the floor of the whole run ({len(floor['times'])} presses, median "
          f"{floor['median'] * 1e3:.1f} ms, quartiles {q[0] * 1e3:.0f} / {q[2] * 1e3:.0f} ms; "
          f"its drag's last change "
          f"{(floor['drag_after'] or 0) * 1e3:.0f} ms after the last key, {len(floor['drags'])} "
          f"drags): key -> pixels / floor (target {TARGET_RATIO}x), drag's last frame after the "
          f"last key / floor (target {DRAG_RATIO}x) and / the floor's drag; then the same for "
          f"the drags at {KEY_RATE:g} keys/s"
          + ("" if not floor.get("paced_after") else
             f" (the floor's: {floor['paced_after'] * 1e3:.0f} ms)")
          + "; then against the floor on the panel's own page: its press and its fast drag's "
            "last frame")
    for (w, name), (s, _) in results.items():
        if w != where or not s.get("median"):
            continue
        columns = ""
        for label in ("drag", "paced"):
            after = s.get(f"{label}_after")
            if after is not None:
                d = after / floor["median"]
                columns += f"  {d:5.1f}x {'OK' if d <= DRAG_RATIO else 'MISSED':6s}" + (
                    f"{after / floor[f'{label}_after']:5.1f}x"
                    if floor.get(f"{label}_after") else "")
        r = s["median"] / floor["median"]
        pf = s.get("page_floor") or {}
        if pf.get("median"):  # against the floor on the panel's own page
            columns += (f"   page floor {pf['median'] * 1e3:5.1f} ms: "
                        f"{s['median'] / pf['median']:5.2f}x")
            if s.get("drag_after") is not None:
                columns += f" {s['drag_after'] / pf['median']:5.1f}x"
        print(f"  {name:<24s}{r:5.2f}x {'OK' if r <= TARGET_RATIO else 'MISSED':6s}{columns}")


if __name__ == "__main__":
    main()
