"""How far kanapy's scene packs under each rotation mode, and what it costs the
orientations: packing fraction, time, turn from the drawn orientation and the achieved
tilt-angle statistics, per seed. Prints a Markdown table for BENCHMARKS.md.

Run from the repository root after `cargo build --release`:

    python3 tools/kanapy_orientations.py
"""

import csv
import json
import math
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

SCENE = Path("configs/kanapy_elongated.toml")
PACK = Path("target/release/pack")
SEEDS = [2024, 1, 2, 3]
# (label, lines added to the scene's [packing] table)
MODES = [
    ("fixed", ["rotation = false"]),
    ("axis, restore = false", ['rotation = "axis"', "restore = false"]),
    ("axis, max_turn = 20", ['rotation = "axis"', "max_turn = 20"]),
    ("axis", ['rotation = "axis"']),
    ("free, restore = false", ["rotation = true", "restore = false"]),
    ("free", ["rotation = true"]),
]


def with_packing(text, lines):
    """The scene with its [packing] table (which it ends with `rotation = ...` in)
    replaced by one holding `lines`."""
    shipped = '\n[packing]\nrotation = "axis"\n'
    assert shipped in text, "configs/kanapy_elongated.toml changed its [packing] table"
    return text.replace(shipped, "\n[packing]\n" + "\n".join(lines) + "\n", 1)


def median_elevation(grains_csv):
    """Median angle (degrees) of the grains' first axes out of the x-y plane: the z
    component of column 0 of the rotation matrix of (w, x, y, z) is 2(xz - wy)."""
    with open(grains_csv) as f:
        rows = list(csv.DictReader(f))
    return statistics.median(
        math.degrees(math.asin(min(1.0, abs(2 * (float(r["qx"]) * float(r["qz"])
                                              - float(r["qw"]) * float(r["qy"]))))))
        for r in rows)


def main():
    text = SCENE.read_text()
    print("| mode | seed | fraction | stop | packing (s) | median / largest turn (°) "
          "| out of plane, median (°) | tilt std (°), target 45.0 | tilt KS distance |")
    print("|---|---:|---:|---|---:|---|---:|---:|---:|")
    with tempfile.TemporaryDirectory() as tmp:
        scene = Path(tmp) / "scene.toml"
        for label, lines in MODES:
            scene.write_text(with_packing(text, lines))
            for seed in SEEDS:
                out = Path(tmp) / "out"
                run = subprocess.run(
                    [str(PACK), str(scene), "--out", str(out), "--seed", str(seed), "--quiet"],
                    capture_output=True, text=True)
                if run.returncode not in (0, 3):
                    sys.exit(f"pack failed ({run.returncode}): {run.stderr}")
                s = json.loads((out / "summary.json").read_text())
                tilt = s["phases"][0]["tilt_angle_deg"]
                r = s["rotation"]
                print(f"| {label} | {seed} | {s['packing_fraction']:.4f} | {s['stop_reason']} "
                      f"| {s['timings']['packing']:.2f} "
                      f"| {r['median_turn_deg']:.1f} / {r['largest_turn_deg']:.1f} "
                      f"| {median_elevation(out / 'grains.csv'):.1f} "
                      f"| {tilt['achieved']['std']:.1f} | {tilt['ks_distance']:.3f} |")


if __name__ == "__main__":
    main()
