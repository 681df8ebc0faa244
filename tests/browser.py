"""Drive JupyterLab and voila in headless Chromium: time a slider key press to changed pixels.

A small driver library (not a test file) shared by ``tests/test_panels_browser.py`` and
``benchmarks/bench_browser.py``. It starts a JupyterLab or voila server on 127.0.0.1 (a free
port, token auth, copies of the notebooks in a temporary root, the checkout on ``PYTHONPATH``,
``MPLBACKEND`` and ``AFMSMILER_TESTING`` unset, as a student's kernel), drives Debian's Chromium
through Playwright (``executable_path=/usr/bin/chromium``; never Playwright's own download), runs
a notebook, finds a panel's slider by the text of its description and presses its keys.

How a press is timed (:func:`press`): before the press the page takes a checksum of the pixels
of every ``<canvas>`` in the panel's figure element(s) (``getImageData``, an FNV-1a hash), a
capture-phase ``keydown`` listener on ``window`` records ``performance.now()`` when the key goes
down, and a ``requestAnimationFrame`` loop compares the checksums on every frame; the time of the
first frame at which they differ, minus the key-down time, is the press's key-to-pixels time. A
press that changes nothing within ``timeout`` seconds is a failure (``None``), never a hang. The
floor (:func:`press_text`) is timed the same way on a label's text (a ``MutationObserver`` marks
it, the next animation frame is its time): slider -> kernel -> label, the round trip no figure
can beat. :func:`drag` sends a burst of key presses without waiting and records which frames
were painted: the distinct ``data-seq`` values of live figures (``div.afm-live``) seen on
animation frames, and the number of distinct pixel states.

Every wait is bounded; servers are started in their own process group and killed in ``stop``
(called from ``finally``/context managers). :func:`unavailable` says why the browser tests
cannot run here, for a visible ``pytest.skip(reason)``.
"""
from __future__ import annotations

import contextlib
import json
import os
import shutil
import signal
import socket
import statistics
import subprocess
import sys
import tempfile
import time
import urllib.request
from dataclasses import dataclass, field
from pathlib import Path

from afmsmiler.serving import SERVER_OPTION
from afmsmiler.ui.registry import PANELS as REGISTRY

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = ROOT / "notebooks"
CHROMIUM = os.environ.get("AFMSMILER_CHROMIUM", "/usr/bin/chromium")  # Debian's, never a download
CHROMIUM_ARGS = ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                 "--disable-background-networking", "--disable-component-update",
                 "--disable-sync"]
BIN = Path(sys.executable).parent  # jupyter and voila of the interpreter running the tests
TOKEN = "afm-browser-test"
PRESS_TIMEOUT = 15.0  # s: a press whose pixels have not changed by then is a failure (a
# wait, not a speed check: a press repaints in well under a second; 15 s leaves room for a
# loaded CI machine running the other tests beside it)
VIEWPORT = {"width": 1500, "height": 1000}

#: The element of a live figure (afmsmiler.plots.live): it holds <canvas> elements and carries
#: ``data-frames`` (frames drawn) and ``data-seq`` (the kernel's sequence number shown last).
LIVE_FIGURE = ".afm-live"
#: The element of an ipympl figure (the panels' figures before the live component).
IPYMPL_FIGURE = ".jupyter-matplotlib-figure"

#: Every panel of the course, by key: the one registry (afmsmiler.ui.registry), which says the
#: notebook, the panel's name there and the slider to move.
PANELS = {e.key: e for e in REGISTRY}


def figure_selector() -> str:
    """The CSS selector of a panel's figure on this checkout.

    The live component (``afmsmiler/plots/live.py``) draws ``div.afm-live``; before it, the
    panels' figures are ipympl canvases.
    """
    return LIVE_FIGURE if (ROOT / "afmsmiler" / "plots" / "live.py").exists() else IPYMPL_FIGURE


def unavailable() -> str | None:
    """Why the browser tests cannot run here, or None when they can."""
    if not os.access(CHROMIUM, os.X_OK):
        return (f"no {CHROMIUM}: install Debian's chromium (`make test` does so as root) to run "
                "the browser tests")
    try:
        import playwright.sync_api  # noqa: F401 (only whether it imports)
    except ImportError:
        return "playwright is not installed (pip install -e '.[test]')"
    for tool in ("jupyter-lab", "voila"):
        if not (BIN / tool).exists() and shutil.which(tool) is None:
            return f"{tool} is not installed (pip install -e '.[test,lab]')"
    return None


def free_port() -> int:
    """A TCP port on 127.0.0.1 that nobody listens on now."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _tool(name: str) -> str:
    path = BIN / name
    return str(path) if path.exists() else (shutil.which(name) or name)


def kernel_env(checkout: Path = ROOT, *, short: bool = False) -> dict:
    """The environment of a student's kernel: the checkout importable, no test flags.

    With ``short``, ``AFMSMILER_TESTING=1`` shortens the notebooks' animations and simulations
    (for tests that run every cell several times and check what the cells show, not how long).
    """
    env = dict(os.environ)
    env["PYTHONPATH"] = str(checkout) + (os.pathsep + env["PYTHONPATH"]
                                         if env.get("PYTHONPATH") else "")
    for name in ("MPLBACKEND", "AFMSMILER_TESTING", "CI", "NBVAL", "PYTEST_CURRENT_TEST"):
        env.pop(name, None)
    if short:
        env["AFMSMILER_TESTING"] = "1"
    return env


def floor_notebook(path: Path) -> Path:
    """Write the floor notebook: an IntSlider whose observer sets a Label's value.

    A key press on that slider travels browser -> kernel -> browser and changes a text: the
    round trip that bounds any figure drawn from the kernel.
    """
    import nbformat
    nb = nbformat.v4.new_notebook()
    nb.cells = [nbformat.v4.new_code_cell(FLOOR_CODE)]
    nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3",
                                 "language": "python"}
    nbformat.write(nb, str(path))
    return path


FLOOR_NOTEBOOK = "00_floor.ipynb"
FLOOR_SLIDER = "floor slider"
#: The floor's cell: a slider whose observer sets a Label's value (names of its own, so that it
#: can sit in a course notebook beside a panel, :func:`append_cell`).
FLOOR_CODE = ("import ipywidgets as _floor_w\n"
              "_floor_slider = _floor_w.IntSlider(value=50, min=0, max=1000, "
              "description='floor slider')\n"
              "_floor_label = _floor_w.Label('50', layout=_floor_w.Layout(width='200px'))\n"
              "_floor_slider.observe(lambda change: setattr(_floor_label, 'value', "
              "str(change['new'])), 'value')\n"
              "_floor_w.VBox([_floor_slider, _floor_label])")


#: A live figure that runs no model: one line of two points whose end the slider moves, sent
#: from the slider's observer (no panel, no coalescing). Beside a panel it shows what any live
#: figure costs on that page.
NULL_FIGURE_CODE = ("import ipywidgets as _null_w\n"
                    "from matplotlib.figure import Figure as _null_Figure\n"
                    "from afmsmiler.plots.live import LiveFigure as _null_Live\n"
                    "_null_fig = _null_Figure(figsize=(6, 3))\n"
                    "_null_ax = _null_fig.add_subplot()\n"
                    "_null_line, = _null_ax.plot([0, 1], [0, 50])\n"
                    "_null_ax.set_xlim(0, 1)\n"
                    "_null_ax.set_ylim(-1, 1001)\n"
                    "_null_live = _null_Live(_null_fig)\n"
                    "_null_slider = _null_w.IntSlider(value=50, min=0, max=1000, "
                    "description='null figure slider')\n"
                    "def _null_move(change):\n"
                    "    _null_line.set_ydata([0, change['new']])\n"
                    "    _null_live.sync()\n"
                    "_null_slider.observe(_null_move, 'value')\n"
                    "_null_w.VBox([_null_slider, _null_live])")
NULL_FIGURE_SLIDER = "null figure slider"


def append_cell(path: Path, code: str) -> Path:
    """Append a code cell of ``code`` to the notebook at ``path`` (the floor's,
    :data:`FLOOR_CODE`, or the null figure's, :data:`NULL_FIGURE_CODE`: timed on the page of a
    course notebook, beside its panels, by ``benchmarks/bench_browser.py``)."""
    import nbformat
    nb = nbformat.read(str(path), as_version=4)
    nb.cells.append(nbformat.v4.new_code_cell(code))
    nbformat.write(nb, str(path))
    return path


def notebook_root(prefix: str = "afm-browser-") -> Path:
    """A temporary root holding copies of the course notebooks and the floor notebook."""
    root = Path(tempfile.mkdtemp(prefix=prefix))
    nbdir = root / "notebooks"
    nbdir.mkdir()
    for nb in NOTEBOOKS.glob("*.ipynb"):
        shutil.copy2(nb, nbdir / nb.name)
    floor_notebook(nbdir / FLOOR_NOTEBOOK)
    return root


# -- servers -------------------------------------------------------------------------------
#: JupyterLab's notebook windowing modes (its setting ``windowingMode``)
WINDOWING = ("none", "full", "defer", "contentVisibility")


class Server:
    """A JupyterLab (``kind="lab"``) or voila (``kind="voila"``) server on 127.0.0.1.

    Parameters
    ----------
    kind : {"lab", "voila"}
        Which server.
    root : pathlib.Path
        A temporary directory from :func:`notebook_root` (its ``notebooks`` folder is served).
    notebook : str, optional
        voila only: serve this one notebook at ``/`` (else the folder, at
        ``/voila/render/<name>``).
    startup_timeout : float
        Seconds to wait for the server to answer.
    short : bool
        Kernels with shortened animations (:func:`kernel_env`).
    checkout : pathlib.Path
        The checkout the kernels import (:func:`kernel_env`); this one by default, another
        (a git worktree of an older commit) for a benchmark's peer.
    windowing : str or None
        lab only: the notebook's windowing mode, one of :data:`WINDOWING`. ``"none"`` (the
        tests'): every cell in the DOM and rendered, on screen or not. None: JupyterLab's own
        default, the student's (``make lab`` sets no mode; JupyterLab 4.6's is
        ``contentVisibility``: cells out of view kept in the DOM, not rendered), for a
        benchmark of what a student gets.
    """

    def __init__(self, kind: str, root: Path, *, notebook: str | None = None,
                 startup_timeout: float = 90.0, short: bool = False, checkout: Path = ROOT,
                 windowing: str | None = "none"):
        if kind not in ("lab", "voila"):
            raise ValueError(f"kind must be 'lab' or 'voila', got {kind!r}")
        if windowing is not None and windowing not in WINDOWING:
            raise ValueError(f"windowing must be None or one of {', '.join(WINDOWING)}, "
                             f"got {windowing!r}")
        self.windowing = windowing
        self.kind, self.root, self.notebook = kind, Path(root), notebook
        self.port = free_port()
        self.proc = None
        self.log = self.root / f"{kind}-{self.port}.log"
        self.startup_timeout = startup_timeout
        self.short = short
        self.checkout = Path(checkout)

    @property
    def base(self) -> str:
        return f"http://127.0.0.1:{self.port}"

    def url(self, notebook: str | None = None) -> str:
        """The address that opens ``notebook`` (lab: in a fresh workspace)."""
        if self.kind == "lab":
            return f"{self.base}/lab/tree/{notebook}?reset&token={TOKEN}"
        if self.notebook is not None:
            return f"{self.base}/?token={TOKEN}"
        return f"{self.base}/voila/render/{notebook}?token={TOKEN}"

    def _settings(self) -> Path:
        """User settings for JupyterLab: no news/update pop-ups, the windowing mode asked for
        (``windowing``; JupyterLab's own when None)."""
        settings = self.root / "settings"
        tracker = {} if self.windowing is None else {"windowingMode": self.windowing}
        for ext, name, values in (
                ("@jupyterlab/notebook-extension", "tracker", tracker),
                ("@jupyterlab/apputils-extension", "notification",
                 {"fetchNews": "false", "checkForUpdates": False})):
            d = settings / ext
            d.mkdir(parents=True, exist_ok=True)
            (d / f"{name}.jupyterlab-settings").write_text(json.dumps(values))
        return settings

    def command(self) -> list:
        """The server's command line (a subclass may serve otherwise)."""
        nbdir = self.root / "notebooks"
        if self.kind == "lab":
            cmd = [_tool("jupyter-lab"), "--no-browser", "--ServerApp.ip=127.0.0.1",
                   f"--ServerApp.port={self.port}", "--ServerApp.port_retries=0",
                   f"--IdentityProvider.token={TOKEN}", f"--ServerApp.root_dir={nbdir}",
                   f"--LabApp.workspaces_dir={self.root / 'workspaces'}",
                   f"--LabApp.user_settings_dir={self._settings()}",
                   "--LabApp.expose_app_in_browser=True", "--ServerApp.open_browser=False",
                   SERVER_OPTION]
            if hasattr(os, "geteuid") and os.geteuid() == 0:
                cmd.append("--allow-root")
        else:
            # as `make app` and `make apps` serve (afmsmiler.apps: the course's template, which
            # asks no other host for anything), with the tracebacks shown
            from afmsmiler import apps
            target = nbdir / self.notebook if self.notebook else nbdir
            cmd = apps.voila_command(target, port=self.port, token=TOKEN)
            cmd.insert(-1, "--show_tracebacks=True")
        return cmd

    def environment(self) -> dict:
        """The server's (and its kernels') environment: a student's (:func:`kernel_env`);
        voila's with the course's template first on ``JUPYTER_PATH``."""
        env = kernel_env(self.checkout, short=self.short)
        if self.kind == "voila":
            from afmsmiler import apps
            template = self.root / f"voila-template-{self.port}"
            template.mkdir(exist_ok=True)
            env["JUPYTER_PATH"] = os.pathsep.join(
                [str(apps.write_template(template))]
                + ([env["JUPYTER_PATH"]] if env.get("JUPYTER_PATH") else []))
        return env

    def start(self) -> "Server":
        nbdir = self.root / "notebooks"
        cmd = self.command()
        with open(self.log, "wb") as log:
            self.proc = subprocess.Popen(cmd, env=self.environment(), cwd=nbdir, stdout=log,
                                         stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                                         start_new_session=True)
        deadline = time.monotonic() + self.startup_timeout
        probe = f"{self.base}/api/status?token={TOKEN}" if self.kind == "lab" else self.base
        while time.monotonic() < deadline:
            if self.proc.poll() is not None:
                raise RuntimeError(f"{self.kind} exited ({self.proc.returncode}): {self.tail()}")
            try:
                urllib.request.urlopen(probe, timeout=2).read(1)
                return self
            except Exception:  # not up yet
                time.sleep(0.3)
        self.stop()
        raise RuntimeError(f"{self.kind} did not answer within {self.startup_timeout:g} s: "
                           f"{self.tail()}")

    def tail(self, n: int = 1500) -> str:
        try:
            return self.log.read_text(errors="replace")[-n:]
        except OSError:
            return ""

    def api(self, method: str, path: str):
        """Call the server's REST API (lab only) and return the decoded JSON (or None)."""
        req = urllib.request.Request(f"{self.base}{path}?token={TOKEN}", method=method)
        with urllib.request.urlopen(req, timeout=10) as r:
            body = r.read()
        return json.loads(body) if body else None

    def shutdown_kernels(self) -> None:
        """Shut every kernel down gracefully (lab), so their exit handlers close servers."""
        if self.kind != "lab" or self.proc is None or self.proc.poll() is not None:
            return
        with contextlib.suppress(Exception):
            for k in self.api("GET", "/api/kernels") or []:
                with contextlib.suppress(Exception):
                    self.api("DELETE", f"/api/kernels/{k['id']}")

    def stop(self) -> None:
        """Stop the server and everything it started (its process group), bounded."""
        if self.proc is None:
            return
        self.shutdown_kernels()
        for sig, wait in ((signal.SIGTERM, 8.0), (signal.SIGKILL, 5.0)):
            if self.proc.poll() is None or _group_alive(self.proc.pid):
                with contextlib.suppress(ProcessLookupError, PermissionError):
                    os.killpg(self.proc.pid, sig)
                with contextlib.suppress(subprocess.TimeoutExpired):
                    self.proc.wait(timeout=wait)
        self.proc = None

    def __enter__(self):
        return self.start()

    def __exit__(self, *exc):
        self.stop()


def _group_alive(pgid: int) -> bool:
    try:
        os.killpg(pgid, 0)
        return True
    except (ProcessLookupError, PermissionError):
        return False


# -- the browser ---------------------------------------------------------------------------
@contextlib.contextmanager
def browser():
    """A headless Debian Chromium driven by Playwright; yields the Browser, closes it after."""
    from playwright.sync_api import sync_playwright
    with sync_playwright() as p:
        b = p.chromium.launch(executable_path=CHROMIUM, headless=True, args=CHROMIUM_ARGS)
        try:
            yield b
        finally:
            b.close()


def new_page(b):
    """A page with the timing helpers installed (``window.__afm``)."""
    page = b.new_page(viewport=VIEWPORT)
    page.add_init_script(_PAGE_JS)
    page.set_default_timeout(30_000)
    return page


_PAGE_JS = r"""
(() => {
if (window.__afm) return;
const afm = {};
window.__afm = afm;
afm.canvases = (root, sel) => {
  const out = [];
  const figs = root.matches && root.matches(sel) ? [root] : Array.from(root.querySelectorAll(sel));
  for (const f of figs) for (const c of f.querySelectorAll('canvas')) out.push(c);
  return out;
};
afm.checksum = (root, sel) => {    // FNV-1a over the pixels of every canvas of the figure(s)
  let h = 2166136261 >>> 0, lit = 0;
  const cs = afm.canvases(root, sel);
  for (const c of cs) {
    if (!c.width || !c.height) continue;
    const ctx = c.getContext('2d');
    if (!ctx) continue;
    const d = new Uint32Array(ctx.getImageData(0, 0, c.width, c.height).data.buffer);
    for (let i = 0; i < d.length; i++) {
      const v = d[i];
      h = Math.imul(h ^ v, 16777619);
      if (v) lit++;
    }
    h = Math.imul(h ^ c.width, 16777619);
  }
  return {hash: (h >>> 0) + ':' + cs.length, lit: lit, n: cs.length};
};
afm.seqs = (root, sel) => {
  const figs = root.matches && root.matches(sel) ? [root] : Array.from(root.querySelectorAll(sel));
  return figs.map(f => f.getAttribute('data-seq')).join(',');
};
// each live figure's frames received and painted so far (afmsmiler/plots/static/live.js)
afm.frames = (root, sel) => {
  const figs = root.matches && root.matches(sel) ? [root] : Array.from(root.querySelectorAll(sel));
  return figs.map(f => {
    const F = f.afmFigure;
    return F ? {received: F.received, painted: F.painted, receivedSeqs: F.receivedSeqs.slice(),
                paintedSeqs: F.paintedSeqs.slice()} : null;
  });
};
// the frames received and painted since `base` (afm.frames), per figure
afm.framesSince = (root, sel, base) => afm.frames(root, sel).map((f, i) => {
  const b = base[i];
  if (!f || !b) return null;
  const last = (log, n) => (n > 0 ? log.slice(-n) : []);
  return {received: last(f.receivedSeqs, f.received - b.received),
          painted: last(f.paintedSeqs, f.painted - b.painted)};
});
afm.paintedCount = (root, sel) => afm.frames(root, sel)
  .reduce((n, f) => n + (f ? f.painted : 0), 0);
// the closest ancestor of el that holds a figure: the panel's own box
afm.panelOf = (el, sel) => {
  let p = el;
  while (p && !(p.querySelector && p.querySelector(sel))) p = p.parentElement;
  return p;
};
afm.mark = (el, sel) => {
  const p = afm.panelOf(el, sel);
  if (!p) return false;
  document.querySelectorAll('[data-afm-panel]').forEach(e => e.removeAttribute('data-afm-panel'));
  p.setAttribute('data-afm-panel', '1');
  return true;
};
afm.root = () => document.querySelector('[data-afm-panel]');
// arm one press: resolves {dt} (ms from keydown to the first frame with other pixels/text)
afm.arm = (sel, mode, timeoutMs) => {
  const root = afm.root();
  const st = {t0: null};
  const probe = mode === 'text' ? () => root.textContent : () => afm.checksum(root, sel).hash;
  const base = probe();
  // the panel's own readouts (HTML widgets): their change times the kernel's answer itself
  const readouts = () => Array.from(root.querySelectorAll('.widget-html'))
                              .map(e => e.textContent).join('|');
  const readBase = mode === 'text' ? null : readouts();
  let tRead = null;
  // read pixels only after the page changed (a MutationObserver, as for the floor's text): a
  // checksum of every canvas on every frame took the page's main thread for 3-6 ms a frame, the
  // harness's load and not the student's. A live figure stamps data-seq on each draw; a figure
  // without it (ipympl's canvas, drawn without DOM changes) is read on every frame.
  // Only the figure's own elements are watched: the slider's readout beside it changes at the
  // key press, and a checksum then (6 ms for four canvases) delayed the kernel's frame.
  const observed = mode === 'text' || afm.seqs(root, sel).split(',').some(s => s !== '');
  let dirty = !observed;
  const obs = observed ? new MutationObserver(() => { dirty = true; }) : null;
  const watched = mode === 'text' ? [root]
    : (root.matches && root.matches(sel) ? [root] : Array.from(root.querySelectorAll(sel)));
  if (obs) for (const w of watched) obs.observe(w, {subtree: true, childList: true,
                                                     characterData: true, attributes: true});
  const figs = () => (mode === 'text' ? [] : watched).map(f => f.afmFigure).filter(f => f);
  const onKey = () => { if (st.t0 === null) st.t0 = performance.now(); };
  window.addEventListener('keydown', onKey, true);
  const start = performance.now();
  st.promise = new Promise(resolve => {
    const finish = (r) => {
      window.removeEventListener('keydown', onKey, true);
      if (obs) obs.disconnect();
      resolve(r);
    };
    const tick = (ts) => {
      const now = performance.now();
      if (st.t0 !== null && tRead === null && readBase !== null && readouts() !== readBase) {
        tRead = ts;
      }
      let changed = false;
      if (st.t0 !== null && dirty) {
        changed = probe() !== base;
        if (observed) dirty = false;
      }
      if (changed) {
        // a live figure draws in an animation-frame callback, painted in that same frame: the
        // change is dated by that frame's time, as the floor's text is by the frame after its
        // mutation (both: the frame whose rendering shows it), not by this later check
        const drawn = figs().map(f => f.drawnAt).filter(t => t != null && t >= st.t0);
        const at = drawn.length ? Math.min(ts, Math.max(...drawn)) : ts;
        finish({dt: Math.max(at, st.t0) - st.t0, frame: at, keydown: st.t0,
                readout: tRead === null ? null : Math.max(tRead, st.t0) - st.t0});
      } else if (now - start > timeoutMs) {
        finish({dt: null, keydown: st.t0});
      } else requestAnimationFrame(tick);
    };
    requestAnimationFrame(tick);
  });
  afm.current = st;
  return base.length;
};
// arm a drag: record on every frame the painted data-seq and pixel states, until quiet
afm.armDrag = (sel, quietMs, timeoutMs) => {
  const root = afm.root();
  const st = {t0: null, seqs: [], states: 0, times: [], values: [], keys: 0, paints: []};
  const readout = () => {
    const e = document.activeElement, w = e && e.closest && e.closest('.widget-slider');
    const r = w && w.querySelector('.widget-readout');
    return r ? r.textContent.trim() : null;
  };
  let lastSeq = afm.seqs(root, sel), lastHash = afm.checksum(root, sel).hash;
  const baseSeq = lastSeq, baseFrames = afm.frames(root, sel);
  let lastPainted = afm.paintedCount(root, sel);
  // live figures count their paints: each is dated by the animation frame that drew it, and
  // their pixels are read once, when the drag is over (whether they changed). Reading them
  // during the drag cost the page's main thread 2-3 ms a read, time a student's page does not
  // spend: read on every animation frame they took a third of it, read after each paint they
  // still delayed the kernel's next frames they were timing (the floor's drag reads no pixels)
  const live = baseFrames.some(f => f);
  const baseHash = lastHash;
  const figs = (root.matches && root.matches(sel) ? [root] : Array.from(root.querySelectorAll(sel)))
    .map(f => f.afmFigure).filter(f => f);
  const onKey = () => {
    st.keys++;
    st.tLast = performance.now();
    if (st.t0 === null) st.t0 = st.tLast;
  };
  window.addEventListener('keydown', onKey, true);
  const start = performance.now();
  let lastChange = null;
  st.promise = new Promise(resolve => {
    const tick = (ts) => {
      const now = performance.now();
      const painted = afm.paintedCount(root, sel), newPaint = painted !== lastPainted;
      const seq = afm.seqs(root, sel), v = readout();
      const hash = live ? lastHash : afm.checksum(root, sel).hash;
      if (v !== null && v !== st.values[st.values.length - 1]) st.values.push(v);
      if (seq !== lastSeq) {
        if (seq !== baseSeq && !st.seqs.includes(seq)) st.seqs.push(seq);
        lastSeq = seq;
        lastChange = now;
      }
      if (newPaint) {
        lastPainted = painted;
        lastChange = now;
        // a live figure's paint is counted after the rendering that showed it, so this check
        // runs an animation frame later: the change is dated by the frame that drew it, as a
        // single press's is (afm.arm) and as the floor's text is by the frame after its mutation
        const drawn = figs.map(f => f.drawnAt).filter(t => t != null);
        const at = drawn.length ? Math.min(ts, Math.max(...drawn)) : ts;
        st.times.push(at - (st.t0 || at));
        // the frames painted by now, each with this date (the last paint of each figure)
        figs.forEach(f => { const n = f.paintedSeqs.length;
                            if (n) st.paints.push([f.paintedSeqs[n - 1], at - (st.t0 || at)]); });
      }
      if (hash !== lastHash) {  // no live figure: a change of its pixels, dated by this frame
        st.states++;
        st.times.push(ts - (st.t0 || ts));
        lastHash = hash;
        lastChange = now;
      }
      // quiet since the last change or the last key, whichever came later: on a loaded machine
      // the keys alone may take longer than quietMs, and the first frame comes after them
      const stamps = [lastChange, st.tLast].filter(v => v !== null && v !== undefined);
      const quietFrom = stamps.length ? Math.max(...stamps) : null;
      if ((quietFrom !== null && now - quietFrom > quietMs) || now - start > timeoutMs) {
        window.removeEventListener('keydown', onKey, true);
        const changed = afm.checksum(root, sel).hash !== baseHash;
        resolve({seqs: st.seqs, states: st.states, times: st.times, changed: changed,
                 lastKey: st.t0 === null ? null : st.tLast - st.t0,
                 timedOut: now - start > timeoutMs, baseSeq: baseSeq, values: st.values,
                 keys: st.keys, frames: afm.framesSince(root, sel, baseFrames),
                 paints: st.paints});
      } else requestAnimationFrame(tick);
    };
    requestAnimationFrame(tick);
  });
  afm.current = st;
  return true;
};
// wait until the figure's pixels stay the same for quietMs (bounded); resolves the check
afm.quiet = (sel, quietMs, timeoutMs) => new Promise(resolve => {
  const root = afm.root();
  let last = afm.checksum(root, sel).hash, since = performance.now();
  const start = since;
  const tick = () => {
    const now = performance.now(), h = afm.checksum(root, sel).hash;
    if (h !== last) { last = h; since = now; }
    if (now - since >= quietMs) resolve(true);
    else if (now - start > timeoutMs) resolve(false);
    else requestAnimationFrame(tick);
  };
  requestAnimationFrame(tick);
});
})();
"""


def watch_requests(page) -> list:
    """Record every address ``page`` asks for from now on (HTTP requests and WebSockets)."""
    asked: list = []
    page.on("request", lambda r: asked.append(r.url))
    page.on("websocket", lambda ws: asked.append(ws.url))
    return asked


def foreign(asked, host: str = "127.0.0.1") -> list:
    """The addresses in ``asked`` on any host but ``host`` (the page's own data:, blob: and
    about: addresses are not requests to a host)."""
    from urllib.parse import urlsplit
    return [url for url in asked
            if urlsplit(url).scheme not in ("data", "blob", "about")
            and urlsplit(url).hostname != host]


# -- notebooks in JupyterLab and voila -----------------------------------------------------
def open_lab(page, server: Server, notebook: str, *, timeout: float = 90.0) -> None:
    """Open ``notebook`` in JupyterLab and wait until its kernel is ready.

    On a page where JupyterLab already runs, the notebooks open there are closed unsaved and
    every kernel shut down first, and the notebook is opened in the same page (no reload).
    """
    if page.evaluate("() => !!window.jupyterapp"):
        page.evaluate(
            """() => { const a = window.jupyterapp;
                       for (const w of Array.from(a.shell.widgets('main'))) {
                         if (w.context) w.context.model.dirty = false;
                         w.dispose(); } }""")
        server.shutdown_kernels()
        page.evaluate("(path) => window.jupyterapp.commands.execute('docmanager:open', {path})",
                      notebook)
    else:
        page.goto(server.url(notebook), timeout=timeout * 1000)
    page.wait_for_function(
        """(path) => { const a = window.jupyterapp; if (!a) return false;
                   const w = a.shell.currentWidget;
                   return !!(w && w.content && w.context && w.context.path === path
                             && w.sessionContext && w.sessionContext.session
                             && w.sessionContext.session.kernel
                             && w.sessionContext.session.kernel.status === 'idle'); }""",
        arg=notebook, timeout=timeout * 1000, polling="raf")


def close_lab_notebook(page, server: Server) -> None:
    """Leave JupyterLab's page and shut every kernel down (gracefully: exit handlers run)."""
    with contextlib.suppress(Exception):
        page.goto("about:blank")
    server.shutdown_kernels()


#: True once the current notebook's Run All is over: a cell shows an error (Run All stops there),
#: or the kernel is idle with every code cell run and no prompt still busy.
RUN_ALL_DONE_JS = """() => { const w = window.jupyterapp.shell.currentWidget;
    const cells = w.content.model.cells;
    for (let i = 0; i < cells.length; i++) {
      const c = cells.get(i);
      if (c.type !== 'code') continue;
      for (let j = 0; j < c.outputs.length; j++)
        if (c.outputs.get(j).type === 'error') return true;
    }
    const k = w.sessionContext.session.kernel;
    if (!k || k.status !== 'idle') return false;
    for (let i = 0; i < cells.length; i++) {
      const c = cells.get(i);
      if (c.type === 'code' && c.executionCount === null) return false;
    }
    return !Array.from(document.querySelectorAll('.jp-InputArea-prompt'))
                .some(p => p.textContent.includes('*')); }"""


def run_all(page, *, timeout: float = 300.0) -> float:
    """Run All in JupyterLab and wait until every cell ran and the kernel is idle; seconds.

    A cell that shows an error stops Run All (the cells after it never run): the error is
    raised at once with the cell's number, never waited for until ``timeout``. On a timeout,
    the cell still running (``[*]``) and its source are named.
    """
    t0 = time.monotonic()
    page.evaluate(
        """(ms) => Promise.race([
               window.jupyterapp.commands.execute('notebook:run-all-cells'),
               new Promise(r => setTimeout(() => r('timeout'), ms))])""", timeout * 1000)
    left = max(1.0, timeout - (time.monotonic() - t0))
    try:
        page.wait_for_function(
            RUN_ALL_DONE_JS,
            timeout=left * 1000, polling="raf")
    except Exception as exc:
        raise AssertionError(f"Run All did not end within {timeout:.0f} s; still running: "
                             f"{_running_cells(page)}") from exc
    errors = lab_errors(page)
    if errors:
        raise AssertionError(f"Run All stopped at an error: {errors}")
    return time.monotonic() - t0


def _running_cells(page) -> list[str]:
    """The open notebook's cells whose prompt shows ``[*]``: index and source's first line."""
    with contextlib.suppress(Exception):
        return page.evaluate(
            """() => { const w = window.jupyterapp.shell.currentWidget, out = [];
                       w.content.widgets.forEach((cell, i) => {
                         const p = cell.node.querySelector('.jp-InputArea-prompt');
                         if (p && p.textContent.includes('*'))
                           out.push(i + ': ' + cell.model.sharedModel.getSource().slice(0, 120));
                       });
                       return out; }""")
    return ["(the page did not answer)"]


def wait_idle(page, *, timeout: float = 300.0) -> None:
    """Wait until the open notebook's kernel is idle and no cell is queued (bounded)."""
    page.wait_for_function(
        """() => { const w = window.jupyterapp.shell.currentWidget;
                   const k = w.sessionContext.session.kernel;
                   if (!k || k.status !== 'idle') return false;
                   return !Array.from(document.querySelectorAll('.jp-InputArea-prompt'))
                               .some(p => p.textContent.includes('*')); }""",
        timeout=timeout * 1000, polling="raf")


def code_cells(page) -> list[int]:
    """Indices of the open notebook's code cells."""
    return page.evaluate(
        """() => { const cells = window.jupyterapp.shell.currentWidget.content.model.cells, out = [];
                   for (let i = 0; i < cells.length; i++)
                     if (cells.get(i).type === 'code') out.push(i);
                   return out; }""")


def run_cell(page, index: int, *, timeout: float = 300.0) -> None:
    """Run cell ``index`` of the open notebook as a student would (select it, Ctrl-Enter)."""
    page.evaluate(
        """(i) => { const nb = window.jupyterapp.shell.currentWidget.content;
                    nb.activeCellIndex = i; nb.deselectAll();
                    return window.jupyterapp.commands.execute('notebook:run-cell'); }""", index)
    wait_idle(page, timeout=timeout)


#: The element of a 3D view (afmsmiler.scenes.view.SceneView): it holds meshcat's WebGL canvas
#: and carries ``data-commands`` (the scene's commands) and ``data-applied`` (commands drawn).
SCENE_VIEW = ".afm-scene"


def scene_views(page) -> list[dict]:
    """Every 3D view shown on the page: its commands, commands applied, canvases and size."""
    return page.evaluate(
        """(sel) => Array.from(document.querySelectorAll(sel))
                     .filter(e => e.dataset.commands !== undefined)
                     .map(e => ({commands: Number(e.dataset.commands),
                                 applied: Number(e.dataset.applied || 0),
                                 canvases: e.querySelectorAll('canvas').length,
                                 width: e.clientWidth, height: e.clientHeight}))""", SCENE_VIEW)


def scene_pixels(page, index: int):
    """The pixels of the ``index``-th 3D view on the page, as an RGB PIL image (a screenshot:
    WebGL keeps no drawing buffer to read back)."""
    import io

    from PIL import Image
    loc = page.locator(SCENE_VIEW).nth(index)
    loc.scroll_into_view_if_needed()
    page.wait_for_timeout(300)  # meshcat paints on its next animation frame
    return Image.open(io.BytesIO(loc.screenshot())).convert("RGB")


def cell_isolation(page) -> list[str]:
    """The computed ``isolation`` of every cell of the notebooks in the page (``live.css``: the
    cells of a notebook that holds a live figure are each a stacking context, painted on their
    own; those of any other notebook are left as JupyterLab styles them)."""
    return page.evaluate(
        "() => Array.from(document.querySelectorAll('.jp-Notebook .jp-Cell'))"
        ".map(c => getComputedStyle(c).isolation)")


def lab_errors(page) -> list[str]:
    """The error outputs of the open notebook: tracebacks and panels that could not update."""
    return page.evaluate(
        """() => { const w = window.jupyterapp.shell.currentWidget, out = [];
                   const cells = w.content.model.cells;
                   for (let j = 0; j < cells.length; j++) {
                     const c = cells.get(j);
                     if (c.type !== 'code') continue;
                     for (let i = 0; i < c.outputs.length; i++) {
                       const o = c.outputs.get(i).toJSON();
                       if (o.output_type === 'error') out.push(o.ename + ': ' + o.evalue);
                     }
                   }
                   for (const e of document.querySelectorAll('.jp-OutputArea-output'))
                     if (e.textContent.includes('The panel could not update'))
                       out.push(e.textContent.slice(0, 300));
                   return out; }""")


def kernel_eval(page, code: str, *, timeout: float = 30.0) -> str:
    """Run ``code`` silently in the open notebook's kernel (lab); return what it printed."""
    return page.evaluate(
        """async ([code, ms]) => {
             const k = window.jupyterapp.shell.currentWidget.sessionContext.session.kernel;
             let text = '';
             const f = k.requestExecute({code, silent: false, store_history: false});
             f.onIOPub = (m) => {
               const t = m.header.msg_type;
               if (t === 'stream') text += m.content.text;
               else if (t === 'error') text += m.content.ename + ': ' + m.content.evalue;
             };
             await Promise.race([f.done, new Promise(r => setTimeout(r, ms))]);
             return text; }""", [code, timeout * 1000])


def open_voila(page, server: Server, notebook: str | None, slider: str, *,
               timeout: float = 240.0) -> None:
    """Open a notebook in voila and wait until ``slider`` is shown (a CSS selector of the
    slider's widget when it starts with ".", else part of its description)."""
    page.goto(server.url(notebook), timeout=timeout * 1000, wait_until="domcontentloaded")
    handle = (page.locator(f"{slider} .noUi-handle").first if slider.startswith(".")
              else find_slider(page, slider))
    handle.wait_for(state="visible", timeout=timeout * 1000)


def voila_errors(page) -> list[str]:
    """Tracebacks and failed panel updates shown on a voila page."""
    return page.evaluate(
        """() => { const out = [];
                   for (const e of document.querySelectorAll(
                       '.jp-OutputArea-output, .voila-error, .jp-RenderedText'))
                     if (/Traceback|The panel could not update/.test(e.textContent))
                       out.push(e.textContent.slice(0, 300));
                   return Array.from(new Set(out)); }""")


def find_control(page, entry):
    """The handle of registry ``entry``'s slider, inside its own panel: a Locator."""
    return page.locator(f"{entry.slider_selector} .noUi-handle").first


def find_slider(page, description: str):
    """The slider whose description contains ``description``: a Locator of its handle."""
    row = page.locator(".widget-slider").filter(
        has=page.locator(".widget-label", has_text=description))
    return row.locator(".noUi-handle").first


def slider_value(slider) -> str:
    """The value a slider's readout shows."""
    return slider.evaluate(
        "h => h.closest('.widget-slider').querySelector('.widget-readout').textContent.trim()")


def keys(slider) -> tuple[str, str]:
    """(towards the far end, back): the arrow key with the more room on ``slider`` first.

    A notebook may leave a slider at an end (notebook 02 sweeps the input up to its maximum),
    where a press towards that end changes nothing.
    """
    low, now, high = slider.evaluate(
        "h => ['aria-valuemin', 'aria-valuenow', 'aria-valuemax']"
        ".map(a => parseFloat(h.getAttribute(a)))")
    return ("ArrowRight", "ArrowLeft") if high - now >= now - low else ("ArrowLeft", "ArrowRight")


def focus_panel(page, slider, selector: str, *, quiet: float = 0.6,
                timeout: float = 30.0) -> bool:
    """Mark the panel holding ``slider`` (the closest box with a figure), scroll it into view
    and wait until its figure's pixels stay the same for ``quiet`` s (bounded)."""
    if not slider.evaluate("(h, sel) => window.__afm.mark(h, sel)", selector):
        raise LookupError(f"no figure ({selector}) in the box of the slider")
    slider.scroll_into_view_if_needed()
    page.evaluate(
        "() => { const r = window.__afm.root(); "
        "const f = r.querySelector('canvas'); if (f) f.scrollIntoView({block: 'center'}); }")
    slider.scroll_into_view_if_needed()
    return settle(page, selector, quiet=quiet, timeout=timeout)


def settle(page, selector: str, *, quiet: float = 0.3, timeout: float = 5.0) -> bool:
    """Wait until the marked panel's figure keeps its pixels for ``quiet`` s (at most
    ``timeout`` s); whether it did."""
    return page.evaluate("([sel, q, t]) => window.__afm.quiet(sel, q, t)",
                         [selector, quiet * 1000, timeout * 1000])


def figure_state(page, selector: str) -> dict:
    """Canvases and lit pixels of the marked panel's figure(s), and their data-frames/-seq."""
    return page.evaluate(
        """(sel) => { const r = window.__afm.root(), c = window.__afm.checksum(r, sel);
                      const figs = Array.from(r.querySelectorAll(sel));
                      return {canvases: c.n, lit: c.lit, figures: figs.length,
                              frames: figs.map(f => f.getAttribute('data-frames')),
                              seq: figs.map(f => f.getAttribute('data-seq'))}; }""", selector)


def _press_once(page, slider, key: str, selector: str, mode: str, timeout: float) -> dict:
    page.evaluate("([sel, mode, ms]) => window.__afm.arm(sel, mode, ms)",
                  [selector, mode, timeout * 1000])
    slider.press(key)
    r = page.evaluate("() => window.__afm.current.promise")
    return {k: None if r.get(k) is None else r[k] / 1000.0 for k in ("dt", "readout")}


def press_detail(page, slider, key: str = "ArrowRight", n: int = 1, *, selector: str,
                 timeout: float = PRESS_TIMEOUT, settle_s: float = 0.3) -> list:
    """As :func:`press`, each press as ``{"dt": key-to-pixels, "readout": key-to-readouts}``.

    ``readout`` is the first frame at which the panel's own HTML readouts (``.widget-html``)
    changed, if before the pixels (else None): the kernel's answer without the figure.
    """
    out = []
    for _ in range(n):
        out.append(_press_once(page, slider, key, selector, "pixels", timeout))
        settle(page, selector, quiet=settle_s, timeout=timeout)
    return out


def press(page, slider, key: str = "ArrowRight", n: int = 1, *, selector: str,
          timeout: float = PRESS_TIMEOUT, settle_s: float = 0.3) -> list:
    """Press ``key`` on ``slider`` ``n`` times; each press's key-to-pixels time in s (or None).

    The figure is the marked panel's (:func:`focus_panel`); between presses the figure is
    let settle (its pixels unchanged for ``settle_s`` s, at most ``timeout``), so each press
    starts from a still picture.
    """
    return [r["dt"] for r in press_detail(page, slider, key, n, selector=selector,
                                          timeout=timeout, settle_s=settle_s)]


def press_text(page, slider, key: str = "ArrowRight", n: int = 1, *,
               timeout: float = PRESS_TIMEOUT, settle_s: float = 0.2) -> list:
    """The floor: press ``key`` ``n`` times; each press's key-to-changed-text time (or None).

    The marked element is the slider's box (:func:`mark_text`); the time is the first
    animation frame after its text changed (seen by a MutationObserver).
    """
    out = []
    for _ in range(n):
        out.append(_press_once(page, slider, key, "canvas", "text", timeout)["dt"])
        time.sleep(settle_s)
    return out


def mark_text(page, slider, text_selector: str = ".widget-label") -> None:
    """Mark the box that holds ``slider`` and a second widget (the floor's Label)."""
    ok = slider.evaluate(
        """(h) => { let p = h.closest('.widget-slider').parentElement;
                    document.querySelectorAll('[data-afm-panel]')
                      .forEach(e => e.removeAttribute('data-afm-panel'));
                    // the label only (the slider's own readout changes at once, in the browser)
                    const labels = Array.from(p.children)
                                        .filter(c => !c.classList.contains('widget-slider'));
                    if (!labels.length) return false;
                    labels[0].setAttribute('data-afm-panel', '1'); return true; }""")
    if not ok:
        raise LookupError("no label beside the floor slider")
    slider.scroll_into_view_if_needed()


@dataclass
class DragResult:
    """A burst of key presses: what was painted."""

    presses: int
    seqs: list = field(default_factory=list)  # distinct data-seq values painted (live figure)
    states: int = 0  # distinct pixel states painted (no live figure: read every animation frame)
    #: Whether the figure's pixels differ from before the drag (read once it is over); None when
    #: the page did not say.
    changed: bool | None = None
    timed_out: bool = False
    last_frame_s: float | None = None  # s from the first keydown to the last change painted
    last_key_s: float | None = None  # s from the first keydown to the last one
    values: list = field(default_factory=list)  # the slider's readout, as it changed per frame
    keys: int = 0  # keydown events the page saw
    #: Per live figure of the panel: the kernel's sequence numbers of the frames it received
    #: and of those it painted (each recorded by the figure at the animation frame after its
    #: draw, so after a paint), in order; empty without a live figure.
    frames: list = field(default_factory=list)
    #: ``(seq, s from the first keydown)`` of each frame a live figure painted, dated as
    #: ``last_frame_s`` is; empty without a live figure.
    paints: list = field(default_factory=list)

    def painted_at_s(self, seq: int) -> float | None:
        """s from the last keydown to the paint of frame ``seq`` (None if it was not painted)."""
        at = [t for s, t in self.paints if s == seq]
        if not at or self.last_key_s is None:
            return None
        return at[0] / 1000.0 - self.last_key_s

    @property
    def after_last_key_s(self) -> float | None:
        """s from the last keydown to the last change painted (None when nothing changed)."""
        if self.last_frame_s is None or self.last_key_s is None:
            return None
        return self.last_frame_s - self.last_key_s

    @property
    def received(self) -> int:
        """Frames the panel's live figures received during the drag."""
        return sum(len(f["received"]) for f in self.frames if f)

    @property
    def painted(self) -> int:
        """Frames the panel's live figures painted during the drag (a frame painted twice
        counts twice)."""
        return sum(len(f["painted"]) for f in self.frames if f)

    @property
    def painted_once(self) -> bool:
        """Whether every frame received was painted exactly once, in the order received."""
        return all(f["painted"] == f["received"] for f in self.frames if f)

    @property
    def last_painted(self) -> list:
        """Per live figure, the sequence number of the last frame painted (None if none)."""
        return [f["painted"][-1] if f and f["painted"] else None for f in self.frames]

    @property
    def steps_drawn(self) -> int:
        """Steps seen painted: the frames the live figures painted (their own count, made after
        the paint), else distinct pixel states seen on animation frames."""
        if any(self.frames):
            return self.painted
        return self.states

    @property
    def jumped_back(self) -> list:
        """Readouts at which the slider moved against the keys (a value from the kernel
        overriding the student's later presses), e.g. ``["69.00 -> 61.00"]``."""
        def num(text):
            return float(text.replace(",", "").replace("\u2212", "-"))
        try:
            v = [num(x) for x in self.values]
        except ValueError:
            return []
        if len(v) < 3:
            return []
        sign = 1 if v[-1] >= v[0] else -1
        return [f"{self.values[i]} -> {self.values[i + 1]}" for i in range(len(v) - 1)
                if (v[i + 1] - v[i]) * sign < 0]


def press_keys(page, key: str, n: int, interval: float = 0.0) -> None:
    """Press ``key`` ``n`` times on the focused element, trusted key events from Playwright.

    With ``interval`` 0 each press follows the one before as soon as the browser took it (a few
    ms): the page's input queue stays full and it mostly handles no message from the kernel
    until the keys stop. With ``interval`` > 0 the presses start ``interval`` s apart (each
    waits for the one before if that took longer), as a held key repeats (some 30 a second) or
    a mouse drag moves.
    """
    if not interval >= 0:  # nan too: it would press as fast as 0
        raise ValueError(f"interval must be a number >= 0 s, got {interval!r}")
    for i in range(n):
        start = time.monotonic()
        page.keyboard.press(key)
        if interval and i < n - 1:
            time.sleep(max(0.0, interval - (time.monotonic() - start)))


def drag(page, slider, key: str = "ArrowLeft", n: int = 15, *, selector: str,
         quiet: float = 1.5, timeout: float = 20.0, interval: float = 0.0) -> DragResult:
    """Send ``n`` presses of ``key`` (:func:`press_keys`: as fast as possible, or ``interval``
    s apart) and record the frames painted."""
    page.evaluate("([sel, q, t]) => window.__afm.armDrag(sel, q, t)",
                  [selector, quiet * 1000, timeout * 1000])
    slider.focus()
    press_keys(page, key, n, interval)
    r = page.evaluate("() => window.__afm.current.promise")
    seqs = [s for s in r["seqs"] if s.strip(",")]
    return DragResult(presses=n, seqs=seqs, states=r["states"], timed_out=r["timedOut"],
                      last_frame_s=(r["times"][-1] / 1000.0) if r["times"] else None,
                      last_key_s=None if r.get("lastKey") is None else r["lastKey"] / 1000.0,
                      values=r["values"], keys=r["keys"], frames=r.get("frames") or [],
                      changed=r.get("changed"), paints=r.get("paints") or [])


def burst(page, slider, key: str = "ArrowLeft", n: int = 15, *, selector: str,
          quiet: float = 1.5, timeout: float = 20.0) -> DragResult:
    """As :func:`drag`, the ``n`` key presses dispatched in one task of the page.

    Playwright's presses each wait for a round trip to the browser (a few ms, more on a busy
    machine), so the kernel often answers one before the next arrives; dispatched at once, the
    moves reach the kernel while it runs the model for the first, and queue behind it.
    """
    page.evaluate("([sel, q, t]) => window.__afm.armDrag(sel, q, t)",
                  [selector, quiet * 1000, timeout * 1000])
    slider.focus()
    slider.evaluate(
        """(h, [key, n]) => {
             for (let i = 0; i < n; i++) for (const type of ['keydown', 'keyup'])
               h.dispatchEvent(new KeyboardEvent(type, {key, bubbles: true, cancelable: true}));
           }""", [key, n])
    r = page.evaluate("() => window.__afm.current.promise")
    seqs = [s for s in r["seqs"] if s.strip(",")]
    return DragResult(presses=n, seqs=seqs, states=r["states"], timed_out=r["timedOut"],
                      last_frame_s=(r["times"][-1] / 1000.0) if r["times"] else None,
                      last_key_s=None if r.get("lastKey") is None else r["lastKey"] / 1000.0,
                      values=r["values"], keys=r["keys"], frames=r.get("frames") or [],
                      changed=r.get("changed"), paints=r.get("paints") or [])


# -- static export -------------------------------------------------------------------------
@dataclass(frozen=True)
class HeadlessRun:
    """A course notebook run once under nbclient with no browser, as a student's kernel runs it.

    Attributes
    ----------
    frames : dict
        Frames each panel of the notebook (registry variable -> ``live.frames_sent``) sent by
        the end of the run: with a browser attached, every frame beyond these was caused by the
        page itself (an echo of a slider, a redraw on display).
    html : pathlib.Path
        The executed notebook exported to HTML by nbconvert's HTMLExporter (what
        ``jupyter nbconvert --to html --execute`` writes), without the cell that read the frames.
    """
    frames: dict
    html: Path


_HEADLESS: dict = {}


def headless_run(notebook: str, shared: Path, *, timeout: float = 300.0) -> HeadlessRun:
    """Run ``notebook`` (a name in :data:`NOTEBOOKS`) once with no browser: :class:`HeadlessRun`.

    The run is made once per test run and notebook, by whichever xdist worker asks first (the
    other waits for it under a file lock in ``shared``, a directory every worker of the run
    sees: the ``headless`` fixture): the frames the lab test compares with and the HTML the
    static-export test opens come from one execution. The kernel runs in a student's
    environment (:func:`kernel_env`), in a fresh temporary working directory.
    """
    import fcntl
    key = (notebook, str(shared))
    if key in _HEADLESS:
        return _HEADLESS[key]
    stem = Path(notebook).stem
    out = Path(shared) / stem
    with open(Path(shared) / f"{stem}.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)  # released when the file closes
        if not (out / "frames.json").exists():
            out.mkdir(exist_ok=True)
            frames = _execute_and_export(NOTEBOOKS / notebook, out, timeout=timeout)
            (out / "frames.json").write_text(json.dumps(frames))
    run = HeadlessRun(frames=json.loads((out / "frames.json").read_text()),
                      html=out / f"{stem}.html")
    _HEADLESS[key] = run
    return run


def _execute_and_export(path: Path, out: Path, *, timeout: float) -> dict:
    import nbformat
    from nbclient import NotebookClient
    from nbconvert import HTMLExporter
    nb = nbformat.read(path, as_version=4)
    names = [e.variable for e in REGISTRY if e.notebook == path.name]
    nb.cells.append(nbformat.v4.new_code_cell(
        "import json\nprint(json.dumps({"
        + ", ".join(f"{n!r}: {n}.live.frames_sent" for n in names) + "}))"))
    workdir = Path(tempfile.mkdtemp(prefix="afm-headless-run-"))
    old = dict(os.environ)
    try:
        os.environ.clear()
        os.environ.update(kernel_env())
        NotebookClient(nb, timeout=int(timeout), kernel_name="python3",
                       resources={"metadata": {"path": str(workdir)}}).execute()
    finally:
        os.environ.clear()
        os.environ.update(old)
        shutil.rmtree(workdir, ignore_errors=True)
    last = nb.cells.pop()
    text = "".join(o.get("text", "") for o in last.outputs if o.get("name") == "stdout")
    body, _ = HTMLExporter().from_notebook_node(nb)
    (out / f"{path.stem}.html").write_text(body, encoding="utf-8")
    return json.loads(text)


def static_figures(page, html: Path, selector: str = LIVE_FIGURE, *,
                   timeout: float = 30.0) -> list:
    """Open an exported HTML file and return, per figure element, its canvases and lit pixels.

    Waits (bounded) until every figure has a canvas with pixels drawn.
    """
    page.goto(Path(html).resolve().as_uri(), wait_until="load", timeout=timeout * 1000)
    script = """(sel) => Array.from(document.querySelectorAll(sel)).map(f => {
                   const c = window.__afm.checksum(f, sel);
                   return {canvases: f.querySelectorAll('canvas').length, lit: c.lit,
                           frames: f.getAttribute('data-frames')}; })"""
    deadline = time.monotonic() + timeout
    figs = []
    while time.monotonic() < deadline:
        figs = page.evaluate(script, selector)
        if figs and all(f["lit"] > 0 for f in figs):
            break
        time.sleep(0.25)
    return figs


# -- summaries -----------------------------------------------------------------------------
def summary(times: list) -> dict:
    """Median and worst of the presses that changed pixels, and the failures, in s."""
    ok = [t for t in times if t is not None]
    return {"n": len(times), "failed": len(times) - len(ok),
            "median": statistics.median(ok) if ok else None, "worst": max(ok) if ok else None}
