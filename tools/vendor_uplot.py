"""Fetch a named uPlot release from the npm registry, check its hash, and ship its files.

The live figures (``afmsmiler/plots/live.py``) draw with uPlot (https://github.com/leeoniya/uPlot,
MIT licence). Its release files ship inside the package, so a student needs no Node and no network;
this script is the only way they get there, so they are never retyped or edited by hand:

    python tools/vendor_uplot.py            # the pinned version below, into afmsmiler/plots/static/
    python tools/vendor_uplot.py --check    # fetch again and compare with what ships

The tarball's SHA-512 must equal both the pin below and the registry's ``dist.integrity``; the
files written and their SHA-256 are recorded in ``afmsmiler/plots/static/uPlot.json``, which a test
(``tests/test_plots_live.py``) compares with the shipped files.
"""
from __future__ import annotations

import argparse
import base64
import hashlib
import io
import json
import sys
import tarfile
import urllib.request
from pathlib import Path

VERSION = "1.6.32"
#: SHA-512 of uplot-1.6.32.tgz, as the npm registry publishes it (dist.integrity).
INTEGRITY = ("sha512-KIMVnG68zvu5XXUbC4LQEPnhwOxBuLyW1AHtpm6IKTXImkbLgkMy+jabjLgSLMasNuGGzQm/"
             "ep3tOkyTxpiQIw==")
#: Member of the tarball -> file name in the package.
FILES = {"package/dist/uPlot.iife.min.js": "uPlot.iife.min.js",
         "package/dist/uPlot.min.css": "uPlot.min.css",
         "package/LICENSE": "uPlot.LICENSE"}
REGISTRY = "https://registry.npmjs.org/uplot"
STATIC = Path(__file__).resolve().parents[1] / "afmsmiler" / "plots" / "static"


def _get(url: str) -> bytes:
    with urllib.request.urlopen(url, timeout=60) as r:  # noqa: S310 (a fixed https URL)
        return r.read()


def fetch(version: str = VERSION, integrity: str = INTEGRITY) -> dict:
    """The release files of ``version``, checked against ``integrity`` and the registry's."""
    meta = json.loads(_get(f"{REGISTRY}/{version}"))
    dist = meta["dist"]
    if dist["integrity"] != integrity:
        raise SystemExit(f"the registry's integrity of uplot {version} is {dist['integrity']}, "
                         f"the pin is {integrity}")
    tarball = _get(dist["tarball"])
    digest = "sha512-" + base64.b64encode(hashlib.sha512(tarball).digest()).decode()
    if digest != integrity:
        raise SystemExit(f"the tarball of uplot {version} hashes to {digest}, not {integrity}")
    out = {}
    with tarfile.open(fileobj=io.BytesIO(tarball), mode="r:gz") as tar:
        for member, name in FILES.items():
            out[name] = tar.extractfile(member).read()
    return out


def manifest(files: dict, version: str = VERSION) -> dict:
    return {"package": "uplot", "version": version, "integrity": INTEGRITY,
            "source": f"{REGISTRY}/-/uplot-{version}.tgz", "licence": "MIT",
            "files": {name: hashlib.sha256(data).hexdigest() for name, data in sorted(files.items())}}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true",
                        help="compare the shipped files with a fresh download")
    args = parser.parse_args(argv)
    files = fetch()
    if args.check:
        bad = [n for n, d in files.items() if (STATIC / n).read_bytes() != d]
        print("uPlot", VERSION, "shipped files match the registry" if not bad else f"differ: {bad}")
        return 1 if bad else 0
    STATIC.mkdir(parents=True, exist_ok=True)
    for name, data in files.items():
        (STATIC / name).write_bytes(data)
    (STATIC / "uPlot.json").write_text(json.dumps(manifest(files), indent=2) + "\n")
    print(f"uPlot {VERSION}: wrote {', '.join(files)} into {STATIC}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
