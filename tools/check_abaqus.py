#!/usr/bin/env python3
"""Checks the Abaqus/CalculiX deck `pack` wrote (`[output] abaqus = true`) with meshio.

    python tools/check_abaqus.py OUT_DIR

- `rve.inp`, read by meshio: Nx·Ny·Nz hexahedra (C3D8) on the cells of `rve.vti`
  (read by `damask.GeomGrid.load`), (Nx+1)(Ny+1)(Nz+1) grid nodes and 3 reference
  nodes; every element of the set GRAIN_k has its centre in a voxel of material k, and
  the set's size is that grain's voxel count in `rve_grains.csv`; the phase sets
  partition the elements; the 26 face, edge and corner node sets hold the nodes on
  their planes and no others.

Exit code 0 when every check passes, 1 with the failures listed otherwise.
"""

import csv
import os
import sys

import damask
import meshio
import numpy as np
from checklist import Checklist

# Node coordinates are i·L/N printed to 17 significant digits: a plane is found to a
# few ulp of the box size.
PLANE_TOL = 1e-9


def main():
    check = Checklist(__doc__)
    out, summary = check.out, check.summary
    mesh = meshio.read(os.path.join(out, "rve.inp"), file_format="abaqus")
    grid = damask.GeomGrid.load(os.path.join(out, "rve.vti"))
    n = np.array(grid.cells)
    size = np.array(summary["box"], dtype=float)
    hexes = [c for c in mesh.cells if c.type == "hexahedron"]
    check(len(hexes) == 1 and len(hexes[0].data) == n.prod(), f"not {n.prod()} hexahedra")
    check(len(mesh.points) == (n + 1).prod() + 3, f"{len(mesh.points)} nodes, not {(n + 1).prod() + 3}")
    conn = hexes[0].data
    centres = mesh.points[conn].mean(axis=1)
    ijk = np.floor(centres / (size / n)).astype(int)
    # DAMASK's material array is indexed [x, y, z].
    material = grid.material[ijk[:, 0], ijk[:, 1], ijk[:, 2]]
    with open(os.path.join(out, "rve_grains.csv")) as f:
        voxels = {int(r["id"]): int(r["voxels"]) for r in csv.DictReader(f)}
    phases_seen = np.zeros(len(conn), dtype=int)
    for name, blocks in mesh.cell_sets.items():
        elements = np.concatenate([b for b in blocks if b is not None and len(b)])
        if name.startswith("GRAIN_"):
            k = int(name[6:])
            check(np.all(material[elements] == k), f"{name}: elements outside grain {k}'s voxels")
            check(len(elements) == voxels[k], f"{name}: {len(elements)} elements, {voxels[k]} voxels")
        elif name.startswith("PHASE") or name == "MATRIX" or name.startswith("MATRIX"):
            phases_seen[elements] += 1
    check(np.all(phases_seen == 1), "the phase element sets do not partition the elements")
    grid_points = mesh.points[: (n + 1).prod()]
    for name, ids in mesh.point_sets.items():
        if not name[:1] in "XYZ":
            continue
        want = np.ones(len(grid_points), dtype=bool)
        for axis, side in zip(name[0::2], name[1::2]):
            a = "XYZ".index(axis)
            plane = 0.0 if side == "0" else size[a]
            want &= np.abs(grid_points[:, a] - plane) <= PLANE_TOL * size[a]
        got = np.zeros(len(grid_points), dtype=bool)
        got[np.asarray(ids)] = True
        check(np.array_equal(got, want), f"node set {name} is not the nodes on its planes")
    sets = [k for k in mesh.point_sets if k[:1] in "XYZ"]
    check(len(sets) == 26, f"{len(sets)} face/edge/corner node sets, not 26")
    grains = sum(1 for k in mesh.cell_sets if k.startswith("GRAIN_"))
    print(f"rve.inp: {len(conn)} C3D8 elements, {len(mesh.points)} nodes, {grains} grain sets, "
          f"{len(sets)} face/edge/corner node sets")
    return check.exit_code()


if __name__ == "__main__":
    sys.exit(main())
