"""Slider key press -> the panel's 3D view repainted with the change, in a real browser.

Headless Debian Chromium (Playwright, ``/usr/bin/chromium``) against two JupyterLab servers (one
per side, below), driven by ``tests/browser.py``; per panel (notebook 01's cantilever, slider
"end force F"; notebook 07's tapping panel, slider "setpoint A_sp / A0"), on each side: Run All,
the 3D animations paused, the slider focused, the 3D view scrolled into the middle of the
viewport, one warm-up press; then ``PRESSES`` timed presses of the arrow key with the more room
per side, the two sides' presses alternating (and which goes first), so both see the same load
of a shared machine.

A press is timed from its ``keydown`` (a capture-phase listener on the notebook's window) to the
first animation frame after the last 3D command of that press was handed to meshcat's viewer
(meshcat renders a changed scene in its own ``requestAnimationFrame`` callback, so that frame is
the one that paints the change); the press's commands are those that arrive until none has for
``QUIET`` s (at most ``PRESS_TIMEOUT`` s; a press that draws nothing by then counts as failed).
Times are ``performance.timeOrigin + performance.now()`` (and ``timeOrigin`` + the frame's
timestamp) so that the notebook page and an iframe of another origin read one clock.

- **after** (this checkout): each panel's view is a ``SceneView`` widget (``.afm-scene``) below its
  figure; its commands arrive as one comm message over the kernel's connection. A command drawn is
  an increase of the element's ``data-applied`` (seen by a MutationObserver).
- **before** (the peer, commit ``BEFORE``, the old transport): a git worktree of that commit served
  by its own JupyterLab with the worktree on ``PYTHONPATH``; the scene builders send each command
  over ZMQ to one meshcat server per kernel (another process and port), which forwards it over
  its websocket to meshcat's own page in an ``<iframe>`` of the notebook
  (``get_viewer().jupyter_cell()``).
  A command drawn is a call of that page's ``viewer.handle_command_bytearray`` (wrapped in the
  iframe's document). The copies of the old notebooks leave out their last cell,
  ``close_viewer()``, which would close the view that is measured.

Both include: the kernel's update of the panel (model run, figure frame built and sent, scene
commands built), the transport (comm message over the kernel's websocket; or ZMQ request/reply
per command to the meshcat server, then its websocket to the iframe), meshcat's decoding and
scene update, up to the start of the frame that renders it. They leave out that render itself
(three.js's ``render`` runs inside the frame; a long render shows only as later frames starting
late), the GPU work and compositing after it (headless, software GL), and the live figure's own
drawing, which runs in the same page but is not waited for.

Beside the times: the commands per press, the animation frames they were drawn over (one when
they arrive together; the old transport sends one websocket message per command, and meshcat
renders the scene once per frame in which one arrived), and the panel's update alone, timed in its
kernel (``panel._run`` with its current values, median of 5; for before it includes the ZMQ
round trip to the meshcat server of each command), and how long one meshcat render takes in
that page (``viewer.render`` timed while presses are timed).

For scale, the floor (``press_text``): an ipywidgets IntSlider whose observer sets a Label, key
press -> the label's text changed, in each server. ``BENCH_SCENE_PRESSES`` (default 20),
``BENCH_SCENE_PANELS`` (default ``cantilever,tapping``), ``BENCH_SCENE_BEFORE`` (the commit,
default 9f60579) and ``BENCH_SCENE_CHECKOUT`` (an existing checkout of it; else a temporary git
worktree is made and removed) change the run. Prints a reason and exits 0 when the browser or the
old commit is missing.
"""
import contextlib
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
import traceback
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # the checkout, for tests/

from tests import browser as B  # noqa: E402

PRESSES = int(os.environ.get("BENCH_SCENE_PRESSES", "20"))
BEFORE = os.environ.get("BENCH_SCENE_BEFORE", "9f60579")
#: panel -> (notebook, part of its slider's description, the panel's name in the notebook)
ALL_PANELS = {"cantilever": ("01_cantilever_mechanics.ipynb", "end force F", "panel"),
              "tapping": ("07_imaging_modalities.ipynb", "setpoint A_sp / A0", "tapping")}
PANELS = [p for p in os.environ.get("BENCH_SCENE_PANELS", ",".join(ALL_PANELS)).split(",") if p]
QUIET = 0.4  # s without a new command: the press's commands are all in
PRESS_TIMEOUT = 8.0  # s: a press that drew nothing by then failed
RUN_ALL_TIMEOUT = 400.0  # s
VIEW_TIMEOUT = 60.0  # s for a 3D view to be up after Run All

#: The probe, installed in the document that holds the 3D view (and in the notebook page, for
#: the keydown): command times, and the frame after each (the frame meshcat renders it in).
_PROBE_JS = r"""
() => {
  if (window.__afmScene) return true;
  const S = window.__afmScene = {events: [], armed: false, keydown: null, hooked: false,
                                 renders: []};
  const clock = () => performance.timeOrigin + performance.now();
  window.addEventListener('keydown', () => {
    if (S.armed && S.keydown === null) S.keydown = clock();
  }, true);
  S.note = () => {  // commands were handed to meshcat's viewer
    if (!S.armed) return;
    const e = {t: clock(), painted: null};
    S.events.push(e);
    requestAnimationFrame(ts => { e.painted = Math.max(performance.timeOrigin + ts, e.t); });
  };
  // how long meshcat's renders take (its animate() calls this.render() in a frame)
  S.timeRenders = (v) => {
    if (!v || v.__afmTimed) return;
    const r = v.render.bind(v);
    v.render = () => {
      const t = performance.now();
      r();
      if (S.armed) S.renders.push(performance.now() - t);
    };
    v.__afmTimed = true;
  };
  // before: meshcat's own page (its websocket calls this.handle_command_bytearray)
  S.hookViewer = () => {
    const v = window.viewer;
    if (!v || !v.handle_command_bytearray) return false;
    if (!S.hooked) {
      const f = v.handle_command_bytearray.bind(v);
      v.handle_command_bytearray = (b) => { const r = f(b); S.note(); return r; };
      S.hooked = true;
    }
    S.timeRenders(v);
    return true;
  };
  // after: a SceneView's element, which counts the commands drawn in data-applied
  S.observe = (el) => {
    if (S.observer) S.observer.disconnect();
    S.el = el;
    if (el.afmView) S.timeRenders(el.afmView.viewer);
    S.observer = new MutationObserver(() => S.note());
    S.observer.observe(el, {attributes: true, attributeFilter: ['data-applied']});
  };
  S.applied = () => (S.el ? Number(S.el.dataset.applied || 0) : null);
  S.arm = () => {
    S.events = []; S.renders = []; S.keydown = null; S.armed = true; S.base = S.applied();
  };
  // resolves when no command came for quietMs after the first (or timeoutMs passed)
  S.wait = (quietMs, timeoutMs) => new Promise(resolve => {
    const start = clock();
    const check = () => {
      const now = clock(), ev = S.events, last = ev[ev.length - 1];
      const done = last && last.painted !== null && now - last.t > quietMs;
      if (done || now - start > timeoutMs) {
        S.armed = false;
        resolve({events: ev.map(e => [e.t, e.painted]), timedOut: !done, renders: S.renders,
                 applied: S.base === null ? null : S.applied() - S.base});
      } else setTimeout(check, 25);
    };
    setTimeout(check, 25);
  });
  return true;
}
"""


def _ms(t):
    return "      -" if t is None else f"{t * 1e3:7.1f}"


def _stats(times):
    ok = [t for t in times if t is not None]
    return {"n": len(times), "failed": len(times) - len(ok),
            "median": statistics.median(ok) if ok else None,
            "min": min(ok) if ok else None, "max": max(ok) if ok else None}


@contextlib.contextmanager
def _before_checkout():
    """A checkout of ``BEFORE``: ``BENCH_SCENE_CHECKOUT``, or a temporary detached worktree."""
    given = os.environ.get("BENCH_SCENE_CHECKOUT")
    if given:
        yield Path(given)
        return
    path = Path(tempfile.mkdtemp(prefix="afm-bench-before-")) / "checkout"
    proc = subprocess.run(["git", "-C", str(B.ROOT), "worktree", "add", "--detach", str(path),
                           BEFORE], capture_output=True, text=True, timeout=120)
    if proc.returncode != 0:
        shutil.rmtree(path.parent, ignore_errors=True)
        raise RuntimeError(f"no worktree of {BEFORE}: {proc.stderr.strip()[-300:]}")
    try:
        yield path
    finally:
        subprocess.run(["git", "-C", str(B.ROOT), "worktree", "remove", "--force", str(path)],
                       capture_output=True, timeout=120)
        shutil.rmtree(path.parent, ignore_errors=True)
        subprocess.run(["git", "-C", str(B.ROOT), "worktree", "prune"], capture_output=True,
                       timeout=60)


def _notebook_root(checkout: Path, prefix: str) -> Path:
    """Copies of the panels' notebooks of ``checkout`` (without ``close_viewer()`` cells) and
    the floor notebook, in a temporary root."""
    root = Path(tempfile.mkdtemp(prefix=prefix))
    nbdir = root / "notebooks"
    nbdir.mkdir()
    for name in {ALL_PANELS[p][0] for p in PANELS}:
        nb = json.loads((checkout / "notebooks" / name).read_text(encoding="utf-8"))
        nb["cells"] = [c for c in nb["cells"] if not any(
            line.strip() == "close_viewer()" for line in "".join(c["source"]).splitlines())]
        (nbdir / name).write_text(json.dumps(nb), encoding="utf-8")
    B.floor_notebook(nbdir / B.FLOOR_NOTEBOOK)
    return root


def _floor_setup(server, page):
    B.open_lab(page, server, B.FLOOR_NOTEBOOK)
    B.run_all(page)
    slider = B.find_slider(page, B.FLOOR_SLIDER)
    B.mark_text(page, slider)
    B.press_text(page, slider, "ArrowRight", 2)  # warm-up
    return lambda: B.press_text(page, slider, "ArrowRight", 1, settle_s=0.1)[0]


def _view_after(page, slider):
    """The panel's SceneView element (probe in the notebook page): scrolled to the middle."""
    ok = slider.evaluate(
        """(h) => { let p = h;
                    while (p && !(p.querySelector && p.querySelector('.afm-scene')))
                      p = p.parentElement;
                    const el = p && p.querySelector('.afm-scene');
                    if (!el) return false;
                    el.scrollIntoView({block: 'center'});
                    window.__afmScene.el = el;
                    return true; }""")
    if not ok:
        raise LookupError("no 3D view (.afm-scene) in the panel of the slider")
    page.wait_for_function(
        "() => window.__afmScene.el.afmView && Number(window.__afmScene.el.dataset.applied) > 0",
        timeout=VIEW_TIMEOUT * 1000, polling=250)
    page.evaluate("""() => { window.__afmScene.observe(window.__afmScene.el);
                             for (const s of document.querySelectorAll('.afm-scene'))
                               if (s.afmView) s.afmView.viewer.animator.pause(); }""")
    return page


def _view_before(page):
    """The iframe of meshcat's own page (probe in its document): scrolled to the middle."""
    iframe = page.locator("iframe[src*='/static/']").first
    iframe.wait_for(state="attached", timeout=VIEW_TIMEOUT * 1000)
    iframe.evaluate("f => f.scrollIntoView({block: 'center'})")
    frame = iframe.element_handle().content_frame()
    frame.wait_for_function(
        "() => window.viewer && viewer.connection && viewer.connection.readyState === 1",
        timeout=VIEW_TIMEOUT * 1000, polling=250)
    frame.evaluate(_PROBE_JS)
    if not frame.evaluate("() => window.__afmScene.hookViewer()"):
        raise LookupError("meshcat's page in the iframe has no viewer")
    frame.evaluate("() => viewer.animator.pause()")
    return frame


def _press(page, doc, key):
    """One press: (keydown -> last command's frame, keydown -> first command's frame, in s;
    commands; animation frames they were drawn over; meshcat's render times in ms), Nones when
    nothing was drawn within PRESS_TIMEOUT."""
    page.evaluate("() => window.__afmScene.arm()")
    if doc is not page:
        doc.evaluate("() => window.__afmScene.arm()")
    page.keyboard.press(key)
    r = doc.evaluate("([q, t]) => window.__afmScene.wait(q, t)",
                     [QUIET * 1000, PRESS_TIMEOUT * 1000])
    keydown = page.evaluate("() => window.__afmScene.keydown")
    ev = r["events"]
    if r["timedOut"] or not ev or keydown is None:
        return None, None, len(ev), None, []
    n = r["applied"] if r["applied"] is not None else len(ev)
    frames = len({painted for _, painted in ev})
    return ((ev[-1][1] - keydown) / 1000.0, (ev[0][1] - keydown) / 1000.0, n, frames,
            r["renders"])


def _kernel_update(page, variable, n=5):
    """Median s of the panel's update run in its kernel with its current values (model, figure
    frame and scene commands built and handed to the transport), ``n`` times."""
    code = (f"import time as _t, statistics as _s\n_v, _ts = {variable}.values(), []\n"
            f"for _i in range({n}):\n"
            f"    _t0 = _t.perf_counter(); {variable}._run(_v)\n"
            f"    _ts.append(_t.perf_counter() - _t0)\n"
            f"print(_s.median(_ts))")
    out = B.kernel_eval(page, code, timeout=60).strip()
    try:
        return float(out.splitlines()[-1])
    except (ValueError, IndexError):
        return None


def _panel_setup(version, server, page, name):
    """Run the panel's notebook and aim the probe at its 3D view; returns (one timed press,
    the notebook's errors, the kernel's update time)."""
    notebook, description, variable = ALL_PANELS[name]
    B.open_lab(page, server, notebook, timeout=120)
    B.run_all(page, timeout=RUN_ALL_TIMEOUT)
    errors = B.lab_errors(page)
    page.evaluate(_PROBE_JS)
    slider = B.find_slider(page, description)
    slider.focus()
    doc = _view_after(page, slider) if version == "after" else _view_before(page)
    key, _ = B.keys(slider)
    time.sleep(0.5)
    _press(page, doc, key)  # warm-up
    return (lambda: _press(page, doc, key)), errors, (lambda: _kernel_update(page, variable))


def _interleaved(presses):
    """Call each side's press function PRESSES times, alternating which goes first, so that both
    see the same load of this (shared) machine; per side the list of results."""
    out = {v: [] for v in presses}
    order = list(presses)
    for i in range(PRESSES):
        for v in (order if i % 2 == 0 else order[::-1]):
            try:
                out[v].append(presses[v]())
            except Exception as exc:  # a press that broke counts as failed, the run goes on
                print(f"  a press ({v}) failed: {type(exc).__name__}: {str(exc)[:200]}")
                out[v].append(None)
            time.sleep(0.1)
    return out


def _panel_stats(results):
    results = [r if r is not None else (None, None, 0, None, []) for r in results]
    s = _stats([r[0] for r in results])
    s["first"] = _stats([r[1] for r in results])["median"]
    s["commands"] = statistics.median([r[2] for r in results]) if results else 0
    frames = [r[3] for r in results if r[3] is not None]
    s["frames"] = statistics.median(frames) if frames else None
    renders = [t / 1000.0 for r in results for t in r[4]]
    s["render"] = statistics.median(renders) if renders else None
    return s


def _row(name, version, s):
    print(f"{name:<11s}{version:<8s}{_ms(s.get('median'))} {_ms(s.get('min'))} "
          f"{_ms(s.get('max'))}  {_ms(s.get('first'))}   "
          f"{format(s['commands'], '6g') if 'commands' in s else '     -'} "
          f"{format(s['frames'], '6g') if s.get('frames') is not None else '     -'}   "
          f"{s['failed']:3d}/{s['n']:<3d}  {_ms(s.get('kernel'))}  {_ms(s.get('render'))}"
          + (f"  errors in the notebook: {s['errors'][:2]}" if s.get("errors") else ""),
          flush=True)


def _measure(what, setups, results):
    """Set every side up for ``what`` (floor or a panel), then time their presses interleaved."""
    presses, errors, kernel = {}, {}, {}
    for version, setup in setups.items():
        try:
            presses[version], errors[version], kernel[version] = setup()
        except Exception as exc:
            print(f"{what:<11s}{version:<8s}failed: {type(exc).__name__}: "
                  f"{str(exc).splitlines()[0] if str(exc) else ''}", flush=True)
            traceback.print_exc(limit=2, file=sys.stdout)
    for version, out in _interleaved(presses).items():
        s = _stats(out) if what == "floor" else _panel_stats(out)
        s["errors"] = errors[version]
        if kernel[version] is not None:
            try:
                s["kernel"] = kernel[version]()
            except Exception as exc:
                print(f"  kernel update ({version}) not timed: {type(exc).__name__}: {exc}")
        results[what, version] = s
        _row(what, version, s)


def _sides(stack, b):
    """Start one JupyterLab per side (after: this checkout; before: a checkout of BEFORE, when
    there is one) and open a page on each; {version: (server, page)}."""
    checkouts = {"after": B.ROOT}
    try:
        checkouts["before"] = stack.enter_context(_before_checkout())
    except Exception as exc:
        print(f"before ({BEFORE}) not run: {type(exc).__name__}: {exc}")
    sides = {}
    for version, checkout in checkouts.items():
        root = _notebook_root(checkout, f"afm-bench-scene-{version}-")
        stack.callback(shutil.rmtree, root, True)
        server = stack.enter_context(B.Server("lab", root, checkout=checkout))
        page = B.new_page(b)
        stack.callback(page.close)
        stack.callback(B.close_lab_notebook, page, server)
        sides[version] = (server, page)
    return sides


def main():
    reason = B.unavailable()
    if reason:
        print(f"3D view benchmark not run: {reason}")
        return
    print(f"key press -> 3D view repainted, headless {B.CHROMIUM}, JupyterLab, {PRESSES} presses "
          f"per panel and side (after one warm-up), the two sides' presses interleaved")
    print(f"after = this checkout (SceneView widget, comm messages); before = {BEFORE} (a meshcat "
          f"server per kernel, iframe + websocket), the peer; each side its own JupyterLab")
    print("time: keydown -> the animation frame after the press's last 3D command reached "
          "meshcat's viewer (it renders in that frame). Includes the kernel's update (model run, "
          "live figure frame built and sent, scene commands built), the transport (after: one "
          "comm message; before: ZMQ request/reply per command to the meshcat server, then its "
          "websocket) and meshcat's decoding and scene update, up to the frame that renders it. "
          "Leaves out that render, GPU work and compositing, and the live figure's own drawing")
    print(f"{'panel':<11s}{'version':<8s}{'median':>7s} {'min':>7s} {'max':>7s}  "
          f"{'1st cmd':>7s}   {'cmds':>6s} {'frames':>6s}   failed   {'kernel':>7s}  "
          f"{'render':>7s}")
    print("(ms; 1st cmd: median to the frame after the press's first command; cmds: commands "
          "per press; frames: animation frames they were drawn over; kernel: the panel's update "
          "alone, run in its kernel with the same values, median of 5: the model, the figure's "
          "frame and the scene's commands built and handed to the transport, which for before "
          "includes a ZMQ round trip to the meshcat server per command; render: median duration "
          "of one meshcat render (three.js, software GL) while a press was timed)")
    results = {}
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else None
    with B.browser() as b, contextlib.ExitStack() as stack:
        sides = _sides(stack, b)
        _measure("floor", {v: (lambda s=s: (_floor_setup(*s), None, None))
                           for v, s in sides.items()},
                 results)
        for name in PANELS:
            _measure(name, {v: (lambda v=v, s=s: _panel_setup(v, *s, name))
                            for v, s in sides.items()}, results)
    if load is not None:
        print(f"load average (1 min) {load:.1f} at the start, {os.getloadavg()[0]:.1f} at the end, "
              f"on {os.cpu_count()} CPUs (the floor's before/after ratio shows the noise left)")
    print("before/after (medians, the peer over this checkout; > 1 means faster now):")
    for name in ["floor"] + PANELS:
        a, p = results.get((name, "after")), results.get((name, "before"))
        if a and p and a.get("median") and p.get("median"):
            print(f"  {name:<11s}{p['median'] / a['median']:6.2f}x   "
                  f"(before {p['median'] * 1e3:.1f} ms, after {a['median'] * 1e3:.1f} ms)")
        else:
            print(f"  {name:<11s}     -   (not measured on both sides)")
    for version in ("after", "before"):
        f = results.get(("floor", version))
        for name in PANELS:
            s = results.get((name, version))
            if f and s and f.get("median") and s.get("median"):
                print(f"  {name} {version}: {s['median'] / f['median']:.1f}x its server's floor")


if __name__ == "__main__":
    main()
