#!/usr/bin/env python3
"""Checks the Abaqus/CalculiX deck `pack` wrote (`[output] abaqus = true`) with meshio.

    python tools/check_abaqus.py OUT_DIR

- `rve.inp`, read by meshio: Nx·Ny·Nz hexahedra (C3D8) on the cells of `rve.vti`
  (read by `damask.GeomGrid.load`), (Nx+1)(Ny+1)(Nz+1) grid nodes and 3 reference
  nodes; every element of the set GRAIN_k has its centre in a voxel of material k, and
  the set's size is that grain's voxel count in `rve_grains.csv`; the phase sets
  partition the elements; the 26 face, edge and corner node sets hold the nodes on
  their planes and no others.

A 2D RVE (the summary's `rve.layer_thickness`): Nx·Ny quadrilaterals (CPE4) on the
pixels, (Nx+1)(Ny+1) nodes in the plane and 2 reference nodes, the 8 edge and corner
node sets.

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
    # meshio 5.3.5 knows the plane-stress quadrilateral CPS4 but not the plane-strain
    # CPE4, the same four-node quadrilateral: register it under the same cell type.
    import meshio.abaqus._abaqus as abaqus_reader
    abaqus_reader.abaqus_to_meshio_type.setdefault("CPE4", "quad")
    check = Checklist(__doc__)
    out, summary = check.out, check.summary
    mesh = meshio.read(os.path.join(out, "rve.inp"), file_format="abaqus")
    grid = damask.GeomGrid.load(os.path.join(out, "rve.vti"))
    plane = summary["rve"].get("layer_thickness") is not None
    axes = 2 if plane else 3
    n = np.array(grid.cells)[:axes]
    size = np.array(summary["box"][:axes], dtype=float)
    kind = "quad" if plane else "hexahedron"
    hexes = [c for c in mesh.cells if c.type == kind]
    check(len(hexes) == 1 and len(hexes[0].data) == n.prod(), f"not {n.prod()} cells of type {kind}")
    want_points = (n + 1).prod() + axes
    check(len(mesh.points) == want_points, f"{len(mesh.points)} nodes, not {want_points}")
    check(mesh.points.shape[1] == axes, f"nodes have {mesh.points.shape[1]} coordinates, not {axes}")
    conn = hexes[0].data
    centres = mesh.points[conn].mean(axis=1)
    ijk = np.floor(centres / (size / n)).astype(int)
    if plane:
        ijk = np.hstack([ijk, np.zeros((len(ijk), 1), dtype=int)])
    # DAMASK's material array is indexed [x, y, z].
    material = grid.material[ijk[:, 0], ijk[:, 1], ijk[:, 2]]
    # The grains' voxel counts: rve_grains.csv's, or (a set written without it)
    # rve.vti's own.
    table = os.path.join(out, "rve_grains.csv")
    if os.path.exists(table) or not plane:
        with open(table) as f:
            voxels = {int(r["id"]): int(r["voxels"]) for r in csv.DictReader(f)}
    else:
        voxels = dict(enumerate(np.bincount(grid.material.reshape(-1))))
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
            at = 0.0 if side == "0" else size[a]
            want &= np.abs(grid_points[:, a] - at) <= PLANE_TOL * size[a]
        got = np.zeros(len(grid_points), dtype=bool)
        got[np.asarray(ids)] = True
        check(np.array_equal(got, want), f"node set {name} is not the nodes on its planes")
    sets = [k for k in mesh.point_sets if k[:1] in "XYZ"]
    want_sets = 8 if plane else 26
    check(len(sets) == want_sets, f"{len(sets)} face/edge/corner node sets, not {want_sets}")
    grains = sum(1 for k in mesh.cell_sets if k.startswith("GRAIN_"))
    print(f"rve.inp: {len(conn)} {'CPE4' if plane else 'C3D8'} elements, {len(mesh.points)} nodes, {grains} grain sets, "
          f"{len(sets)} face/edge/corner node sets")
    return check.exit_code()


if __name__ == "__main__":
    sys.exit(main())
