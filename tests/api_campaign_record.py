"""Regenerate tests/api_campaign_known.py from a run of the bad-input campaign.

    python tests/api_campaign_record.py          # every case, slow ones too (about a minute)

Runs tests/test_api_campaign.py with the known failures switched off
(``AFMSMILER_CAMPAIGN_RECORD=1``), and writes every failing case with its calls as a strict
xfail. Read the diff before committing it: an entry that disappears was fixed, a new one is a
new failure (fix it rather than record it when it is in code you are changing).
"""
import os
import re
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET
from pathlib import Path

HERE = Path(__file__).parent
HEADER = (
    '"""Known failures of the bad-input campaign (tests/test_api_campaign.py), as strict xfails.'
    '''

``"module.callable:parameter"`` -> (what fails, slow): each call listed fails today (written by
``python tests/api_campaign_record.py`` from a run of the campaign, then read). Fix them and delete
the entry (strict: a fixed entry turns the run red until it is deleted). ``slow`` marks an entry
whose calls hang until the campaign's 10 s alarm. ``"module.callable:*"`` is the hypothesis search
over random numbers for that callable (its first failing example).
"""
''')


def failures(junit):
    entries = {}
    for tc in ET.parse(junit).getroot().iter("testcase"):
        f = tc.find("failure")
        if f is None:
            continue
        test, _, cid = tc.get("name").partition("[")
        cid = cid[:-1] + (":*" if test.startswith("test_random") else "")
        txt = f.text or ""
        lines = []
        for line in txt.splitlines():
            if not (line.startswith("E ") and "->" in line):
                continue
            line = line[2:].strip().replace("AssertionError: ", "")
            if line.startswith("assert"):
                continue
            if len(line) > 150:
                line = re.sub(r"(: ['\"].{0,90}).*$", r"\1...'", line)
            if line not in lines:
                lines.append(line)
        if not lines:
            lines = [txt.strip().splitlines()[-1][:200]]
        entries[cid] = (lines, any("still running after" in line for line in lines))
    return entries


def _pieces(text, width):
    out = []
    while text:
        cut = width
        while len(repr(text[:cut])) > width + 2 and cut > 10:
            cut -= 4
        out.append(text[:cut])
        text = text[cut:]
    return out


def render(entries):
    rows = [HEADER, "KNOWN = {"]
    for cid in sorted(entries):
        lines, slow = entries[cid]
        rows.append(f"    {cid!r}: ((")
        for i, line in enumerate(lines):
            for piece in _pieces(line + ("\n" if i < len(lines) - 1 else ""), 85):
                rows.append(f"        {piece!r}")
        rows.append(f"    ), {slow}),")
    rows.append("}")
    return "\n".join(rows) + "\n"


def main():
    with tempfile.TemporaryDirectory() as tmp:
        junit = Path(tmp) / "campaign.xml"
        env = {**os.environ, "AFMSMILER_CAMPAIGN_RECORD": "1"}
        subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider",
                        str(HERE / "test_api_campaign.py"), f"--junitxml={junit}"],
                       env=env, check=False)
        entries = failures(junit)
    (HERE / "api_campaign_known.py").write_text(render(entries))
    print(f"{len(entries)} known failures written to {HERE / 'api_campaign_known.py'}")


if __name__ == "__main__":
    main()
