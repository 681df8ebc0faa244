"""Run every benchmark script in this folder (``make bench``) and print their figures.

Each ``bench_*.py`` measures one issue's speed targets as ratios against the named peer, in one
run on this machine, and prints a short table. Nothing here is asserted by the tests: tests check
correctness, benchmarks report speed. ``bench_browser`` measures end to end in headless Chromium
(key press -> pixels, against the slider -> label floor of the same run; a few minutes; it prints
why when there is no browser); ``bench_scene_view`` times a key press to the 3D view repainted
against the old transport (a meshcat server per kernel in an iframe, from a temporary git worktree
of commit 9f60579). Name scripts to run only those: ``run_all.py browser contact``.
"""
import runpy
import sys
from pathlib import Path

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE))  # for the shared _timing helpers


def main(names=None):
    scripts = sorted(HERE.glob("bench_*.py"))
    if names:
        scripts = [s for s in scripts if any(n in s.stem for n in names)]
    for script in scripts:
        print(f"\n=== {script.stem} ===", flush=True)
        runpy.run_path(str(script), run_name="__main__")


if __name__ == "__main__":
    main(sys.argv[1:])
