"""Fetch a named MathJax 3 release from the npm registry, check its hash, unpack it into the book.

The course book (``make book``) typesets its equations with MathJax (https://www.mathjax.org,
Apache licence 2.0). Sphinx would load it from a CDN on every page view; the book instead ships
the release inside its build (``book/_extra/mathjax``, copied to the build's ``mathjax/``,
which ``book/_config.yml`` names as ``mathjax_path``), so a reader needs no network. This script is the only way the files get
there, so they are never edited by hand and never committed (``book/_extra/`` and the
cached tarball are ignored by git):

    python tools/vendor_mathjax.py book/_extra/mathjax    # make book runs this

The tarball of the pinned version is downloaded once from the npm registry into
``book/_vendor/`` (or read from ``$MATHJAX_TARBALL``, e.g. a file that ``npm pack
mathjax@3.2.2`` wrote on another machine, for a build with no network at all). Its SHA-512
must equal the pin below (the registry's ``dist.integrity``) before anything is unpacked; a
tarball that does not match is refused, and a cached one that does not match is fetched again.
Only what the book's pages load is unpacked (:data:`KEEP`): the combined TeX and MathML to
CommonHTML component that Sphinx loads, the TeX extensions it autoloads, the CommonHTML fonts,
the menu and the accessibility components with the speech rules they load, and the licence.
"""
from __future__ import annotations

import argparse
import base64
import hashlib
import io
import os
import shutil
import sys
import tarfile
import urllib.request
from pathlib import Path

VERSION = "3.2.2"
#: SHA-512 of mathjax-3.2.2.tgz, as the npm registry publishes it (dist.integrity).
INTEGRITY = ("sha512-Bt+SSVU8eBG27zChVewOicYs7Xsdt40qm4+UpHyX7k0/O9NliPc+x77k1/"
             "FEsPsjKPZGJvtRZM1vO+geW0OhGw==")
TARBALL_URL = f"https://registry.npmjs.org/mathjax/-/mathjax-{VERSION}.tgz"
ROOT = Path(__file__).resolve().parents[1]
CACHE = ROOT / "book" / "_vendor" / f"mathjax-{VERSION}.tgz"
#: The entry point Sphinx loads (``mathjax_path`` in book/_config.yml).
ENTRY = "tex-mml-chtml.js"
#: Members of the tarball's ``package/es5/`` that are unpacked (a file or a folder prefix).
KEEP = (ENTRY, "input/", "output/chtml/", "output/chtml.js", "ui/", "a11y/", "sre/",
        "adaptors/")
MAX_TARBALL = 64 * 2**20  # bytes: the 3.2.2 tarball is 6 MB; anything far larger is not it


def integrity_of(data: bytes) -> str:
    """The npm ``dist.integrity`` string (``sha512-<base64>``) of ``data``."""
    return "sha512-" + base64.b64encode(hashlib.sha512(data).digest()).decode()


def tarball(cache: Path = CACHE) -> bytes:
    """The pinned release's tarball, checked: ``$MATHJAX_TARBALL``, else the cache, else npm."""
    given = os.environ.get("MATHJAX_TARBALL")
    if given:
        data = Path(given).read_bytes()
        if integrity_of(data) != INTEGRITY:
            raise SystemExit(f"MATHJAX_TARBALL={given} hashes to {integrity_of(data)}, "
                             f"not mathjax {VERSION}'s {INTEGRITY}")
        return data
    if cache.exists():
        data = cache.read_bytes()
        if integrity_of(data) == INTEGRITY:
            return data
        print(f"{cache} does not match the pin: fetching it again", file=sys.stderr)
    try:
        with urllib.request.urlopen(TARBALL_URL, timeout=60) as r:  # noqa: S310 (fixed https URL)
            data = r.read(MAX_TARBALL + 1)
    except OSError as err:
        raise SystemExit(f"cannot fetch {TARBALL_URL} ({err}); with no network, set "
                         f"MATHJAX_TARBALL to a copy (npm pack mathjax@{VERSION})") from None
    if integrity_of(data) != INTEGRITY:
        raise SystemExit(f"{TARBALL_URL} hashes to {integrity_of(data)}, not the pin {INTEGRITY}")
    cache.parent.mkdir(parents=True, exist_ok=True)
    cache.write_bytes(data)
    return data


def unpack(data: bytes, dest: Path) -> int:
    """Unpack the kept members of the tarball ``data`` into ``dest`` (replaced); return the count."""
    dest = Path(dest)
    if dest.exists():
        shutil.rmtree(dest)
    dest.mkdir(parents=True)
    n = 0
    with tarfile.open(fileobj=io.BytesIO(data), mode="r:gz") as tar:
        for member in tar.getmembers():
            if member.name == "package/LICENSE":
                (dest / "LICENSE").write_bytes(tar.extractfile(member).read())
                continue
            if not member.isfile() or not member.name.startswith("package/es5/"):
                continue
            rel = member.name[len("package/es5/"):]
            if ".." in Path(rel).parts or not rel.startswith(KEEP):
                continue
            out = dest / rel
            out.parent.mkdir(parents=True, exist_ok=True)
            out.write_bytes(tar.extractfile(member).read())
            n += 1
    if not (dest / ENTRY).exists():
        raise SystemExit(f"mathjax {VERSION}'s tarball has no es5/{ENTRY}")
    (dest / "VERSION").write_text(f"mathjax {VERSION} {INTEGRITY}\n", encoding="utf-8")
    return n


def vendor(dest: Path, cache: Path = CACHE) -> Path:
    """Make ``dest`` hold the pinned MathJax (nothing to do when it already does); return it."""
    dest = Path(dest)
    stamp = dest / "VERSION"
    if stamp.exists() and stamp.read_text(encoding="utf-8").split() == \
            ["mathjax", VERSION, INTEGRITY] and (dest / ENTRY).exists():
        return dest
    n = unpack(tarball(cache), dest)
    print(f"MathJax {VERSION}: {n} files into {dest}")
    return dest


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("dest", type=Path, help="the folder to fill (book/_extra/mathjax)")
    args = parser.parse_args(argv)
    vendor(args.dest)
    return 0


if __name__ == "__main__":
    sys.exit(main())
