"""Per-pair time of grainpack.contact_function against the library's batch code.

The Python function (numpy arrays in, checks, copies into the batch's layout in
chunks, results out as arrays) and the Rust batch alone (`contact_functions` on the
same pairs already in its layout, one call; timed inside the same native module, so
built with the same flags) are run in alternation, ROUNDS times each, on 10⁶ pairs:
the typical reference set (tests/data/contact_typical.csv) repeated 1000 times.

    python python/benches/contact.py            # after pip install ./python
"""

from __future__ import annotations

import statistics
import sys
import time
from pathlib import Path

import numpy as np

import grainpack as gp
from grainpack import _grainpack

ROUNDS = 15
REPEATS = 1000


def main() -> None:
    data = Path(__file__).resolve().parents[2] / "tests" / "data" / "contact_typical.csv"
    table = np.loadtxt(data, delimiter=",", skiprows=1)
    r12 = np.ascontiguousarray(np.tile(table[:, 0:3], (REPEATS, 1)))
    q1 = np.ascontiguousarray(np.tile(table[:, 3:9], (REPEATS, 1)))
    q2 = np.ascontiguousarray(np.tile(table[:, 9:15], (REPEATS, 1)))
    n = len(r12)
    rust, python = [], []
    for _ in range(ROUNDS):
        rust += _grainpack._rust_batch_seconds(r12, q1, q2, 1)
        started = time.perf_counter()
        gp.contact_function(r12, q1, q2)
        python.append(time.perf_counter() - started)
    ns = lambda s: 1e9 * s / n
    r, p = statistics.median(rust), statistics.median(python)
    print(f"pairs: {n}, rounds: {ROUNDS} each, alternated")
    print(f"rust batch    : median {ns(r):6.1f} ns/pair (min {ns(min(rust)):6.1f})")
    print(f"python (numpy): median {ns(p):6.1f} ns/pair (min {ns(min(python)):6.1f})")
    print(f"ratio python/rust: median {p / r:.3f}, min/min {min(python) / min(rust):.3f}")
    sys.stdout.flush()


if __name__ == "__main__":
    main()
