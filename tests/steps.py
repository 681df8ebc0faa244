"""Run a model's steps (``force_volume_steps``, ``amplitude_curve_steps``) as a test reads them."""


def run_steps(steps, most=20_000):
    """Run a generator of a model's steps to its end: (what it yielded, what it returned)."""
    yielded = []
    for _ in range(most):  # bounded: a map's or a curve's steps are fewer
        try:
            yielded.append(next(steps))
        except StopIteration as done:
            return yielded, done.value
    raise AssertionError("the steps did not end")
