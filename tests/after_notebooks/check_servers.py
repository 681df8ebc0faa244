"""Run by `make test` after nbval: no meshcat server started by a notebook kernel may survive it.

nbval kills kernels hard, so meshcat's exit handler never runs; notebooks close the viewer in
their last cell and the server also dies with its kernel (PR_SET_PDEATHSIG). Every server that
afmsmiler starts carries AFMSMILER_MESHCAT_OWNER=<kernel pid>; an orphan is a leak.
"""
import psutil

from afmsmiler.scenes.viewer import OWNER_ENV


def _afmsmiler_servers():
    for proc in psutil.process_iter(["pid", "cmdline"]):
        try:
            if "afmsmiler.scenes._server" in " ".join(proc.info["cmdline"] or []):
                owner = proc.environ().get(OWNER_ENV)
                if proc.status() != psutil.STATUS_ZOMBIE:
                    yield proc, owner
        except (psutil.NoSuchProcess, psutil.AccessDenied):
            continue


def orphaned_servers():
    """(pid, owner pid) of every afmsmiler meshcat server whose owning kernel is gone."""
    return [(p.pid, owner) for p, owner in _afmsmiler_servers()
            if owner is None or not psutil.pid_exists(int(owner))]


def test_no_meshcat_server_outlives_its_kernel():
    orphans = orphaned_servers()
    assert not orphans, f"meshcat servers left behind by dead kernels (pid, owner): {orphans}"
