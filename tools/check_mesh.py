#!/usr/bin/env python3
"""Checks the conforming mesh `pack` writes with `[output] mesh = true` (issue 29).

    python tools/check_mesh.py [--pack target/release/pack] [--work DIR]

Needs gmsh in the Python that `pack` runs (`$GRAINPACK_PYTHON`, else python3), and in
this one meshio, numpy and scipy (tools/requirements-exports.txt), and CalculiX `ccx`.
Two scenes are packed and meshed, then checked by programs other than gmsh:

- mesh.msh, read by meshio: every node on a far face of the box has a node on the
  opposite face at the same place moved by the box length, to PERIODIC_TOL of it,
  and the other way round;
- mesh.vtu, read by meshio: no two nodes at one place (a crack between a grain and
  the matrix would be one); cell data grain and phase; every tetrahedron positive; the
  volumes sum to the box's (VOLUME_TOL) and give summary.json's phase fractions;
- a grain crosses a corner of the box: its elements reach all six faces;
- mesh.inp, solved by CalculiX under its periodic equations in uniaxial tension along
  x, y and z (tools/ccx_solve.py's step): a homogeneous RVE (grains and matrix of one
  material) gives back E and nu to HOMOGENEOUS_TOL, and a composite (stiff ellipsoids
  in a soft matrix) gives moduli inside the Hashin-Shtrikman bounds of the mesh's own
  volume fraction; and a homogeneous box with walls (no periodic equations) run as
  written (`ccx -i mesh`) carries E * strain * area.

Exit code 0 when every check passes, 1 otherwise.
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

import meshio
import numpy as np
from scipy.spatial import cKDTree

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from ccx_solve import HOMOGENEOUS_TOL, STRAIN, hashin_shtrikman, kg, solve  # noqa: E402

# Opposite nodes must match to this fraction of the box length (issue 29): gmsh's
# copies sit up to 1e-8 L off, which pack snaps onto master + L exactly.
PERIODIC_TOL = 1e-9
# A node is on a face when within this fraction of the box length of its plane.
ON_FACE_TOL = 1e-7
# Tetrahedra volumes summed in double precision over ~1e4 elements: the sum matches
# the box's to far better than this.
VOLUME_TOL = 1e-9

SCENE = """
seed = {seed}
target_fraction = {fraction}
[box]
size = [10.0, 10.0, 10.0]
boundary = "{boundary}"
[packing]
gap = 0.05
[[phase]]
name = "grains"
size = {{ distribution = "uniform", min = {dmin}, max = {dmax} }}
aspect_ratio = {{ distribution = "uniform", min = 1.2, max = 2.0 }}
elastic = {{ E = {e_grain}, nu = 0.3 }}
[matrix]
elastic = {{ E = {e_matrix}, nu = {nu_matrix} }}
[output]
dir = "{name}"
vtk = false
centers = false
statistics_png = false
mesh = true
mesh_size = 0.3
"""

# Homogeneous: grains and matrix of one material, so the periodic solution is the
# uniform strain. Composite: stiff grains (E 100) in a soft matrix (E 10, nu 0.35).
# The seeds are ones whose packing, in the window the mesher picks, has a grain across
# a corner of the box (10 and 20 grains; the check fails if none does).
SCENES = {
    "homogeneous": dict(seed=1, fraction=0.2, dmin=2.5, dmax=4.0, e_grain=210.0,
                        e_matrix=210.0, nu_matrix=0.3, boundary="periodic"),
    "composite": dict(seed=12, fraction=0.3, dmin=2.5, dmax=4.0, e_grain=100.0,
                      e_matrix=10.0, nu_matrix=0.35, boundary="periodic"),
    # Walls: no periodic equations; the deck is run as written (`ccx -i mesh`).
    "walled": dict(seed=2, fraction=0.25, dmin=2.5, dmax=3.5, e_grain=210.0,
                   e_matrix=210.0, nu_matrix=0.3, boundary="reflecting"),
}


def check_periodic(out, summary, failures):
    mesh = meshio.read(os.path.join(out, "mesh.msh"))
    origin = np.array(summary["mesh"]["origin"])
    size = np.array(summary["box"])
    length = size.max()
    p = mesh.points
    worst = 0.0
    for d in range(3):
        near = np.flatnonzero(np.abs(p[:, d] - origin[d]) < ON_FACE_TOL * length)
        far = np.flatnonzero(np.abs(p[:, d] - origin[d] - size[d]) < ON_FACE_TOL * length)
        if len(near) == 0 or len(near) != len(far):
            failures.append(f"{out}: {len(near)} nodes on the near {'xyz'[d]} face, "
                            f"{len(far)} on the far one")
            continue
        shift = np.zeros(3)
        shift[d] = size[d]
        dist, _ = cKDTree(p[near]).query(p[far] - shift)
        back, _ = cKDTree(p[far]).query(p[near] + shift)
        worst = max(worst, dist.max(), back.max())
    print(f"{out}: opposite face nodes match to {worst / length:.1e} L "
          f"(at most {PERIODIC_TOL:.0e})")
    if worst > PERIODIC_TOL * length:
        failures.append(f"{out}: face nodes {worst / length:.2e} L from their images")


def check_conforming(out, summary, failures):
    """No two nodes at one place: a face meshed twice (a crack) would show so."""
    mesh = meshio.read(os.path.join(out, "mesh.vtu"))
    pairs = cKDTree(mesh.points).query_pairs(ON_FACE_TOL * max(summary["box"]))
    print(f"{out}: {len(pairs)} pairs of coincident nodes (0 for a conforming mesh)")
    if pairs:
        failures.append(f"{out}: {len(pairs)} pairs of coincident nodes: not conforming")


def check_cells(out, summary, failures):
    """Volumes, cell data, and a grain split at a corner; returns the grain fraction."""
    mesh = meshio.read(os.path.join(out, "mesh.vtu"))
    tets = mesh.cells_dict["tetra"]
    grain = mesh.cell_data_dict["grain"]["tetra"]
    phase = mesh.cell_data_dict["phase"]["tetra"]
    p = mesh.points
    a, b, c = (p[tets[:, i]] - p[tets[:, 0]] for i in (1, 2, 3))
    vol = np.einsum("ij,ij->i", a, np.cross(b, c)) / 6.0
    size = np.array(summary["box"])
    box = size.prod()
    if vol.min() <= 0.0:
        failures.append(f"{out}: {np.sum(vol <= 0)} tetrahedra with volume <= 0")
    total = vol.sum()
    print(f"{out}: {len(tets)} tetrahedra, volume {total!r} of a box of {box!r}")
    if abs(total / box - 1.0) > VOLUME_TOL:
        failures.append(f"{out}: tetrahedra sum to {total}, the box is {box}")
    reported = {v["phase"]: v["mesh"] for v in summary["mesh"]["phase_volume_fractions"]}
    for ph, frac in reported.items():
        mine = vol[phase == ph].sum() / box
        if abs(mine - frac) > VOLUME_TOL:
            failures.append(f"{out}: phase {ph} fills {mine} of the mesh, summary says {frac}")
    origin = np.array(summary["mesh"]["origin"])
    length = size.max()
    corner = []
    for g in np.unique(grain[grain >= 0]):
        nodes = p[np.unique(tets[grain == g])]
        faces = [np.any(np.abs(nodes[:, d] - origin[d] - s * size[d]) < ON_FACE_TOL * length)
                 for d in range(3) for s in (0, 1)]
        if all(faces):
            corner.append(int(g))
    print(f"{out}: grains split across all six faces (a corner): {corner}")
    if not corner:
        failures.append(f"{out}: no grain crosses a corner of the box")
    return vol[grain >= 0].sum() / box


def check_walled(out, summary, failures):
    """The deck as written, run by ccx: its template stretches the box by STRAIN along
    x on rollers, so a homogeneous box carries E * STRAIN * Ly * Lz."""
    run = subprocess.run(["ccx", "-i", "mesh"], cwd=out, capture_output=True, text=True)
    if run.returncode != 0 or "ERROR" in run.stdout:
        failures.append(f"{out}: ccx -i mesh failed:\n{run.stdout[-1500:]}")
        return
    with open(os.path.join(out, "mesh.dat")) as f:
        lines = [line.split() for line in f if line.strip()]
    i = next(i for i, w in enumerate(lines) if w[:2] == ["total", "force"])
    force = float(lines[i + 1][0])
    size = summary["box"]
    want = 210.0 * STRAIN * size[1] * size[2]
    print(f"{out}: ccx -i mesh as written: force {force!r} on X1 ({want!r})")
    if abs(force / want - 1.0) > HOMOGENEOUS_TOL:
        failures.append(f"{out}: force {force} on X1, not {want}")


def moduli(out, work, summary):
    deck = os.path.join(out, "mesh.inp")
    size = summary["box"]
    results = []
    for d in range(3):
        force, strains = solve(deck, d, size, work, iterative=False)
        area = size[(d + 1) % 3] * size[(d + 2) % 3]
        e = force / area / strains[d]
        results.append((e, [-strains[o] / strains[d] for o in range(3) if o != d]))
    return results


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--pack", default="target/release/pack")
    parser.add_argument("--work", default=None)
    args = parser.parse_args()
    pack = os.path.abspath(args.pack)
    work = args.work or tempfile.mkdtemp(prefix="check_mesh_")
    os.makedirs(work, exist_ok=True)
    failures = []
    for name, values in SCENES.items():
        started = time.time()
        with open(os.path.join(work, name + ".toml"), "w") as f:
            f.write(SCENE.format(name=name, **values))
        subprocess.run([pack, name + ".toml", "--quiet"], cwd=work, check=True)
        out = os.path.join(work, name)
        with open(os.path.join(out, "summary.json")) as f:
            summary = json.load(f)
        m = summary["mesh"]
        print(f"{name}: {m['elements']} elements, min SICN {m['min_sicn']:.3f}, 1st "
              f"percentile {m['p1_sicn']:.3f}, packed and meshed in {time.time() - started:.1f} s")
        check_conforming(out, summary, failures)
        if name == "walled":
            check_walled(out, summary, failures)
            continue
        check_periodic(out, summary, failures)
        phi = check_cells(out, summary, failures)
        started = time.time()
        results = moduli(out, work, summary)
        if name == "homogeneous":
            for d, (e, nus) in enumerate(results):
                print(f"homogeneous {'xyz'[d]}: E = {e!r} (210), nu = {nus} (0.3)")
                if abs(e / 210.0 - 1.0) > HOMOGENEOUS_TOL:
                    failures.append(f"homogeneous E along {'xyz'[d]} = {e}, not 210")
                failures += [f"homogeneous nu along {'xyz'[d]} = {nu}, not 0.3"
                             for nu in nus if abs(nu - 0.3) > HOMOGENEOUS_TOL]
        else:
            lower, upper = hashin_shtrikman(phi, *kg(10.0, 0.35), *kg(100.0, 0.3))
            print(f"composite: grain fraction {phi:.4f} (mesh), HS bounds "
                  f"[{lower:.4f}, {upper:.4f}]")
            for d, (e, _) in enumerate(results):
                print(f"composite {'xyz'[d]}: E = {e:.4f}")
                if not lower <= e <= upper:
                    failures.append(f"composite E along {'xyz'[d]} = {e} outside the HS "
                                    f"bounds [{lower}, {upper}]")
        print(f"{name}: 3 solves in {time.time() - started:.1f} s")
    if failures:
        print("FAILED:\n  " + "\n  ".join(failures))
        return 1
    print("all mesh checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
