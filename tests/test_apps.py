"""The web apps' pieces without a browser (afmsmiler.apps): which notebook a name means, the
course's voila template (voila's own without the addresses of other hosts), the command line
(127.0.0.1 only). ``tests/test_apps_browser.py`` serves them in Chromium."""
import re

import pytest

from afmsmiler import apps
from afmsmiler.ui.registry import MODULES

REMOTE = re.compile(r"""(href|src)\s*=\s*["'](https?:)?//""", re.IGNORECASE)


@pytest.mark.parametrize("name", ["06_virtual_imaging", "06_virtual_imaging.ipynb", "f"])
def test_a_module_is_named_by_its_notebook_or_its_letter(name):
    path = apps.notebook_path(name)
    assert path.name == MODULES["f"][0] and path.is_file()


@pytest.mark.parametrize("bad", ["09_nothing", "z", ""])
def test_an_unknown_module_is_refused_naming_the_argument(bad):
    with pytest.raises(ValueError, match="name"):
        apps.notebook_path(bad)


def test_the_template_is_voilas_without_other_hosts(tmp_path):
    installed = apps._installed_templates()
    # what there is to take out: voila's lab page links Font Awesome on a CDN (if a voila
    # release drops it, this test says the filter has nothing left to do)
    assert REMOTE.search((installed / "lab" / "index.html.j2").read_text())
    root = apps.write_template(tmp_path)
    written = list((root / "voila" / "templates").rglob("*.htm*")) + \
        list((root / "voila" / "templates").rglob("*.j2"))
    assert any(p.name == "index.html.j2" for p in written)
    for path in written:
        for tag in re.findall(r"<(?:link|script)\b[^>]*>", path.read_text()):
            assert not REMOTE.search(tag), f"{path.name} still links {tag}"
    # the rest is voila's own: every other line of its lab page is kept
    ours = (root / "voila" / "templates" / apps.TEMPLATE / "index.html.j2").read_text()
    theirs = (installed / "lab" / "index.html.j2").read_text()
    kept = [line for line in theirs.splitlines() if not REMOTE.search(line)]
    assert all(line in ours for line in kept)
    assert "html_head_js_mermaidjs" in ours  # nbconvert's CDN import of Mermaid emptied


def test_the_command_serves_on_127_0_0_1_with_the_course_template():
    cmd = apps.voila_command(apps.NOTEBOOKS, port=8899, token="t")
    assert "--Voila.ip=127.0.0.1" in cmd and "--port=8899" in cmd
    assert f"--template={apps.TEMPLATE}" in cmd and "--token=t" in cmd
    assert cmd[-1] == str(apps.NOTEBOOKS)
    with pytest.raises(ValueError, match="port"):
        apps.voila_command(apps.NOTEBOOKS, port=70000)
