#!/usr/bin/env python3
"""Checks the mesher's surface repairs (src/io/mesh/mesh_surface.py) on the two grains
of issue 29's 500-grain failure, with gmsh itself.

    python tools/check_mesh_repairs.py

Needs gmsh (the pinned one of tools/requirements-exports.txt). The geometries in
tests/data/mesh_repair/ are two grains cut from that packing's geometry (BREP, as
build_geometry made it), each grain's two pieces with the pair of box-face pieces
that setPeriodic ties:

- shallow_cut: a grain that crosses a box face by a sliver; its big piece's curved
  surface and the face piece copied from the other side held the same triangles,
  which HXT refuses ("two overlapping facets");
- invalid_surface: a grain piece's curved surface that gmsh leaves with invalid
  triangles; recovering its edges splits a curve whose periodic copy then mismatches.

For each: meshed without repairs, gmsh fails as it did in the packing (so the data
still shows the failure with this gmsh); with them, the repairs named are of the kind
expected and the 3D mesh has tetrahedra. A few seconds. Exit code 0 when both pass.
"""

import gzip
import os
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "src", "io", "mesh"))
from mesh_surface import surface_mesh  # noqa: E402

import gmsh  # noqa: E402

DATA = os.path.join(HERE, "..", "tests", "data", "mesh_repair")
# The packing's element size (mesh_size 0.3 of its smallest grain).
ELEMENT_SIZE = 0.7519447712740592
# A face piece is flat along an axis when its bounding box is thinner than this (OCC
# inflates bounding boxes by up to 2.7e-5; issue 29).
FLAT_TOL = 1e-3
# case: (the axis its face pieces are on, gmsh's failure without repairs, a word of
# each repair expected)
CASES = {
    "shallow_cut": (1, "HXT 3D mesh failed", ["nodes on curve"]),
    "invalid_surface": (2, "whereas correspondant", ["Delaunay on surface"]),
}


def mesh(path, axis, repaired):
    """(repairs, error or None, tetrahedra) of one geometry meshed."""
    gmsh.initialize(["check_mesh_repairs"], readConfigFiles=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("Mesh.MeshSizeMax", ELEMENT_SIZE)
        gmsh.option.setNumber("Mesh.Algorithm3D", 10)
        gmsh.logger.start()
        gmsh.model.occ.importShapes(path)
        gmsh.model.occ.synchronize()
        flat = []
        for _, s in gmsh.model.getEntities(2):
            box = gmsh.model.getBoundingBox(2, s)
            if box[axis + 3] - box[axis] < FLAT_TOL:
                flat.append((box[axis], s))
        (low, master), (high, slave) = sorted(flat)
        affine = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]
        affine[4 * axis + 3] = high - low
        gmsh.model.mesh.setPeriodic(2, [slave], [master], affine)
        repairs = []
        try:
            if repaired:
                repairs = surface_mesh(gmsh)
            gmsh.model.mesh.generate(3)
        except Exception as e:  # gmsh raises plain Exception
            return repairs, str(e), 0
        return repairs, None, sum(len(t) for t in gmsh.model.mesh.getElements(3)[1])
    finally:
        gmsh.finalize()


def main():
    failures = []
    with tempfile.TemporaryDirectory() as work:
        for name, (axis, failure, kinds) in CASES.items():
            path = os.path.join(work, f"{name}.brep")
            with gzip.open(os.path.join(DATA, f"{name}.brep.gz"), "rb") as f, \
                    open(path, "wb") as out:
                out.write(f.read())
            _, error, _ = mesh(path, axis, repaired=False)
            if error is None or failure not in error:
                failures.append(f"{name}: without repairs gmsh gave {error!r}, "
                                f"not {failure!r}")
            repairs, error, tets = mesh(path, axis, repaired=True)
            print(f"{name}: {tets} tetrahedra after the repairs {repairs}")
            if error is not None or tets == 0:
                failures.append(f"{name}: repaired, gmsh gave {error!r}")
            for kind in kinds:
                if not any(kind in r for r in repairs):
                    failures.append(f"{name}: no repair {kind!r} in {repairs}")
    for f in failures:
        print("FAILED:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
