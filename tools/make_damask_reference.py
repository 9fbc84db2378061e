#!/usr/bin/env python3
"""Writes tests/data/damask_rotations.csv: Bunge Euler angles and quaternions as DAMASK's
own `damask.Rotation` converts them, the reference of grainpack's orientation convention
(tests/damask_convention.rs).

    python tools/make_damask_reference.py --out tests/data

Rows `kind=euler`: Euler angles (radians) drawn uniformly in [0, 2π) × [0, π] × [0, 2π)
with numpy's PCG64 seeded 13, and `Rotation.from_Euler_angles(...).quaternion`.
Rows `kind=quaternion`: `Rotation.from_random(seed=17)` quaternions and
`as_Euler_angles()` (radians). Values with 17 significant digits (exact doubles).
Needs the pinned damask (tools/requirements-exports.txt).
"""

import argparse
import os

import damask
import numpy as np

SAMPLES = 500


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--out", default="tests/data")
    args = parser.parse_args()
    rng = np.random.default_rng(13)
    eu = np.column_stack([rng.uniform(0, 2 * np.pi, SAMPLES), rng.uniform(0, np.pi, SAMPLES),
                          rng.uniform(0, 2 * np.pi, SAMPLES)])
    qu = damask.Rotation.from_Euler_angles(eu).quaternion
    random = damask.Rotation.from_random(SAMPLES, rng_seed=17)
    rows = [("euler", e, q) for e, q in zip(eu, qu)]
    rows += [("quaternion", e, q) for e, q in zip(random.as_Euler_angles(), random.quaternion)]
    path = os.path.join(args.out, "damask_rotations.csv")
    with open(path, "w") as f:
        f.write(f"# damask {damask.__version__}: tools/make_damask_reference.py\n")
        f.write("kind,phi1,Phi,phi2,q0,q1,q2,q3\n")
        for kind, e, q in rows:
            f.write(kind + "," + ",".join(f"{v:.16e}" for v in (*e, *q)) + "\n")


if __name__ == "__main__":
    main()
