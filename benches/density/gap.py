#!/usr/bin/env python3
"""What `packing.gap` costs in density and time.

    python3 benches/density/gap.py PACK_BINARY [--main MAIN_PACK] [--gaps 0,0.02,0.05,0.1] [SCENES...]

Packs each scene (default: mono_periodic_1000, mono_periodic and lognormal_periodic of
this folder, which ask for more than random packings reach) with each gap, on one thread
with the scene's seed, and prints one Markdown row per run: the fraction reached, what
the gap-0 run predicts if the gap simply inflates the grains (its fraction over
(1 + gap)^3), the FIRE steps and the time.

A scene must not ask for more than the densest packing once inflated (pack refuses
expected fraction x (1 + gap)^3 > 0.7707), so for each gap the box is widened, its
proportions kept, until the inflated grains ask for at most CAP = 0.76 of it: still
beyond random close packing, so every run goes on until it jams. With --main, a build
without `packing.gap` packs each scene as it stands first (row "main"), interleaved with
the branch's runs, for the time and steps of gap 0 before the change.
"""

import argparse
import json
import re
import subprocess
import tempfile
from pathlib import Path

CAP = 0.76
HERE = Path(__file__).resolve().parent
SCENES = ["mono_periodic_1000", "mono_periodic", "lognormal_periodic"]


def run(pack, text, work):
    scene = work / "scene.toml"
    scene.write_text(text)
    subprocess.run(
        [pack, "--quiet", "--threads", "1", "--out", work / "run", scene], check=False, capture_output=True
    )
    summary = json.loads((work / "run" / "summary.json").read_text())
    (work / "run" / "summary.json").unlink()
    return summary


def with_gap(text, gap, widen):
    size = re.search(r"^size = \[([^\]]*)\]", text, re.M)
    sides = [float(x) * widen for x in size.group(1).split(",")]
    text = text[: size.start()] + f"size = [{', '.join(repr(x) for x in sides)}]" + text[size.end() :]
    return text if gap is None else text + f"\n[packing]\ngap = {gap}\n"


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("pack")
    parser.add_argument("--main", help="a pack built without packing.gap, run on the scene as it stands")
    parser.add_argument("--gaps", default="0,0.02,0.05,0.1")
    parser.add_argument("scenes", nargs="*")
    args = parser.parse_args()
    gaps = [float(g) for g in args.gaps.split(",")]
    scenes = [Path(s) for s in args.scenes] or [HERE / f"{s}.toml" for s in SCENES]
    print("| scene | grains | gap | asked (grains) | asked (inflated) | reached | gap 0 / (1 + gap)³ "
          "| ratio | estimate | smallest gap | FIRE steps | time (s) | stop |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|")
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        for scene in scenes:
            text = scene.read_text()
            assert "[packing]" not in text, f"{scene} has a [packing] table"
            plain = run(args.pack, with_gap(text, 0, 1.0), work)
            full = plain["full_size_fraction"]
            base = None
            for gap in ([None] if args.main else []) + gaps:
                widen = max(1.0, (full * (1 + (gap or 0)) ** 3 / CAP) ** (1 / 3))
                if gap == 0 and widen == 1.0:
                    s = plain
                else:
                    s = run(args.main if gap is None else args.pack, with_gap(text, gap, widen), work)
                if gap == 0:
                    base = s["packing_fraction"]
                expect = base / (1 + (gap or 0)) ** 3 if base else float("nan")
                reached = s["packing_fraction"]
                least = "–" if s.get("min_gap") is None else f"{s['min_gap']:.5f}"
                asked = s["full_size_fraction"]
                label = "main" if gap is None else gap
                print(f"| {scene.stem} | {s['grains']} | {label} | {asked:.4f} | {asked * (1 + (gap or 0)) ** 3:.4f} "
                      f"| {reached:.4f} | {expect:.4f} | {reached / expect:.4f} | {s['reachable_fraction']:.4f} "
                      f"| {least} | {s['counters']['fire_steps']} | {s['timings']['packing']:.1f} "
                      f"| {s['stop_reason']} |", flush=True)


if __name__ == "__main__":
    main()
