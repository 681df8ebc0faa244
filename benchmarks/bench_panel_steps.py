"""Modules (g) and (h): each panel's kernel step per slider move (issue 24's floor, ~30 ms for a
text label's round trip; target: a panel's whole ``update``, model and figure data, within
15-20 ms), in plain Python, no browser.

For each panel of the registry (:data:`afmsmiler.ui.registry.PANELS`) of modules (g) and (h)
whose slider redraws at once, the panel is made at its defaults (no 3D view) and its registry
slider is moved :data:`MOVES` times, one slider step at a time (up from its default, down
where the range ends), as a student's drag does; the figure is the median wall time of
``panel.set(...)`` (the contract's conversion, the model and the figure's data, ready to send)
over those moves. A few more sliders the issue names (tapping's free amplitude, force volume's
peak force) are moved the same way. ``BENCH_PANELS`` (comma-separated ``key`` or ``key:slider``)
chooses the rows. To compare with an earlier commit in the same run, export its library
(``git archive <commit> afmsmiler | tar -x -C /tmp/base``) and run this script with
``PYTHONPATH=/tmp/base`` and with the current tree in turns: on a shared machine the medians
move by tens of per cent from one run to the next (the min column less so).
"""
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
#: The floor (a text label's kernel round trip in the browser, issue 24) and the target in s.
FLOOR, TARGET = 0.030, 0.020


def rows():
    """(entry, slider name) pairs to time."""
    out = []
    for e in panels("g") + panels("h"):
        if not e.figure:
            continue
        out.append((e, e.slider))
        out.extend((e, name) for name in EXTRA.get(e.key, ()))
    chosen = [s for s in os.environ.get("BENCH_PANELS", "").split(",") if s]
    if chosen:
        out = [(e, n) for e, n in out if e.key in chosen or f"{e.key}:{n}" in chosen]
    return out


def steps(control, moves):
    """``moves`` display values one slider step apart, from the default up (or down)."""
    v0, step = float(control.value), float(control.step)
    lo, hi = float(control.min), float(control.max)
    base = getattr(control, "base", None)  # a log slider's min, max and step are exponents
    if base is not None:
        v0 = math.log(v0, base)
    sign = 1.0 if v0 + moves * step <= hi else -1.0
    values = v0 + sign * step * np.arange(1, moves + 1)
    values = values[(values >= lo) & (values <= hi)]
    if base is not None:
        values = base ** values
    return [float(f"{v:.12g}") for v in values]


def time_moves(entry, name, moves=MOVES):
    """Wall times in s of ``moves`` moves of slider ``name`` of a fresh panel."""
    panel = entry.make()
    times = []
    for v in steps(panel.controls[name], moves):
        t0 = time.perf_counter()
        panel.set(**{name: v})
        times.append(time.perf_counter() - t0)
    return times


def main():
    print(f"median of {MOVES} moves per row; target < {TARGET * 1e3:g} ms, floor "
          f"~{FLOOR * 1e3:g} ms (a text label's round trip)", flush=True)
    print(f"{'panel':<14s} {'slider':<22s} {'median':>9s} {'min':>8s} {'max':>8s}", flush=True)
    for entry, name in rows():
        t = time_moves(entry, name)
        med = statistics.median(t)
        flag = "OK" if med < TARGET else ("floor" if med < FLOOR else "SLOW")
        print(f"{entry.key:<14s} {name:<22s} {med * 1e3:7.1f} ms {min(t) * 1e3:5.1f} ms "
              f"{max(t) * 1e3:5.1f} ms  {flag}", flush=True)


if __name__ == "__main__":
    sys.exit(main())
