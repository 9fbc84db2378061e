#!/usr/bin/env python3
"""Runs the user guide's examples, so that none of them can rot.

    python tools/run_guide.py [--pack target/release/pack] [--keep DIR] [PAGE.md ...]

A fenced block in a page of `docs/` (or in README.md) runs when the line just before
its opening fence is the marker `<!-- run -->` (invisible on GitHub and in the built
guide):

    <!-- run -->
    ```sh
    pack configs/grains.toml --out first --quiet
    ```

With the marker `<!-- run: NAME -->` instead, a block of any language is not run but
written to the file NAME, for the next blocks to use (a scene shown in TOML).

- `sh` (or `bash`, `console` is not accepted) blocks run with bash, `set -eo pipefail`;
  `python` blocks run with the Python that runs this script (the venv whose packages
  the guide installs: grainpack, pyvista, damask, dask).
- Each page's blocks run in order in one fresh directory, the page's own, where the
  repository's `configs`, `tools` and `examples` folders are linked, as if the reader
  were at the repository root; what one block writes, the next one reads.
- `pack` on the PATH is the given binary (default `target/release/pack`), and `python`
  and `python3` are this Python.

A block that exits non-zero fails the page, and the script exits 1 after running every
page; a marker not followed by a fence, a block of another language, or a tutorial
page (`docs/tutorials/`) with no marked block is an error too. With no PAGE, README.md
and every page of `docs/` run. Uses only the standard library.
"""

import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
MARKER = "<!-- run -->"
# `<!-- run: NAME -->`: the block is written to the file NAME.
FILE_MARKER = re.compile(r"^<!-- run: ([A-Za-z0-9_.-]+) -->$")
FENCE = re.compile(r"^(```+)\s*([A-Za-z0-9_+-]*)\s*$")
SHELLS = {"sh", "bash"}
# Repository folders a tutorial's commands name, linked into each page's directory.
LINKED = ["configs", "tools", "examples"]
# A block that runs longer than this has hung (the slowest, the Dask ensemble, takes
# about 15 s on the 2-core CI machine).
BLOCK_TIMEOUT_S = 300


def shown(page: Path) -> str:
    """The page's path as reports give it: from the repository root when inside it."""
    return str(page.relative_to(ROOT)) if page.is_relative_to(ROOT) else str(page)


class GuideError(Exception):
    """A page whose markers or blocks cannot be run as written."""


def blocks(page: Path) -> list[tuple[int, str, str]]:
    """The marked blocks of a page: (line of the fence, language or "file:NAME", code)."""
    lines = page.read_text(encoding="utf-8").splitlines()
    found = []
    i = 0
    while i < len(lines):
        to_file = FILE_MARKER.match(lines[i].strip())
        if lines[i].strip() != MARKER and to_file is None:
            i += 1
            continue
        start = i + 1
        fence = FENCE.match(lines[start]) if start < len(lines) else None
        if fence is None:
            raise GuideError(f"{page}:{i + 1}: {lines[i].strip()} is not followed by a fenced block")
        lang = f"file:{to_file.group(1)}" if to_file else fence.group(2)
        if not to_file and lang not in SHELLS and lang != "python":
            raise GuideError(f"{page}:{start + 1}: a marked block must be sh, bash or python, not {lang!r}")
        end = start + 1
        while end < len(lines) and lines[end].strip() != fence.group(1):
            end += 1
        if end == len(lines):
            raise GuideError(f"{page}:{start + 1}: the block is never closed")
        found.append((start + 1, lang, "\n".join(lines[start + 1:end]) + "\n"))
        i = end + 1
    return found


def run_page(page: Path, work: Path, env: dict[str, str]) -> list[str]:
    """Runs a page's blocks in `work`; returns the failures."""
    for name in LINKED:
        os.symlink(ROOT / name, work / name)
    failures = []
    for n, (line, lang, code) in enumerate(blocks(page)):
        if lang.startswith("file:"):
            (work / lang[len("file:"):]).write_text(code)
            continue
        script = work / f".block{n}.{'py' if lang == 'python' else 'sh'}"
        script.write_text(code if lang == "python" else "set -eo pipefail\n" + code)
        command = [sys.executable, script.name] if lang == "python" else ["bash", script.name]
        started = time.time()
        try:
            done = subprocess.run(command, cwd=work, env=env, stdin=subprocess.DEVNULL,
                                  capture_output=True, text=True, timeout=BLOCK_TIMEOUT_S)
            status = done.returncode
            output = done.stdout + done.stderr
        except subprocess.TimeoutExpired as e:
            status, output = "timeout", f"{e.stdout or ''}{e.stderr or ''}"
        where = f"{shown(page)}:{line}"
        print(f"  {where} ({lang}) {'ok' if status == 0 else 'FAILED'} in {time.time() - started:.1f} s")
        if status != 0:
            failures.append(f"{where}: exit {status}\n{output[-3000:]}")
            break  # the next blocks read what this one should have written
    return failures


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("pages", nargs="*", type=Path)
    parser.add_argument("--pack", default=str(ROOT / "target" / "release" / "pack"))
    parser.add_argument("--keep", type=Path, help="run in DIR/<page> and keep what was written")
    args = parser.parse_args()
    pack = Path(args.pack).resolve()
    if not pack.is_file():
        print(f"run_guide: no pack binary at {pack} (build it: cargo build --release)")
        return 1
    pages = [p.resolve() for p in args.pages] or [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]

    bin_dir = Path(tempfile.mkdtemp(prefix="run_guide_bin_"))
    os.symlink(pack, bin_dir / "pack")
    # A wrapper, not a link: a venv's Python finds its packages from the path it is
    # started by, and a link elsewhere would start the base Python.
    for name in ("python", "python3"):
        (bin_dir / name).write_text(f'#!/bin/sh\nexec "{sys.executable}" "$@"\n')
        (bin_dir / name).chmod(0o755)
    env = dict(os.environ, PATH=f"{bin_dir}{os.pathsep}{Path(sys.executable).parent}"
               f"{os.pathsep}{os.environ.get('PATH', '')}", MPLBACKEND="Agg")

    failures, ran, started = [], 0, time.time()
    try:
        for page in pages:
            try:
                marked = blocks(page)
            except GuideError as e:
                failures.append(str(e))
                continue
            if not any(not lang.startswith("file:") for _, lang, _ in marked):
                if page.parent.name == "tutorials":
                    failures.append(f"{shown(page)}: a tutorial with no {MARKER} block")
                continue
            print(f"{shown(page)}: {len(marked)} blocks")
            if args.keep:
                work = args.keep.resolve() / page.stem
                shutil.rmtree(work, ignore_errors=True)
                work.mkdir(parents=True)
            else:
                work = Path(tempfile.mkdtemp(prefix=f"run_guide_{page.stem}_"))
            failures += run_page(page, work, env)
            ran += len(marked)
            if not args.keep:
                shutil.rmtree(work, ignore_errors=True)
    finally:
        shutil.rmtree(bin_dir, ignore_errors=True)
    print(f"{ran} blocks of {len(pages)} pages in {time.time() - started:.1f} s")
    if failures:
        print("FAILED:\n" + "\n".join(failures))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
