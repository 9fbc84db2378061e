#!/usr/bin/env python3
"""One scene, two solvers: the effective Young's modulus of configs/particle_composite.toml
from CalculiX (rve.inp, in the scene's units) and from DAMASK_grid (material.yaml and
rve.vti, in SI), compared in the scene's stress unit. Run by hand: DAMASK_grid is not
on a package registry (docs/damask.md says how it was built).

    python tools/damask_vs_ccx.py --damask /path/to/DAMASK_grid [--cells 20 40]

For each resolution N the scene is packed once (the same grains at every N: the seed
fixes them) with `rve_resolution = N`, and both solvers load the same voxels in
uniaxial stress along x (the normal strain along x imposed, the lateral normal
stresses zero, the shears held at zero):

- CalculiX: the deck's periodic equations, the template step of rve.inp along x
  (strain 1e-3, small-strain linear elasticity, SPOOLES); E = total force on the face
  x = Lx over its area, over the strain (as tools/ccx_solve.py).
- DAMASK_grid (spectral_basic, finite strain): one increment of dot_F_xx = 1e-3/s for
  0.1 s (strain 1e-4, so the finite-strain stiffening, of the order of the strain, is
  1e-4 relative), P = 0 on the other normal components; E = mean P_xx over
  mean F_xx - 1 (damask.Result; every voxel has the same volume), divided by the
  pascals per unit of the scene's `units.stress` (summary.json).

Prints a table of both moduli and their relative difference per resolution; exit 0.
Needs `ccx` (Debian: calculix-ccx) and the `damask` Python package (pinned in
tools/requirements-exports.txt).
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

import damask
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from ccx_solve import solve  # noqa: E402

SCENE = "configs/particle_composite.toml"
PASCALS = {"Pa": 1.0, "kPa": 1e3, "MPa": 1e6, "GPa": 1e9}
# One small increment: the strain 1e-4 keeps the finite-strain terms at 1e-4 relative.
LOAD = """solver:
  mechanical: spectral_basic
loadstep:
  - boundary_conditions:
      mechanical:
        dot_F: [[1.0e-3, 0, 0], [0, x, 0], [0, 0, x]]
        P: [[x, x, x], [x, 0, x], [x, x, 0]]
    discretization: {t: 0.1, N: 1}
    f_out: 1
"""


def damask_modulus(out, damask_grid):
    """E_xx and nu_xy of DAMASK's solution on the set in `out`, in Pa."""
    with open(os.path.join(out, "load_small.yaml"), "w") as f:
        f.write(LOAD)
    started = time.time()
    run = subprocess.run(
        [damask_grid, "--load", "load_small.yaml", "--geom", "rve.vti", "--material", "material.yaml"],
        cwd=out, capture_output=True, text=True)
    seconds = time.time() - started
    with open(os.path.join(out, "damask.log"), "w") as f:
        f.write(run.stdout + run.stderr)
    if run.returncode != 0 or "increment 1 converged" not in run.stdout:
        raise RuntimeError(f"DAMASK_grid failed in {out} (see damask.log):\n{run.stdout[-2000:]}")
    result = damask.Result(os.path.join(out, "rve_load_small_material.hdf5"))
    last = result.view(increments=result.increments[-1])
    p = np.asarray(last.place("P")).mean(axis=0)
    f = np.asarray(last.place("F")).mean(axis=0)
    return p[0, 0] / (f[0, 0] - 1.0), -(f[1, 1] - 1.0) / (f[0, 0] - 1.0), seconds


def ccx_modulus(out, size, work):
    """E_xx and nu_xy of CalculiX's solution of rve.inp, in the deck's units."""
    started = time.time()
    force, strains = solve(os.path.join(out, "rve.inp"), 0, size, work, iterative=False)
    e = force / (size[1] * size[2]) / strains[0]
    return e, -strains[1] / strains[0], time.time() - started


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--damask", required=True, help="the DAMASK_grid executable")
    parser.add_argument("--pack", default="target/release/pack")
    parser.add_argument("--cells", type=int, nargs="+", default=[20, 40])
    parser.add_argument("--work", default=None, help="directory to work in (default: a temporary one)")
    args = parser.parse_args()
    pack = os.path.abspath(args.pack)
    damask_grid = os.path.abspath(args.damask)
    work = os.path.abspath(args.work or tempfile.mkdtemp(prefix="damask_vs_ccx_"))
    os.makedirs(work, exist_ok=True)
    with open(SCENE) as f:
        text = f.read()
    rows = []
    for n in args.cells:
        name = f"composite_{n}"
        scene = os.path.join(work, name + ".toml")
        with open(scene, "w") as f:
            f.write(text.replace("rve_resolution = 20", f"rve_resolution = {n}"))
        out = os.path.join(work, name)
        subprocess.run([pack, scene, "--out", out, "--quiet"], check=True)
        with open(os.path.join(out, "summary.json")) as f:
            summary = json.load(f)
        unit = summary["units"]["stress"]
        e_ccx, nu_ccx, t_ccx = ccx_modulus(out, summary["box"], work)
        e_si, nu_damask, t_damask = damask_modulus(out, damask_grid)
        e_damask = e_si / PASCALS[unit]
        rows.append((n, 1.0 - summary["rve"]["matrix_fraction"], e_ccx, e_damask, nu_ccx, nu_damask))
        print(f"{n}^3 cells: CalculiX E = {e_ccx:.1f} {unit} (nu {nu_ccx:.4f}, {t_ccx:.1f} s), "
              f"DAMASK_grid E = {e_damask:.1f} {unit} (nu {nu_damask:.4f}, {t_damask:.1f} s), "
              f"DAMASK / CalculiX - 1 = {e_damask / e_ccx - 1:+.4f}", flush=True)
    print(f"\n| cells | particle fraction (voxels) | CalculiX E ({unit}) | DAMASK_grid E ({unit}) "
          "| DAMASK / CalculiX − 1 | CalculiX ν | DAMASK ν |")
    print("| ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for n, phi, e_ccx, e_damask, nu_ccx, nu_damask in rows:
        print(f"| {n}³ | {phi:.4f} | {e_ccx:.1f} | {e_damask:.1f} | {e_damask / e_ccx - 1:+.4f} "
              f"| {nu_ccx:.4f} | {nu_damask:.4f} |")
    print(f"(work in {work})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
