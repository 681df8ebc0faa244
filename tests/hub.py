"""A local JupyterHub and its simulated students: a class on one machine, on 127.0.0.1 only.

A driver library (not a test file) shared by ``tests/test_hub_browser.py`` (two students) and
``benchmarks/bench_hub.py`` (1, 4 and 8 students). :class:`Hub` runs JupyterHub from PyPI with
configurable-http-proxy from the npm registry (``make hub-proxy`` puts it in ``.hub/``), every
port on 127.0.0.1, system users ``course-student-N`` (created with ``useradd``, homes 0700)
logging in through JupyterHub's dummy authenticator restricted to them, and the local-process
spawner starting each student's JupyterLab as that user. The course reaches each home as in a
class: the student follows an nbgitpuller link (here to a bare clone of this checkout, on a
``file://`` address) that clones the course into ``~/course`` and opens a module.

:func:`class_session` drives the students in one headless Chromium (Debian's; a browser context
each, so each has its own login): all log in at once, open the module, Run All, and then press
their panel's slider together; per student it returns the time from the login to the first
figure drawn, the key-to-pixels time of each press (timed in the page as
``tests/browser.py`` times a press), the memory of the student's processes and whether the
student's kernel still answers at the end. Every wait is bounded; the hub and everything it
started are stopped in ``Hub.stop`` (called from ``finally``).
"""
from __future__ import annotations

import contextlib
import json
import os
import pwd
import random
import shutil
import signal
import stat
import subprocess
import sys
import tempfile
import time
import urllib.parse
import urllib.request
from dataclasses import dataclass, field
from pathlib import Path

from tests import browser as B

ROOT = B.ROOT
CHP = ROOT / ".hub" / "node_modules" / ".bin" / "configurable-http-proxy"
STUDENT = "course-student-{}"
PASSWORD = "afm-class-password"  # the dummy authenticator's one password (127.0.0.1 only)
NOTEBOOK = "04_contact_mechanics.ipynb"  # the module the students open
PANEL = "contact"  # its panel in the registry (afmsmiler.ui.registry)
COURSE = "course"  # the folder nbgitpuller clones the course into, in each home
MAX_STUDENTS = 16  # a bound on the class size these helpers accept


def unavailable() -> str | None:
    """Why a local hub cannot run here, or None when it can."""
    if not hasattr(os, "geteuid") or os.geteuid() != 0:
        return "not root: the hub test creates system users (useradd) and spawns as them"
    if shutil.which("useradd") is None:
        return "no useradd on this machine"
    if shutil.which("git") is None:
        return "no git: nbgitpuller needs it"
    try:
        import jupyterhub  # noqa: F401
        import nbgitpuller  # noqa: F401
    except ImportError:
        return "jupyterhub or nbgitpuller is not installed (pip install -e '.[hub]')"
    if student_python() is None:
        return (f"the students cannot run {sys.executable} (under a folder only root may "
                f"enter) and the system has no python3 {sys.version_info[0]}."
                f"{sys.version_info[1]}")
    if not os.access(CHP, os.X_OK):
        return f"no {CHP}: `make hub-proxy` installs configurable-http-proxy from npm"
    return B.unavailable()


def _others_can_run(path: Path) -> bool:
    """Whether a user other than its owner can execute ``path`` (every folder above it
    searchable by others, the file executable by others)."""
    path = Path(path).resolve()
    try:
        if not os.stat(path).st_mode & stat.S_IXOTH:
            return False
        return all(os.stat(d).st_mode & stat.S_IXOTH for d in path.parents)
    except OSError:
        return False


def student_python() -> tuple[str, list[str]] | None:
    """The interpreter the students' servers run, and the folders to put on their
    ``PYTHONPATH``: this one when other users can run it, else the system's ``python3`` of the
    same version with this environment's packages (a Python built under root's home, 0700, is
    out of their reach); None when neither will do."""
    site = [p for p in sys.path if p.endswith("site-packages") and Path(p).is_dir()]
    if _others_can_run(Path(sys.executable)):
        return sys.executable, []
    system = shutil.which("python3", path="/usr/local/bin:/usr/bin:/bin")
    if system and _others_can_run(Path(system)):
        out = subprocess.run([system, "-c", "import sys; print(sys.version_info[:2])"],
                             capture_output=True, text=True, timeout=30)
        if out.stdout.strip() == str(tuple(sys.version_info[:2])):
            return system, site
    return None


def students(n: int) -> list[str]:
    """Make sure system users ``course-student-1..n`` exist with homes only they can read.

    Each home is mode 0700 and starts without the course (nbgitpuller clones it afresh) and
    with JupyterLab settings that keep news and update checks off (no request leaves
    127.0.0.1) and every cell in the page (the browser helpers read the cells' prompts).
    """
    if not isinstance(n, int) or not 1 <= n <= MAX_STUDENTS:
        raise ValueError(f"n must be an int in 1..{MAX_STUDENTS}, got {n!r}")
    names = [STUDENT.format(i) for i in range(1, n + 1)]
    for name in names:
        try:
            pwd.getpwnam(name)
        except KeyError:
            subprocess.run(["useradd", "--create-home", "--shell", "/bin/bash", name],
                           check=True, timeout=30)
        user = pwd.getpwnam(name)
        home = Path(user.pw_dir)
        home.mkdir(exist_ok=True)
        os.chown(home, user.pw_uid, user.pw_gid)
        home.chmod(0o700)
        shutil.rmtree(home / COURSE, ignore_errors=True)
        for ext, setting, values in (
                ("@jupyterlab/notebook-extension", "tracker", {"windowingMode": "none"}),
                ("@jupyterlab/apputils-extension", "notification",
                 {"fetchNews": "false", "checkForUpdates": False})):
            d = home / ".jupyter" / "lab" / "user-settings" / ext
            d.mkdir(parents=True, exist_ok=True)
            (d / f"{setting}.jupyterlab-settings").write_text(json.dumps(values))
        for dirpath, dirnames, filenames in os.walk(home / ".jupyter"):
            for entry in [dirpath] + [os.path.join(dirpath, f) for f in filenames]:
                os.chown(entry, user.pw_uid, user.pw_gid)
    return names


def home_mode(name: str) -> int:
    """The permission bits of a user's home directory."""
    return stat.S_IMODE(os.stat(pwd.getpwnam(name).pw_dir).st_mode)


def _head() -> str:
    """The commit checked out here (CI may check out a commit, not a branch)."""
    out = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "HEAD"],
                         capture_output=True, text=True, timeout=30, check=True)
    return out.stdout.strip()


class Hub:
    """JupyterHub on 127.0.0.1 for the users ``names``, with the course in a bare git clone.

    Parameters
    ----------
    names : list of str
        The students (system users, :func:`students`).
    short : bool
        Kernels with ``AFMSMILER_TESTING=1`` (shortened animations).
    startup_timeout : float
        Seconds to wait for the hub to answer.
    """

    def __init__(self, names, *, short: bool = False, startup_timeout: float = 90.0):
        self.names = list(names)
        self.short = short
        self.startup_timeout = startup_timeout
        self.dir = Path(tempfile.mkdtemp(prefix="afm-hub-"))
        self.dir.chmod(0o755)  # the students read the course's clone and git's settings here
        self.secret = self.dir / "secret"  # the hub's database and cookie secret: root's only
        self.secret.mkdir(mode=0o700)
        self.port, self.hub_port, self.api_port = B.free_port(), B.free_port(), B.free_port()
        self.proc = None
        self.log = self.dir / "hub.log"
        self.repo = self.dir / "course.git"

    @property
    def base(self) -> str:
        return f"http://127.0.0.1:{self.port}"

    def pull_url(self, notebook: str = NOTEBOOK) -> str:
        """The nbgitpuller link an instructor hands out: clone the course, open ``notebook``."""
        query = urllib.parse.urlencode({
            "repo": self.repo.as_uri(), "branch": self.branch, "targetpath": COURSE,
            "urlpath": f"lab/tree/{COURSE}/notebooks/{notebook}"})
        return f"/hub/user-redirect/git-pull?{query}"

    def login_url(self, notebook: str = NOTEBOOK) -> str:
        return f"{self.base}/hub/login?" + urllib.parse.urlencode(
            {"next": self.pull_url(notebook)})

    def _config(self) -> Path:
        python, site = student_python()
        gitconfig = self.dir / "gitconfig"
        # the clone belongs to root: git refuses another user's repository unless told it is safe
        gitconfig.write_text("[safe]\n\tdirectory = *\n")
        gitconfig.chmod(0o644)
        env = {"PATH": "/usr/local/bin:/usr/bin:/bin",
               "PYTHONPATH": os.pathsep.join([str(ROOT)] + site),
               # this environment's Jupyter files: server extensions (nbgitpuller), the
               # widgets' JupyterLab extensions, the kernel's spec
               "JUPYTER_CONFIG_PATH": str(Path(sys.prefix) / "etc" / "jupyter"),
               "JUPYTER_PATH": str(Path(sys.prefix) / "share" / "jupyter"),
               "GIT_CONFIG_GLOBAL": str(gitconfig), "LANG": "C.UTF-8"}
        if self.short:
            env["AFMSMILER_TESTING"] = "1"
        config = {
            "bind_url": f"http://127.0.0.1:{self.port}",
            "hub_bind_url": f"http://127.0.0.1:{self.hub_port}",
            "api_url": f"http://127.0.0.1:{self.api_port}",
            "chp": str(CHP), "db": f"sqlite:///{self.secret / 'jupyterhub.sqlite'}",
            "cookie": str(self.secret / "cookie_secret"), "pid": str(self.secret / "proxy.pid"),
            "users": self.names, "password": PASSWORD, "env": env,
            "singleuser": [python, "-m", "jupyterhub.singleuser"], "nodelay": B.SERVER_OPTION,
        }
        path = self.secret / "jupyterhub_config.py"
        path.write_text(
            "import json\n"
            f"k = json.loads({json.dumps(json.dumps(config))})\n"
            "c.JupyterHub.bind_url = k['bind_url']\n"
            "c.JupyterHub.hub_bind_url = k['hub_bind_url']\n"
            "c.ConfigurableHTTPProxy.api_url = k['api_url']\n"
            "c.ConfigurableHTTPProxy.command = [k['chp']]\n"
            "c.ConfigurableHTTPProxy.pid_file = k['pid']\n"
            "c.JupyterHub.db_url = k['db']\n"
            "c.JupyterHub.cookie_secret_file = k['cookie']\n"
            "c.JupyterHub.cleanup_servers = True\n"
            "c.JupyterHub.authenticator_class = 'dummy'\n"
            "c.DummyAuthenticator.password = k['password']\n"
            "c.Authenticator.allowed_users = set(k['users'])\n"
            "c.JupyterHub.spawner_class = 'localprocess'\n"
            "c.Spawner.cmd = k['singleuser']\n"
            "c.Spawner.args = ['--LabApp.expose_app_in_browser=True', k['nodelay']]\n"
            "c.Spawner.default_url = '/lab'\n"
            "c.Spawner.ip = '127.0.0.1'\n"
            "c.Spawner.environment = k['env']\n"
            "c.Spawner.start_timeout = 300\n"
            "c.Spawner.http_timeout = 300\n")
        return path

    def start(self) -> "Hub":
        # the course as an instructor publishes it: a repository whose branch is this commit
        self.branch = "course"
        subprocess.run(["git", "clone", "--quiet", "--bare", str(ROOT), str(self.repo)],
                       check=True, timeout=120, capture_output=True)
        subprocess.run(["git", "-C", str(self.repo), "branch", "--force", self.branch, _head()],
                       check=True, timeout=30, capture_output=True)
        for dirpath, _, _ in os.walk(self.repo):
            os.chmod(dirpath, 0o755)
        subprocess.run(["chmod", "-R", "a+rX", str(self.repo)], check=True, timeout=60)
        config = self._config()
        cmd = [str(Path(sys.executable).parent / "jupyterhub"), "-f", str(config)]
        env = dict(os.environ)
        for name in ("MPLBACKEND", "AFMSMILER_TESTING", "CI", "NBVAL", "PYTEST_CURRENT_TEST"):
            env.pop(name, None)
        with open(self.log, "wb") as log:
            self.proc = subprocess.Popen(cmd, cwd=self.secret, env=env, stdout=log,
                                         stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                                         start_new_session=True)
        deadline = time.monotonic() + self.startup_timeout
        while time.monotonic() < deadline:
            if self.proc.poll() is not None:
                raise RuntimeError(f"jupyterhub exited ({self.proc.returncode}): {self.tail()}")
            try:
                urllib.request.urlopen(f"{self.base}/hub/api", timeout=2).read(1)
                return self
            except Exception:  # not up yet
                time.sleep(0.3)
        tail = self.tail()  # before stop(), which removes the log with the hub's folder
        self.stop()
        raise RuntimeError(f"jupyterhub did not answer within {self.startup_timeout:g} s: "
                           f"{tail}")

    def tail(self, n: int = 3000) -> str:
        try:
            return self.log.read_text(errors="replace")[-n:]
        except OSError:
            return ""

    def processes(self, name: str) -> list:
        """The processes running as student ``name`` (their JupyterLab, kernels, children)."""
        import psutil
        uid = pwd.getpwnam(name).pw_uid
        out = []
        for p in psutil.process_iter(["uids"]):
            with contextlib.suppress(psutil.Error):
                if p.info["uids"] and p.info["uids"].real == uid:
                    out.append(p)
        return out

    def memory(self, name: str) -> dict:
        """Student ``name``'s processes' memory, MiB: ``rss`` (resident) and ``uss`` (their own
        pages, what one more student adds)."""
        import psutil
        rss = uss = 0
        for p in self.processes(name):
            with contextlib.suppress(psutil.Error):
                m = p.memory_full_info()
                rss += m.rss
                uss += m.uss
        return {"rss": rss / 2**20, "uss": uss / 2**20}

    def listening(self) -> list:
        """Every listening TCP socket of the hub, its proxy and the students' processes, as
        ``(process name, address, port)``."""
        import psutil
        procs = []
        with contextlib.suppress(psutil.Error):
            hub = psutil.Process(self.proc.pid)
            procs = [hub] + hub.children(recursive=True)
        for name in self.names:
            procs += self.processes(name)
        out = []
        for p in procs:
            with contextlib.suppress(psutil.Error):
                for c in p.net_connections("inet"):
                    if c.status == psutil.CONN_LISTEN:
                        out.append((p.name(), c.laddr.ip, c.laddr.port))
        return out

    def stop(self) -> None:
        """Stop the hub (it stops the students' servers), then anything left of them, bounded."""
        if self.proc is not None:
            for sig, wait in ((signal.SIGTERM, 20.0), (signal.SIGKILL, 5.0)):
                if self.proc.poll() is None:
                    with contextlib.suppress(ProcessLookupError, PermissionError):
                        os.killpg(self.proc.pid, sig)
                    with contextlib.suppress(subprocess.TimeoutExpired):
                        self.proc.wait(timeout=wait)
            self.proc = None
        for name in self.names:  # a server the hub could not stop: ended by its pid
            for p in self.processes(name):
                with contextlib.suppress(Exception):
                    p.kill()
        shutil.rmtree(self.dir, ignore_errors=True)

    def __enter__(self):
        return self.start()

    def __exit__(self, *exc):
        self.stop()


# -- the students in the browser --------------------------------------------------------------
_FIRST_FIGURE_JS = r"""
(() => {
  if (window.__afmFirst) return;
  window.__afmFirst = {at: null};
  const look = () => {
    if (window.__afmFirst.at !== null || !window.__afm) return;
    for (const f of document.querySelectorAll('.afm-live')) {
      if (window.__afm.checksum(f, '.afm-live').lit > 0) { window.__afmFirst.at = Date.now(); return; }
    }
  };
  setInterval(look, 50);
})();
"""

_READY_JS = """(path) => { const a = window.jupyterapp; if (!a) return false;
    const w = a.shell.currentWidget;
    return !!(w && w.content && w.context && w.context.path.endsWith(path)
              && w.sessionContext && w.sessionContext.session
              && w.sessionContext.session.kernel
              && w.sessionContext.session.kernel.status === 'idle'); }"""

_DONE_JS = B.RUN_ALL_DONE_JS  # the same end of Run All as tests/browser.run_all waits for


@dataclass
class Student:
    """One simulated student: what the class session measured for them."""

    name: str
    login_at: float = 0.0  # time.time() when they pressed "Sign in"
    first_figure_s: float | None = None  # login to the first figure's pixels
    presses: list = field(default_factory=list)  # key-to-pixels per press (None: no change), s
    #: the same with each student pressing at their own moment of each round (``spread``)
    spread_presses: list = field(default_factory=list)
    memory: dict = field(default_factory=dict)  # MiB, after Run All (Hub.memory)
    errors: list = field(default_factory=list)  # error outputs after Run All and the presses
    foreign: list = field(default_factory=list)  # addresses asked for beyond 127.0.0.1
    kernel_alive: bool = False  # the kernel answered at the end
    page: object = None
    asked: list = field(default_factory=list)


_FAILED_JS = """() => /Spawn failed|500 : Internal Server Error|403 : Forbidden|404 : Not Found/
                      .test(document.body ? document.body.innerText : '')"""


def _poll_all(pages, predicate, *, arg=None, timeout: float, what: str, hub=None) -> None:
    """Wait (bounded) until ``predicate`` holds on every page, polling each in turn; a page
    showing the hub's error page fails at once, with the hub's log."""
    left = dict(enumerate(pages))
    deadline = time.monotonic() + timeout
    while left:
        for i, page in list(left.items()):
            failed = False
            with contextlib.suppress(Exception):  # a page between navigations
                if page.evaluate(predicate, arg) if arg is not None else page.evaluate(predicate):
                    del left[i]
                    continue
                failed = page.evaluate(_FAILED_JS)
            if failed:
                raise RuntimeError(f"{what}: the hub shows an error at {page.url}: "
                                       f"{page.inner_text('body')[:500]}\n"
                                       f"{hub.tail() if hub else ''}")
        if not left:
            return
        if time.monotonic() > deadline:
            raise AssertionError(f"{what}: {len(left)} of {len(pages)} students still waiting "
                                 f"after {timeout:g} s")
        time.sleep(0.25)


def class_session(chromium, hub: Hub, *, presses: int = 3, timeout: float = 900.0,
                  readable_by_others: bool = True, spread: float | None = None,
                  seed: int = 22) -> list[Student]:
    """Every student of ``hub`` logs in at once, opens the module through the nbgitpuller link,
    runs all its cells and presses the panel's slider ``presses`` times, together (and, with
    ``spread``, ``presses`` times more, each at their own moment).

    Parameters
    ----------
    chromium : playwright Browser
        One headless Chromium (a context per student).
    hub : Hub
        A started hub.
    presses : int
        Key presses of each student's slider (all students press at once, each round).
    timeout : float
        The bound of each phase (log in and open, Run All), s.
    readable_by_others : bool
        Also try, from the first student's kernel, to read the second student's notebook (the
        result is in the first student's ``errors`` if it could be read).
    spread : float or None
        After the rounds together, ``presses`` rounds in which each student presses at a moment
        drawn uniformly within ``spread`` s (a class, whose students do not press in the same
        millisecond), recorded in ``Student.spread_presses``; None: none. 0 < spread <= 10.
    seed : int
        The random moments' seed (the same moments run after run).

    Returns
    -------
    list of Student
    """
    if not 1 <= presses <= 50:
        raise ValueError(f"presses must be in 1..50, got {presses!r}")
    if spread is not None and not 0 < spread <= 10:
        raise ValueError(f"spread must be None or in (0, 10] s, got {spread!r}")
    entry = B.PANELS[PANEL]
    selector = f"{entry.selector} {B.LIVE_FIGURE}"
    out = []
    contexts = []
    try:
        for name in hub.names:
            ctx = chromium.new_context(viewport=B.VIEWPORT)
            contexts.append(ctx)
            page = ctx.new_page()
            page.add_init_script(B._PAGE_JS)
            page.add_init_script(_FIRST_FIGURE_JS)
            page.set_default_timeout(60_000)
            s = Student(name, page=page, asked=B.watch_requests(page))
            page.goto(hub.login_url(), wait_until="domcontentloaded")
            page.fill("#username_input", name)
            page.fill("#password_input", PASSWORD)
            out.append(s)
        for s in out:  # all at once: the spawns overlap
            s.login_at = time.time()
            s.page.click("#login_submit", no_wait_after=True)
        pages = [s.page for s in out]
        _poll_all(pages, _READY_JS, arg=NOTEBOOK, timeout=timeout, what="open the module",
                  hub=hub)
        for page in pages:
            page.evaluate("() => { window.jupyterapp.commands.execute("
                          "'notebook:run-all-cells'); return true; }")
        _poll_all(pages, _DONE_JS, timeout=timeout, what="Run All")
        _poll_all(pages, "() => window.__afmFirst && window.__afmFirst.at !== null",
                  timeout=60, what="the first figure")
        for s in out:
            s.first_figure_s = s.page.evaluate("() => window.__afmFirst.at") / 1000 - s.login_at
            s.errors = B.lab_errors(s.page)
            s.memory = hub.memory(s.name)
        # the slider, pressed by every student at once, round by round
        sliders = []
        for s in out:
            slider = B.find_control(s.page, entry)
            B.focus_panel(s.page, slider, selector)
            sliders.append((slider, B.keys(slider)[0]))
        rng = random.Random(seed)
        rounds = [None] * presses + ([spread] * presses if spread is not None else [])
        for within in rounds:
            for s in out:
                s.page.evaluate("([sel, mode, ms]) => window.__afm.arm(sel, mode, ms)",
                                [selector, "pixels", B.PRESS_TIMEOUT * 1000])
            # together: one after the other as fast as Playwright sends keys (a few ms apart);
            # spread: each at its own moment of the round, in the order of those moments
            at = [0.0] * len(out) if within is None else [rng.uniform(0, within) for _ in out]
            start = time.monotonic()
            for i in sorted(range(len(out)), key=at.__getitem__):
                time.sleep(max(0.0, start + at[i] - time.monotonic()))
                slider, key = sliders[i]
                slider.press(key)
            for s in out:
                r = s.page.evaluate("() => window.__afm.current.promise")
                dt = None if r.get("dt") is None else r["dt"] / 1000.0
                (s.presses if within is None else s.spread_presses).append(dt)
            for s in out:
                B.settle(s.page, selector, quiet=0.3, timeout=B.PRESS_TIMEOUT)
        if readable_by_others and len(out) >= 2:
            other = Path(pwd.getpwnam(out[1].name).pw_dir) / COURSE / "notebooks" / NOTEBOOK
            code = ("try:\n    open(%r).read(1)\n    print('READ')\n"
                    "except PermissionError:\n    print('DENIED')\n" % str(other))
            if B.kernel_eval(out[0].page, code).strip() != "DENIED":
                out[0].errors.append(f"{out[0].name} could read {other}")
        for s in out:
            s.kernel_alive = B.kernel_eval(s.page, "print(6 * 7)").strip() == "42"
            s.errors += B.lab_errors(s.page)
            s.foreign = B.foreign(s.asked)
    finally:
        for ctx in contexts:
            with contextlib.suppress(Exception):
                ctx.close()
    return out
