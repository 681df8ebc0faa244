"""afmsmiler._steps: a model's steps run whole, within their bound."""
import pytest

from afmsmiler._steps import run_steps


def _count_to(n):
    for i in range(n):
        yield i
    return "done"


def test_steps_run_to_their_end_return_their_result():
    assert run_steps(_count_to(3), 4, "count") == "done"  # three yields, the fourth call ends


def test_steps_that_take_more_than_their_bound_are_named():
    with pytest.raises(RuntimeError, match="count took more than 3 steps"):
        run_steps(_count_to(3), 3, "count")
