"""pytest plugin for ``make test``'s doctest run: a docstring example may not start a 3D server.

Loaded with ``-p tests.doctest_no_viewer`` when pytest collects ``--doctest-modules afmsmiler``.
Collecting the docstrings imports every module of the package (the scene modules too); an example
that asked for the kernel's meshcat viewer would start a server process that outlives the run.
Here starting one raises instead, so such an example fails by name rather than leaking a server.
Examples that need a shipped file read it through :func:`afmsmiler.data.path`, which needs no
set-up.
"""
import pytest


def _refuse(*_args, **_kwargs):
    raise RuntimeError("a docstring example may not start a meshcat server (use a Recorder "
                       "from tests/recording.py in tests, or show the call without running it)")


@pytest.fixture(autouse=True)
def _no_meshcat_server(monkeypatch):
    """Every doctest runs with the viewer's server start replaced by an error."""
    from afmsmiler.scenes import viewer
    monkeypatch.setattr(viewer, "_start_server", _refuse)
    yield
