"""Module (f)'s live panel: what watching a scan form costs on top of the scan itself.

Ours: ``ImagingPanel.start(run=False)`` then ``step()`` for every line of a 128 x 128
constant-force scan of the panel's default sample: per line, one run of the mode, the line copied
into the panel's image, and one frame of the live figure (its artists updated and read by
:func:`afmsmiler.plots.live.describe` into the message a browser draws; no browser here).

Peer: the same scan by the scanner alone, ``Scan(...).run()`` (the same sample, tip, mode and
settings, built from the panel's own values). The ratio is the price of the live view; its
per-line cost is what delays the next line while the student watches (target: under 20 ms, so a
128-line image is drawn within a few seconds beyond the scan).
"""
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _timing import best_time, report  # noqa: E402

from afmsmiler.imaging.scanner import Scan  # noqa: E402
from afmsmiler.ui.imaging import ImagingPanel  # noqa: E402

PIXELS = 128
panel = ImagingPanel(pixels=PIXELS)


def ours():
    panel.start(run=False)
    while panel.step():
        pass


def peer():
    c = panel._configure(panel.values())
    Scan(c.sample, c.tip, c.mode, c.settings).run()


def main():
    t_ours = best_time(ours, repeat=3, number=1)
    t_peer = best_time(peer, repeat=3, number=1)
    assert panel.last.lines_done == PIXELS
    per_line = (t_ours - t_peer) / PIXELS
    print(f"{PIXELS} x {PIXELS} constant-force scan, panel line by line vs the scanner alone")
    report([("scanner alone, Scan.run()", t_peer, None, None),
            ("panel: step() per line, one live frame each", t_ours, None, None),
            ("live view's cost per line", per_line, 0.02, None)])
    print(f"panel / scanner = {t_ours / t_peer:.2f}x")


if __name__ == "__main__":
    main()
