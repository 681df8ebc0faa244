"""A class on one machine: 1, 4 and 8 students at once on a local JupyterHub (issue 22).

For each class size a fresh hub (``tests/hub.py``: JupyterHub on 127.0.0.1, the local-process
spawner, system users ``course-student-N``) and one headless Chromium with a context per student.
All students log in at the same moment through the course's nbgitpuller link, which clones the
course into their home and opens module (d); they Run All, then press the contact panel's slider
together, round after round (the worst case: every key within a few ms), and then each at a moment
of their own within each round (:data:`SPREAD`, as a class presses). Printed per class size: each
student's memory (resident and unique to them, MiB: their JupyterLab and kernel), the time from
"Sign in" to their first figure's pixels, the key-to-pixels time of both kinds of presses (median
and worst over students and rounds) and their ratio to the one-student figure, and kernels lost.
The students' browsers run on the same two cores as the hub (as no real class's would), so the
figures are an upper bound of the load. Skipped, saying why, when not root or when JupyterHub, the
proxy or Chromium is missing.
``python benchmarks/bench_hub.py 1 4`` measures only those sizes.
"""
import statistics
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from tests import browser as B  # noqa: E402
from tests import hub as H  # noqa: E402

SIZES = (1, 4, 8)
PRESSES = 5  # rounds of presses, every student pressing once per round
#: s: the second set of rounds, each student pressing at a moment of their own within it (a
#: class: students do not press in the same millisecond); the first set presses together
SPREAD = 1.0


def measure(chromium, n: int) -> dict:
    names = H.students(n)
    with H.Hub(names) as hub:
        students = H.class_session(chromium, hub, presses=PRESSES, timeout=900,
                                   readable_by_others=False, spread=SPREAD)
    presses = [t for s in students for t in s.presses if t is not None]
    spread = [t for s in students for t in s.spread_presses if t is not None]
    return {
        "n": n,
        "rss": statistics.mean(s.memory["rss"] for s in students),
        "uss": statistics.mean(s.memory["uss"] for s in students),
        "first": statistics.median(s.first_figure_s for s in students),
        "first_worst": max(s.first_figure_s for s in students),
        "press": statistics.median(presses) if presses else None,
        "press_worst": max(presses) if presses else None,
        "spread": statistics.median(spread) if spread else None,
        "spread_worst": max(spread) if spread else None,
        "failed": sum(t is None for s in students for t in s.presses + s.spread_presses),
        "lost": sum(not s.kernel_alive for s in students),
        "errors": sum(len(s.errors) for s in students),
        "foreign": sum(len(s.foreign) for s in students),
    }


def main(sizes=SIZES) -> None:
    reason = H.unavailable()
    if reason:
        print(f"skipped: {reason}")
        return
    rows = []
    with B.browser() as chromium:
        for n in sizes:
            rows.append(measure(chromium, n))
            r = rows[-1]
            print(f"  {n} student(s) measured: first figure {r['first']:.1f} s, "
                  f"press together {r['press']:.3f} s, spread {r['spread']:.3f} s", flush=True)
    one = next((r for r in rows if r["n"] == 1), rows[0])

    def ratio(r, key):
        return r[key] / one[key] if r[key] and one[key] else float("nan")

    nan = float("nan")
    print(f"\nmodule (d) ({H.NOTEBOOK}) on a local JupyterHub; {PRESSES} rounds of presses "
          f"with every student pressing together (a few ms apart), then {PRESSES} rounds with "
          f"each at their own moment within {SPREAD:g} s (a shared 2-core machine that also "
          "runs every student's browser: ratios say more than seconds)")
    print(f"{'students':>8} {'RSS MiB':>8} {'USS MiB':>8} {'first fig s':>11} {'worst':>6} "
          f"{'ratio':>6} | {'together s':>10} {'worst':>6} {'ratio':>6} | {'spread s':>8} "
          f"{'worst':>6} {'ratio':>6} | {'no px':>5} {'lost':>4} {'err':>3} {'foreign':>7}")
    for r in rows:
        print(f"{r['n']:>8} {r['rss']:>8.0f} {r['uss']:>8.0f} {r['first']:>11.1f} "
              f"{r['first_worst']:>6.1f} {r['first'] / one['first']:>6.2f} | "
              f"{r['press'] or nan:>10.3f} {r['press_worst'] or nan:>6.3f} "
              f"{ratio(r, 'press'):>6.2f} | {r['spread'] or nan:>8.3f} "
              f"{r['spread_worst'] or nan:>6.3f} {ratio(r, 'spread'):>6.2f} | "
              f"{r['failed']:>5} {r['lost']:>4} {r['errors']:>3} {r['foreign']:>7}")
    print("target (issue 22): with 8 students, slider-to-pixels within 3x the one-student "
          "figure and no kernel lost")

if __name__ == "__main__":
    main(tuple(int(a) for a in sys.argv[1:]) or SIZES)
