"""Wall time of `pack` from Python against the CLI, on the shipped example.

`grainpack.pack(scene, seed).write(dir)` and `pack configs/grains.toml --seed S --out
DIR --quiet` (a subprocess, so its time includes starting the process and reading the
scene), run in alternation ROUNDS times each, same seed, same threads (all cores).

    python python/benches/pack.py [path/to/pack]     # after pip install ./python
"""

from __future__ import annotations

import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import grainpack as gp

ROUNDS = 5
SEED = 7


def main() -> None:
    repo = Path(__file__).resolve().parents[2]
    cli = Path(sys.argv[1]) if len(sys.argv) > 1 else repo / "target" / "release" / "pack"
    example = repo / "configs" / "grains.toml"
    cli_times, py_times = [], []
    with tempfile.TemporaryDirectory() as tmp:
        for k in range(ROUNDS):
            started = time.perf_counter()
            subprocess.run([cli, example, "--seed", str(SEED), "--out", f"{tmp}/cli{k}", "--quiet"], check=True)
            cli_times.append(time.perf_counter() - started)
            started = time.perf_counter()
            gp.pack(gp.Scene.from_toml(example), seed=SEED, progress=False).write(f"{tmp}/py{k}")
            py_times.append(time.perf_counter() - started)
    c, p = statistics.median(cli_times), statistics.median(py_times)
    print(f"{example.name}, seed {SEED}, {ROUNDS} rounds each, alternated")
    print(f"cli   : median {c:.3f} s (min {min(cli_times):.3f})")
    print(f"python: median {p:.3f} s (min {min(py_times):.3f})")
    print(f"ratio python/cli: median {p / c:.3f}")


if __name__ == "__main__":
    main()
