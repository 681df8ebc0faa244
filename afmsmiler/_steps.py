"""Run a model's steps (a generator that yields progress and returns its result) to the end.

A model that a panel runs in steps, one per turn of the kernel's loop
(:func:`~afmsmiler.modes.force_volume.force_volume_steps`,
:func:`~afmsmiler.modes.tapping.amplitude_curve_steps`), is run whole by its plain function
through :func:`run_steps`.
"""


def run_steps(steps, most: int, name: str):
    """Run the generator ``steps`` to its end and return what it returns.

    Parameters
    ----------
    steps : generator
        The model's steps.
    most : int
        The most ``next()`` calls its steps can take (the bound of the loop).
    name : str
        The steps' function, named if they take more.

    Raises
    ------
    RuntimeError
        If the steps take more than ``most`` calls (a bug in the model, not the input).
    """
    for _ in range(most):  # bounded
        try:
            next(steps)
        except StopIteration as done:
            return done.value
    raise RuntimeError(f"{name} took more than {most} steps")
