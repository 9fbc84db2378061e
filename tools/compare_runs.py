#!/usr/bin/env python3
"""Compares the outputs of two builds of `pack` on the same scenes, file by file.

    python3 tools/compare_runs.py BEFORE_DIR AFTER_DIR [--new-keys gap,min_gap]

Each directory holds one output directory per scene (`pack SCENE --out DIR/NAME`).
Every file but summary.json must be byte-identical; each summary.json must be equal,
key order included, once its timings (`timings`, `rve.voxelise_seconds`) and the keys
AFTER adds (--new-keys, top level) are removed. Prints one line per scene and exits
non-zero on any difference.
"""

import argparse
import json
import sys
from pathlib import Path


def without_timings(summary):
    summary.pop("timings")
    if "rve" in summary:
        summary["rve"].pop("voxelise_seconds", None)
    return summary


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("before", type=Path)
    parser.add_argument("after", type=Path)
    parser.add_argument("--new-keys", default="")
    args = parser.parse_args()
    new_keys = [k for k in args.new_keys.split(",") if k]
    ok = True
    for scene in sorted(p for p in args.before.iterdir() if p.is_dir()):
        other = args.after / scene.name
        files = sorted(p.name for p in scene.iterdir())
        differ = [f for f in files if f != "summary.json" and (scene / f).read_bytes() != (other / f).read_bytes()]
        if sorted(p.name for p in other.iterdir()) != files:
            differ.append("(the file lists)")
        if "summary.json" in files:
            a = without_timings(json.loads((scene / "summary.json").read_text()))
            b = without_timings(json.loads((other / "summary.json").read_text()))
            added = {k: b.pop(k, "(missing)") for k in new_keys}
            if a != b or list(a) != list(b):
                differ.append("summary.json")
        else:
            added = {}
        ok &= not differ
        state = f"{len(files)} files identical" if not differ else f"DIFFERENT: {', '.join(differ)}"
        print(f"{scene.name}: {state}; added {added}")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
