"""The course's modules as web apps: each notebook rendered by voila, on 127.0.0.1 only.

An app is the module's notebook itself, run and rendered by `voila <https://voila.readthedocs.io>`_
(every cell runs when the page is asked for, the code is hidden, the widgets, live figures and 3D
views stay live over the kernel's connection): no notebook code is copied anywhere. ::

    python -m afmsmiler.apps 06_virtual_imaging    # one module (make app NB=06_virtual_imaging)
    python -m afmsmiler.apps                       # the index of every module (make apps)

voila's own page templates ask a CDN for Font Awesome's style sheets on every page; a student
offline (or a class whose network only reaches its hub) would wait for them, and the course's
pages must ask for nothing beyond their own server. :func:`write_template` writes the course's
template, voila's installed ``lab`` template with every link to another host taken out, and
:func:`voila_command` serves with it. ``tests/test_apps_browser.py`` checks in Chromium that the
pages ask for nothing but 127.0.0.1.
"""
from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
from pathlib import Path

from .serving import VOILA_OPTION
from .ui.registry import MODULES
from .validation import check_choice

__all__ = ["NOTEBOOKS", "TEMPLATE", "notebook_path", "write_template", "voila_command"]

#: The course's notebooks (a checkout's ``notebooks/``: they are not part of the wheel).
NOTEBOOKS = Path(__file__).resolve().parents[1] / "notebooks"
#: The name of the course's voila template.
TEMPLATE = "afmsmiler"

# a <link> or <script> whose address is on another host (http://, https:// or //host)
_REMOTE = re.compile(r"""<(link|script)\b[^>]*\b(href|src)\s*=\s*["'](https?:)?//[^"']*["']"""
                     r"""[^>]*>(\s*</script>)?""", re.IGNORECASE)


def notebook_path(name: str) -> Path:
    """The notebook of a module, by its name (``"06_virtual_imaging"``, with or without
    ``.ipynb``) or its letter (``"f"``).

    Parameters
    ----------
    name : str
        A notebook's name or a module's letter (:data:`afmsmiler.ui.registry.MODULES`).

    Returns
    -------
    pathlib.Path
        The notebook in the checkout's ``notebooks/`` folder.

    Raises
    ------
    ValueError
        For a name that is no module's, listing the valid ones.
    """
    if not isinstance(name, str):
        raise TypeError(f"name must be a str, got {type(name).__name__}")
    stems = {nb[:-len(".ipynb")]: nb for nb, _ in MODULES.values()}
    if name in MODULES:
        return NOTEBOOKS / MODULES[name][0]
    stem = name[:-len(".ipynb")] if name.endswith(".ipynb") else name
    check_choice("name", stem, sorted(stems) + sorted(MODULES))
    return NOTEBOOKS / stems[stem]


def _installed_templates() -> Path:
    """voila's installed ``templates`` folder (the one that holds ``lab`` and ``base``)."""
    from jupyter_core.paths import jupyter_path
    for d in jupyter_path("voila", "templates"):
        if (Path(d) / "lab" / "index.html.j2").is_file() and (Path(d) / "base").is_dir():
            return Path(d)
    raise FileNotFoundError("voila's lab template was not found: install voila "
                            "(pip install -e '.[lab]')")


_NO_MERMAID = ("\n{%- block html_head_js_mermaidjs -%}\n"
               "{# afmsmiler: no Mermaid from a CDN #}\n"
               "{%- endblock html_head_js_mermaidjs -%}\n")


def _local(text: str) -> str:
    return _REMOTE.sub("", text)


def write_template(directory) -> Path:
    """Write the course's voila template under ``directory`` and return ``directory``.

    The template (``<directory>/voila/templates/afmsmiler``, based on ``lab``) is voila's
    installed ``lab`` template with every ``<link>`` and ``<script>`` to another host taken out
    (and nbconvert's Mermaid loader, which imports from a CDN, emptied), and
    ``<directory>/voila/templates/base/page.html`` is voila's base page (which the lab template's
    pages extend by that path) likewise. Put ``directory`` first on ``JUPYTER_PATH`` and pass
    ``--template=afmsmiler`` (:func:`voila_command` does both).

    Parameters
    ----------
    directory : str or os.PathLike
        An existing, writable folder (a temporary one).

    Returns
    -------
    pathlib.Path
        ``directory``, the root to put on ``JUPYTER_PATH``.

    Raises
    ------
    ValueError
        When ``directory`` is not an existing folder.
    FileNotFoundError
        When voila is not installed.
    """
    if not isinstance(directory, (str, os.PathLike)) or not Path(directory).is_dir():
        raise ValueError(f"directory must be an existing folder, got {directory!r}")
    root = Path(directory)
    installed = _installed_templates()
    out = root / "voila" / "templates" / TEMPLATE
    if out.exists():
        shutil.rmtree(out)
    shutil.copytree(installed / "lab", out)
    for path in list(out.rglob("*.html")) + list(out.rglob("*.j2")):
        path.write_text(_local(path.read_text(encoding="utf-8")), encoding="utf-8")
    # nbconvert's lab template imports Mermaid from a CDN where a notebook draws a Mermaid
    # diagram (the course's draw none): the block goes
    index = out / "index.html.j2"
    index.write_text(index.read_text(encoding="utf-8") + _NO_MERMAID, encoding="utf-8")
    # the rest of the hierarchy is lab's (voila's and nbconvert's templates of that name)
    (out / "conf.json").write_text(json.dumps({"base_template": "lab"}), encoding="utf-8")
    base = root / "voila" / "templates" / "base"
    base.mkdir(parents=True, exist_ok=True)
    page = (installed / "base" / "page.html").read_text(encoding="utf-8")
    (base / "page.html").write_text(_local(page), encoding="utf-8")
    return root


def voila_command(target, *, port: int = 8866, open_browser: bool = False,
                  token: str | None = None) -> list[str]:
    """The voila command line that serves ``target`` on 127.0.0.1 with the course's template.

    Parameters
    ----------
    target : str or os.PathLike
        A notebook (one app) or a folder of notebooks (the index: voila's list of the folder's
        notebooks, each a link to its app).
    port : int
        The port, 1-65535 (0: voila picks one).
    open_browser : bool
        Whether voila opens a browser.
    token : str, optional
        A token the pages must carry (``?token=``); none by default.

    Returns
    -------
    list of str
        The arguments, for :func:`subprocess.run` with ``JUPYTER_PATH`` starting at the folder
        of :func:`write_template`.

    Raises
    ------
    ValueError
        For a port out of range, a target that does not exist or a token with spaces.
    TypeError
        For an ``open_browser`` that is not a bool.
    """
    if not isinstance(port, int) or isinstance(port, bool) or not 0 <= port <= 65535:
        raise ValueError(f"port must be an int in 0..65535, got {port!r}")
    if not isinstance(target, (str, os.PathLike)) or not Path(target).exists():
        raise ValueError(f"target must be an existing notebook or folder, got {target!r}")
    if not isinstance(open_browser, bool):
        raise TypeError(f"open_browser must be a bool, got {open_browser!r}")
    if token is not None and (not isinstance(token, str) or not token.isprintable()
                              or " " in token):
        raise ValueError(f"token must be None or a printable str without spaces, got {token!r}")
    voila = Path(sys.executable).parent / "voila"
    cmd = [str(voila) if voila.exists() else (shutil.which("voila") or "voila"),
           "--Voila.ip=127.0.0.1", f"--port={port}", f"--template={TEMPLATE}",
           "--VoilaConfiguration.classic_tree=True", VOILA_OPTION,
           "--Voila.open_browser=" + ("True" if open_browser else "False")]
    if token is not None:
        cmd.append(f"--token={token}")
    cmd.append(str(target))
    return cmd


def main(argv=None) -> int:
    """Serve one module's app, or the index of every module, until interrupted.

    Parameters
    ----------
    argv : list of str, optional
        ``[NOTEBOOK] [--port N] [--browser]``; the command line by default.

    Returns
    -------
    int
        voila's exit status.
    """
    parser = argparse.ArgumentParser(prog="python -m afmsmiler.apps", description=__doc__.split(
        "\n\n")[0])
    parser.add_argument("notebook", nargs="?", default=None,
                        help="a module's notebook (06_virtual_imaging) or letter (f); "
                             "none: the index of every module")
    parser.add_argument("--port", type=int, default=8866)
    parser.add_argument("--browser", action="store_true", help="open a browser")
    args = parser.parse_args(argv)
    target = NOTEBOOKS if args.notebook is None else notebook_path(args.notebook)
    with tempfile.TemporaryDirectory(prefix="afmsmiler-voila-") as tmp:
        write_template(tmp)
        env = dict(os.environ)
        env["JUPYTER_PATH"] = os.pathsep.join([tmp] + ([env["JUPYTER_PATH"]]
                                                       if env.get("JUPYTER_PATH") else []))
        env.pop("MPLBACKEND", None)  # the kernels draw for the browser, not to files
        cmd = voila_command(target, port=args.port, open_browser=args.browser)
        proc = subprocess.Popen(cmd, env=env, cwd=NOTEBOOKS)

        def stop(signum, frame):  # a stop of this process stops voila (and its kernels)
            proc.terminate()

        for signum in (signal.SIGTERM, signal.SIGHUP):
            signal.signal(signum, stop)
        try:
            return proc.wait()
        except KeyboardInterrupt:
            proc.terminate()
            return proc.wait(timeout=30)


if __name__ == "__main__":
    sys.exit(main())
