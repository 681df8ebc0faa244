"""Modules (g) and (h): each panel's kernel step per slider move (issue 24's floor, ~30 ms for a
text label's round trip; target: a panel's whole ``update``, model and figure data, within
15-20 ms), in plain Python, no browser.

For each panel of the registry (:data:`afmsmiler.ui.registry.PANELS`) of modules (g) and (h)
whose slider redraws at once, the panel is made at its defaults (no 3D view) and its registry
slider is moved :data:`MOVES` times, one slider step at a time (up from its default, down
where the range ends), as a student's drag does; the figure is the median wall time of
``panel.set(...)`` (the contract's conversion, the model and the figure's data, ready to send)
over those moves. A few more sliders the issue names (tapping's free amplitude, force volume's
peak force) are moved the same way. A panel that shows a quick result first in a live notebook
(force volume's coarse map and tapping's coarse curve, then the full one when the slider
rests) also gets a ``(coarse)``
row: as many moves (the other way from the default, so that the models remember nothing of
the row before) with a live loop that holds the full map back, so ``panel.set`` is the step
the browser waits for. ``BENCH_PANELS`` (comma-separated ``key`` or ``key:slider``)
chooses the rows. To compare with an earlier commit in the same run, export its library
(``git archive <commit> afmsmiler | tar -x -C /tmp/base``) and run this script with
``PYTHONPATH=/tmp/base`` and with the current tree in turns: on a shared machine the medians
move by tens of per cent from one run to the next (the min column less so).
"""
import contextlib
import importlib
import math
import os
import statistics
import sys
import time

import numpy as np

from afmsmiler.ui.registry import panels

#: Moves per row (the median is printed).
MOVES = 21
#: Sliders moved beside each registry slider: panel key -> slider names.
EXTRA = {"tapping": ("free_amplitude",), "force_volume": ("peak_force",)}
#: Panels with a quick first result in a live notebook: panel key -> the module whose
#: ``_live_loop`` decides it (timed again with a loop that holds the rest back).
COARSE = {"force_volume": "afmsmiler.ui.modes", "tapping": "afmsmiler.ui.modes"}
#: Sliders of those panels whose move never shows a quick result (tapping's setpoint reuses
#: the curve shown).
NOT_COARSE = {"tapping": ("setpoint_ratio",)}
#: The floor (a text label's kernel round trip in the browser, issue 24) and the target in s.
FLOOR, TARGET = 0.030, 0.020


def rows():
    """(entry, slider name, coarse) triples to time."""
    out = []
    for e in panels("g") + panels("h"):
        if not e.figure:
            continue
        for name in (e.slider,) + tuple(EXTRA.get(e.key, ())):
            out.append((e, name, False))
            if e.key in COARSE and name not in NOT_COARSE.get(e.key, ()):
                out.append((e, name, True))
    chosen = [s for s in os.environ.get("BENCH_PANELS", "").split(",") if s]
    if chosen:
        out = [(e, n, c) for e, n, c in out if e.key in chosen or f"{e.key}:{n}" in chosen]
    return out


class _Held:
    """A live loop that keeps what a panel schedules for later (the full map) and never runs it."""

    def call_later(self, delay, callback, *args):
        return self

    def cancel(self):
        pass


@contextlib.contextmanager
def live_first_step(entry):
    """Within: ``entry``'s panel believes it runs in a live notebook (see :data:`COARSE`)."""
    module = importlib.import_module(COARSE[entry.key])
    real = module._live_loop
    module._live_loop = _Held
    try:
        yield
    finally:
        module._live_loop = real


def steps(control, moves, down=False):
    """``moves`` display values one slider step apart, from the default up (or down where the
    range ends; ``down``: the other way round)."""
    v0, step = float(control.value), float(control.step)
    lo, hi = float(control.min), float(control.max)
    base = getattr(control, "base", None)  # a log slider's min, max and step are exponents
    if base is not None:
        v0 = math.log(v0, base)
    sign = 1.0 if v0 + moves * step <= hi else -1.0
    if down:
        sign = -1.0 if v0 - moves * step >= lo else 1.0
    values = v0 + sign * step * np.arange(1, moves + 1)
    values = values[(values >= lo) & (values <= hi)]
    if base is not None:
        values = base ** values
    return [float(f"{v:.12g}") for v in values]


def time_moves(entry, name, moves=MOVES, down=False):
    """Wall times in s of ``moves`` moves of slider ``name`` of a fresh panel (see :func:`steps`
    for ``down``)."""
    panel = entry.make()
    times = []
    for v in steps(panel.controls[name], moves, down):
        t0 = time.perf_counter()
        panel.set(**{name: v})
        times.append(time.perf_counter() - t0)
    return times


def main():
    print(f"median of {MOVES} moves per row; target < {TARGET * 1e3:g} ms, floor "
          f"~{FLOOR * 1e3:g} ms (a text label's round trip)", flush=True)
    print(f"{'panel':<14s} {'slider':<22s} {'median':>9s} {'min':>8s} {'max':>8s}", flush=True)
    for entry, name, coarse in rows():
        if coarse:
            with live_first_step(entry):  # other values than the row before: none remembered
                t = time_moves(entry, name, down=True)
        else:
            t = time_moves(entry, name)
        med = statistics.median(t)
        flag = "OK" if med < TARGET else ("floor" if med < FLOOR else "SLOW")
        label = f"{name} (coarse)" if coarse else name
        print(f"{entry.key:<14s} {label:<22s} {med * 1e3:7.1f} ms {min(t) * 1e3:5.1f} ms "
              f"{max(t) * 1e3:5.1f} ms  {flag}", flush=True)


if __name__ == "__main__":
    sys.exit(main())
