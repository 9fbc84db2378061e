#!/usr/bin/env python3
"""The spheres of a periodic packing `pack` wrote, meshed by gmshModel (PyPI gmshModel,
NEFM-TUDresden), for BENCHMARKS.md's side by side with `[output] mesh = true`.

    VENV/bin/python tools/bench_gmshmodel.py OUT [--threads 1]

OUT is the output directory of a periodic scene of spheres run with `mesh = true`
(grains.csv, summary.json). gmshModel's RandomInclusionRVE places spheres by its own
random sequential addition; here its placement is replaced by OUT's spheres (with --own, gmshModel places
as many spheres of their radius in the same box itself), moved
into the window `pack` meshed (summary.json's mesh.origin, so neither mesher meets
thin caps) with their periodic images, and meshed at pack's element size
(mesh.element_size as gmshModel's maxMeshSize, its own refinements off). Prints
gmshModel's time, tetrahedra, nodes, min and 1st-percentile SICN, whether every node
of a far face has a partner on the near one (to 1e-9 L; numpy and scipy), beside
pack's figures.
"""

import argparse
import csv
import json
import os
import time

import gmsh  # the module gmshModel drives
import numpy as np
from gmshModel.Model import RandomInclusionRVE
from scipy.spatial import cKDTree

PERIODIC_TOL = 1e-9  # as tools/check_mesh.py
ON_FACE_TOL = 1e-7


class GivenSpheresRVE(RandomInclusionRVE):
    """RandomInclusionRVE with the spheres (and their images) given, not placed."""

    def __init__(self, info, **kwargs):
        super().__init__(**kwargs)
        self.given = info

    def placeInclusions(self, placementOptions):
        if self.given is None:  # --own: gmshModel's random sequential addition
            super().placeInclusions(placementOptions)
        else:
            self.inclusionInfo = self.given


def spheres(out, summary):
    size = np.array(summary["box"])
    origin = np.array(summary["mesh"]["origin"])
    rows = []
    with open(os.path.join(out, "grains.csv")) as f:
        for g in csv.DictReader(f):
            r = float(g["a1"])
            if abs(float(g["a3"]) / r - 1.0) > 1e-12:
                raise SystemExit(f"{out}: grain {g['id']} is not a sphere")
            c = np.array([float(g["x"]), float(g["y"]), float(g["z"])])
            c = origin + np.mod(c - origin, size)  # into the window
            shifts = [[s for s in (-size[d], 0.0, size[d])
                       if c[d] + s + r > origin[d] and c[d] + s - r < origin[d] + size[d]]
                      for d in range(3)]
            for sx in shifts[0]:
                for sy in shifts[1]:
                    for sz in shifts[2]:
                        rows.append([c[0] + sx - origin[0], c[1] + sy - origin[1],
                                     c[2] + sz - origin[2], r])
    return np.array(rows), size


def periodic_mismatch(gmsh, size):
    _, xyz, _ = gmsh.model.mesh.getNodes()
    p = np.asarray(xyz).reshape(-1, 3)
    length = size.max()
    worst, counts = 0.0, []
    for d in range(3):
        near = p[np.abs(p[:, d]) < ON_FACE_TOL * length]
        far = p[np.abs(p[:, d] - size[d]) < ON_FACE_TOL * length]
        counts.append((len(near), len(far)))
        shift = np.zeros(3)
        shift[d] = size[d]
        if len(near) and len(far):
            worst = max(worst, cKDTree(near).query(far - shift)[0].max(),
                        cKDTree(far).query(near + shift)[0].max())
    return worst / length, counts


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("out")
    parser.add_argument("--threads", type=int, default=1)
    parser.add_argument("--own", action="store_true", help="let gmshModel place as many "
                        "spheres of the same radius in the same box itself")
    parser.add_argument("--refine", action="store_true", help="gmshModel's own refinements "
                        "on (finer elements on and between the spheres)")
    args = parser.parse_args()
    with open(os.path.join(args.out, "summary.json")) as f:
        summary = json.load(f)
    info, size = spheres(args.out, summary)
    h = summary["mesh"]["element_size"]
    sets = [info[0, 3], summary["grains"]]
    started = time.time()
    rve = GivenSpheresRVE(None if args.own else info, inclusionSets=sets, size=size.tolist(),
                          inclusionType="Sphere", origin=[0, 0, 0],
                          periodicityFlags=[1, 1, 1],
                          gmshConfigChanges={"General.Terminal": 0})
    rve.createGmshModel()
    geometry = time.time() - started
    rve.createMesh(threads=args.threads,
                   refinementOptions={"maxMeshSize": h, "inclusionRefinement": args.refine,
                                      "interInclusionRefinement": args.refine})
    meshing = time.time() - started - geometry
    types, tags, _ = gmsh.model.mesh.getElements(3)
    tets = [t for ty, ts in zip(types, tags) if ty in (4, 11) for t in ts]
    q = np.sort(gmsh.model.mesh.getElementQualities(tets, "minSICN"))
    mismatch, counts = periodic_mismatch(gmsh, size)
    m = summary["mesh"]
    placed = "its own placement" if args.own else f"{len(info)} spheres and images"
    print(f"gmshModel ({placed}): element size {h:.4f}: geometry "
          f"{geometry:.1f} s, meshing {meshing:.1f} s, {len(tets)} tetrahedra, "
          f"{len(gmsh.model.mesh.getNodes()[0])} nodes, min SICN {q[0]:.3f}, 1st pct "
          f"{q[int(0.01 * (len(q) - 1))]:.3f}; far/near face nodes {counts}, worst "
          f"mismatch {mismatch:.1e} L ({'periodic' if mismatch <= PERIODIC_TOL else 'NOT periodic'}"
          f" to {PERIODIC_TOL:.0e} L)")
    print(f"pack:      {summary['grains']} spheres: geometry {m['geometry_seconds']:.1f} s, "
          f"meshing {m['mesh_seconds']:.1f} s, {m['elements']} tetrahedra, {m['nodes']} "
          f"nodes, min SICN {m['min_sicn']:.3f}, 1st pct {m['p1_sicn']:.3f}")
    rve.close()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
