"""Small timing helpers shared by the benchmark scripts."""
import time

import numpy as np


def best_time(func, *, repeat=7, number=None, min_time=0.2):
    """Best-of-``repeat`` wall time of one call of ``func`` in seconds (timeit-style).

    ``number`` calls are timed together per repeat; by default enough to last ``min_time``.
    """
    if number is None:
        number, t = 1, 0.0
        while True:
            t0 = time.perf_counter()
            for _ in range(number):
                func()
            t = time.perf_counter() - t0
            if t >= min_time / repeat or number >= 1 << 20:
                break
            number *= 2
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        for _ in range(number):
            func()
        times.append((time.perf_counter() - t0) / number)
    return float(np.min(times))


def report(rows):
    """Print rows of (label, seconds, target_seconds_or_None, peer_seconds_or_None)."""
    for label, t, target, peer in rows:
        line = f"{label:<58s} {t * 1e3:10.3f} ms"
        if target is not None:
            line += f"   target < {target * 1e3:g} ms: {'OK' if t < target else 'MISSED'}"
        if peer is not None:
            line += f"   peer/ours = {peer / t:8.1f}x"
        print(line, flush=True)
