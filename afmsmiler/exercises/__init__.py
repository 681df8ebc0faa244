"""Exercise checkers for the notebooks (one module per course module).

A checker takes the student's answer (in SI units unless its docstring says otherwise), compares it
with what the model says, and returns a :class:`Feedback` that prints as a friendly message and is
truthy when the answer is right, so that tests can assert on it and notebooks can just show it.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["Feedback", "check_close"]


@dataclass(frozen=True)
class Feedback:
    """The verdict of a checker: ``passed`` and a message for the student."""

    passed: bool
    message: str

    def __bool__(self) -> bool:
        return self.passed

    def __str__(self) -> str:
        return ("Correct! " if self.passed else "Not yet. ") + self.message

    def _repr_markdown_(self) -> str:
        return ("**Correct!** " if self.passed else "**Not yet.** ") + self.message


def check_close(quantity: str, answer, expected: float, rtol: float, unit: str = "",
                hint: str = "") -> Feedback:
    """Feedback on a numerical answer that must match ``expected`` within ``rtol`` (relative).

    Parameters
    ----------
    quantity : str
        What the answer is, for the message (e.g. ``"thickness"``).
    answer : float
        The student's value.
    expected : float
        The model's value.
    rtol : float
        Accepted relative error.
    unit : str
        Unit shown in the message.
    hint : str
        Added to the message when the answer is off.
    """
    try:
        value = float(answer)
    except (TypeError, ValueError):
        return Feedback(False, f"{quantity} must be a number, got {answer!r}.")
    if not math.isfinite(value):
        return Feedback(False, f"{quantity} must be finite, got {value!r}.")
    err = abs(value - expected) / abs(expected) if expected else abs(value)
    u = f" {unit}" if unit else ""
    if err <= rtol:
        return Feedback(True, f"{quantity} = {value:.4g}{u} (model: {expected:.4g}{u}).")
    return Feedback(False, f"{quantity} = {value:.4g}{u} is off by {100 * err:.1f}% "
                           f"(needs to be within {100 * rtol:g}%). {hint}".strip())
