#!/usr/bin/env python3
"""Checks what `pack` exported, with readers that share no code with it.

    python tools/check_exports.py OUT_DIR [--rve-fill grains|matrix]

OUT_DIR is a directory `pack` wrote. The grains of `grains.csv` are the reference;
`summary.json` gives the box and the phases.

- `grains.vtu`, read with meshio and with PyVista (VTK's own reader): one closed,
  outward-oriented surface per grain, its points on the ellipsoid of the CSV row, its
  cell data (`grain_id`, `phase`, `volume`, `equivalent_diameter`, `aspect_ratio`,
  `b_over_a`, `c_over_a`, `periodic_image`) present and equal to what the CSV gives. The mesh volume of every
  grain is the same fraction of its ellipsoid's (the map from the icosphere is
  affine), and that fraction is the one docs/config.md lists for the resolution.
  Periodic copies, if any, are their grain shifted by whole box lengths.
- `centers.vtp`, read with PyVista (meshio does not read VTK XML PolyData): one vertex
  per grain at the CSV centre, with the semi-axes and the tensors S = R diag(a) R^T and
  Q = S^2 of the CSV's quaternion.
- `rve.vti`, if present, read with DAMASK (`damask.GeomGrid.load`) and PyVista: a grid
  of the box's size in metres (the box in `summary.json`'s `units.length`, converted)
  at the origin, with integer cell data `material` and `phase`, x
  fastest. The voxel at each large grain's centre belongs to that grain. With
  `rve_fill = "grains"` every voxel belongs to a grain.
- `rve_grains.csv`, if the RVE is there: a row per grain whose voxel counts are those of
  `rve.vti`, and as many split grains as `summary.json` says.
- `statistics.png`, `sections.png`, `packing.png`, if present: PNGs that Pillow decodes
  whole.

A 2D run (`grains.csv` without `z`) has its grains.vtu and centers.vtp checked by
tools/exports_2d.py instead.

Exit code 0 when every check passes, 1 with the failures listed otherwise.
"""

import argparse
import csv
import json
import math
import os
import sys

import numpy as np

import exports_2d

# Units of length per metre, by summary.json's `units.length`.
PER_METRE = {"m": 1.0, "mm": 1e3, "um": 1e6, "nm": 1e9}

# Relative tolerance of figures computed two ways in double precision (the brief's
# 1e-9 for the equivalent diameter; rounding alone is ~1e-15).
REL = 1e-9

# docs/config.md: mesh volume / ellipsoid volume for each vtk_resolution (4 digits,
# so compared to 1e-4).
VOLUME_RATIO = {1: 0.8735, 2: 0.9662, 3: 0.9914, 4: 0.9978, 5: 0.9995, 6: 0.99986}
VOLUME_RATIO_TOL = 1e-4

# grains.vtu stores its points in single precision: a coordinate x is rounded by at
# most |x| * 2**-24, so a point's radius in its ellipsoid's units moves by at most
# sqrt(3) * max|x| * 2**-24 / (smallest semi-axis), and a volume by 3 times that.
F32_ROUNDING = 2.0**-24

VTU_ARRAYS = ["grain_id", "phase", "volume", "equivalent_diameter", "aspect_ratio",
              "b_over_a", "c_over_a", "periodic_image"]
VTP_ARRAYS = ["grain_id", "phase", "semi_axes", "shape_tensor", "quadratic_form"]

failures = []
passed = [0]


def check(ok, message):
    """Records a check, printing the message of a failed one; returns ok."""
    if ok:
        passed[0] += 1
    else:
        failures.append(message)
        print(f"FAIL: {message}")
    return ok


def close(a, b, rel=REL):
    """Whether a and b agree to rel, relative to the larger magnitude."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    return bool(np.all(np.abs(a - b) <= rel * np.maximum(np.abs(a), np.abs(b))))


def rotations(q):
    """Rotation matrices (n, 3, 3) of unit quaternions [w, x, y, z]; column k is
    semi-axis k."""
    w, x, y, z = q.T
    return np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], -1),
        np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], -1),
        np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], -1),
    ], 1)


def read_grains(out):
    with open(os.path.join(out, "grains.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    col = lambda *names: np.array([[float(r[n]) for n in names] for r in rows])
    g = {
        "id": np.array([int(r["id"]) for r in rows]),
        "phase": np.array([int(r["phase"]) for r in rows]),
        "centre": col("x", "y", "z"),
        "axes": col("a1", "a2", "a3"),
        "q": col("qw", "qx", "qy", "qz"),
    }
    g["R"] = rotations(g["q"])
    g["volume"] = 4 / 3 * math.pi * g["axes"].prod(1)
    return g


def check_vtu(path, g, box, n_phases):
    import meshio
    import pyvista as pv

    n = len(g["id"])
    mesh = meshio.read(path)
    check([b.type for b in mesh.cells] == ["triangle"], f"{path}: cells are not all triangles")
    tri = mesh.cells[0].data
    data = {k: np.asarray(v[0]) for k, v in mesh.cell_data.items()}
    if not check(all(k in data for k in VTU_ARRAYS), f"{path}: cell data {sorted(data)}"):
        return
    gid, image = data["grain_id"], data["periodic_image"]
    check(set(np.unique(image)) <= {0, 1}, "periodic_image not 0/1")
    own = image == 0
    check(np.array_equal(np.unique(gid[own]), g["id"]) and np.unique(gid).size == n,
          f"distinct grain_id ({np.unique(gid).size}) != rows of grains.csv ({n})")
    per_grain = np.bincount(gid[own], minlength=n)
    t = int(per_grain[0])
    level = round(math.log(t / 20, 4)) if t >= 20 else -1
    if not check(np.all(per_grain == t) and t == 20 * 4**level and level in VOLUME_RATIO,
                 f"triangles per grain {set(per_grain.tolist())} not 20*4^n, n in 1..6"):
        return
    # Each surface is a block of t triangles over its own points (grain, then copies).
    inst = np.arange(len(tri)) // t
    check(np.all(gid.reshape(-1, t) == gid[::t, None]), "grain_id varies within a surface")
    first = gid[::t]
    sorted_axes = -np.sort(-g["axes"], axis=1)  # a >= b >= c
    for name, want in [("phase", g["phase"]), ("volume", g["volume"]),
                       ("equivalent_diameter", (6 * g["volume"] / math.pi) ** (1 / 3)),
                       ("aspect_ratio", g["axes"][:, 0] / g["axes"][:, 1]),
                       ("b_over_a", sorted_axes[:, 1] / sorted_axes[:, 0]),
                       ("c_over_a", sorted_axes[:, 2] / sorted_axes[:, 0])]:
        check(close(data[name], want[gid]), f"cell data {name} differs from grains.csv")
    check(np.all(data["volume"] > 0), "a volume is not positive")
    check(np.all((data["phase"] >= 0) & (data["phase"] < n_phases)), "phase out of range")

    # Points on their ellipsoid: |diag(1/a) R^T (x - c)| = 1. A copy is shifted back
    # by the whole box lengths it was moved by.
    pts = np.asarray(mesh.points, dtype=float)
    check(mesh.points.dtype == np.float32, f"grains.vtu points are {mesh.points.dtype}")
    on_surface = math.sqrt(3) * np.abs(pts).max() * F32_ROUNDING / g["axes"].min()
    pts_per = pts.shape[0] // len(first)
    if not check(pts_per * len(first) == pts.shape[0] and tri.max() < pts.shape[0],
                 "surfaces do not have their own, equally many points"):
        return
    p = pts.reshape(len(first), pts_per, 3)
    shift = np.round((p.mean(1) - g["centre"][first]) / box) * box
    check(np.all((shift == 0).all(1) == (image[::t] == 0)),
          "a copy is not shifted by whole box lengths, or a grain is")
    local = np.einsum("gpi,gik->gpk", p - shift[:, None] - g["centre"][first][:, None],
                      g["R"][first]) / g["axes"][first][:, None]
    radius = np.linalg.norm(local, axis=2)
    check(np.all(np.abs(radius - 1) <= on_surface),
          f"points off their ellipsoid by {np.abs(radius - 1).max():.2e} > {on_surface:.2e}")

    # Closed and consistently oriented: every directed edge once, its reverse once.
    edges = np.concatenate([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]])
    key = edges[:, 0].astype(np.int64) * len(pts) + edges[:, 1]
    rev = edges[:, 1].astype(np.int64) * len(pts) + edges[:, 0]
    check(np.unique(key).size == key.size and np.array_equal(np.sort(key), np.sort(rev)),
          "a surface is open or not consistently oriented")
    # Outward: the signed volume (divergence theorem) of each surface is positive.
    # About each surface's centre, so that the sum does not cancel large coordinates.
    centred = pts - g["centre"][first].repeat(pts_per, axis=0) - shift.repeat(pts_per, axis=0)
    a, b, c = (centred[tri[:, k]] for k in range(3))
    signed = np.bincount(inst, np.einsum("ij,ij->i", a, np.cross(b, c)) / 6)
    ratio = signed / g["volume"][first]
    check(np.all(ratio > 0), "a surface faces inwards")
    check(close(ratio, ratio[0], 3 * on_surface), "mesh/ellipsoid volume differs between grains")
    check(abs(ratio[0] - VOLUME_RATIO[level]) < VOLUME_RATIO_TOL,
          f"mesh/ellipsoid volume {ratio[0]:.5f}, docs say {VOLUME_RATIO[level]} at level {level}")
    mesh_total = signed[image[::t] == 0].sum()
    print(f"grains.vtu (meshio): {n} grains, {int((image[::t] == 1).sum())} periodic copies, "
          f"level {level} ({t} triangles each), mesh volume {mesh_total:.6g} = "
          f"{ratio[0]:.5f} x ellipsoids {g['volume'].sum():.6g}")

    grid = pv.read(path)
    check(grid.n_cells == len(tri) and grid.n_points == len(pts), "PyVista counts differ")
    check(all(k in grid.cell_data for k in VTU_ARRAYS), "PyVista cell data missing")
    check(np.array_equal(np.asarray(grid.cell_data["grain_id"]), gid), "PyVista grain_id differs")
    check(np.array_equal(np.asarray(grid.points), pts), "PyVista points differ")
    open_edges = 0
    for k in range(len(first)):
        cells = np.arange(k * t, (k + 1) * t)
        surface = grid.extract_cells(cells).extract_surface(algorithm="dataset_surface")
        open_edges += surface.n_open_edges
    check(open_edges == 0, f"PyVista: {open_edges} open edges over the grain surfaces")
    whole = grid.extract_surface(algorithm="dataset_surface")
    check(close(whole.volume, signed.sum()), f"PyVista volume {whole.volume} != {signed.sum()}")
    print(f"grains.vtu (PyVista): every grain surface closed, volume {whole.volume:.6g} "
          "with copies")


def check_vtp(path, g):
    import pyvista as pv

    n = len(g["id"])
    poly = pv.read(path)
    check(poly.n_points == n and poly.n_verts == n, f"{path}: {poly.n_points} points for {n} grains")
    if not check(all(k in poly.point_data for k in VTP_ARRAYS),
                 f"{path}: point data {list(poly.point_data.keys())}"):
        return
    d = {k: np.asarray(poly.point_data[k]) for k in VTP_ARRAYS}
    check(np.array_equal(np.asarray(poly.points), g["centre"]), "points != CSV centres")
    check(np.array_equal(d["grain_id"], g["id"]), "grain_id != CSV ids")
    check(np.array_equal(d["phase"], g["phase"]), "phase != CSV phases")
    check(np.array_equal(d["semi_axes"], g["axes"]), "semi_axes != CSV semi-axes")
    R, a = g["R"], g["axes"]
    S = np.einsum("nik,nk,njk->nij", R, a, R)
    Q = np.einsum("nik,nk,njk->nij", R, a * a, R)
    scale = a.max(1)[:, None, None]
    check(np.all(np.abs(d["shape_tensor"].reshape(-1, 3, 3) - S) <= REL * scale),
          "shape_tensor != R diag(a) R^T")
    check(np.all(np.abs(d["quadratic_form"].reshape(-1, 3, 3) - Q) <= REL * scale**2),
          "quadratic_form != R diag(a^2) R^T")
    eig = np.linalg.eigvalsh(d["shape_tensor"].reshape(-1, 3, 3))
    check(np.all(np.abs(eig - np.sort(a, 1)) <= REL * scale[:, :, 0]),
          "shape_tensor eigenvalues != semi-axes")
    print(f"centers.vtp (PyVista): {n} points at the CSV centres, tensors agree")


def check_vti(path, g, box, n_phases, fill, unit):
    import damask
    import pyvista as pv

    n = len(g["id"])
    grid = damask.GeomGrid.load(path)
    cells = np.array(grid.cells)
    material = np.asarray(grid.material)
    metres = box / PER_METRE[unit]
    check(close(grid.size, metres, 1e-12), f"RVE size {grid.size} m != box {box} {unit} = {metres} m")
    check(np.all(np.asarray(grid.origin) == 0), f"RVE origin {grid.origin} != 0")
    # DAMASK reads other cell data as floats: the types come from PyVista.
    mesh = pv.read(path)
    check(tuple(np.array(mesh.dimensions) - 1) == tuple(cells), "PyVista dimensions differ")
    if not check(all(k in mesh.cell_data for k in ("material", "phase")),
                 f"cell data {list(mesh.cell_data.keys())}, want material and phase"):
        return
    for name in ("material", "phase"):
        dtype = mesh.cell_data[name].dtype
        check(np.issubdtype(dtype, np.integer), f"{name} is {dtype}, not an integer")
    check(np.array_equal(np.asarray(mesh.cell_data["material"]), material.ravel(order="F")),
          "PyVista and DAMASK read different materials")
    phase = np.asarray(mesh.cell_data["phase"]).reshape(tuple(cells), order="F")
    extra = 0 if fill == "grains" else 1  # the matrix
    check(grid.N_materials <= n + extra, f"{grid.N_materials} materials for {n} grains")
    check(material.min() >= 0 and phase.min() >= 0, "a voxel has a negative material or phase")
    check(phase.max() < n_phases + extra, f"phase {phase.max()} for {n_phases} phases")
    # x fastest, spacing L/N: the voxel at the centre of a grain that holds the voxel's
    # whole half-diagonal belongs to it, under one numbering offset for all grains.
    h = box / cells  # in the scene's unit, as the CSV's centres
    big = np.flatnonzero(g["axes"].min(1) > 0.5 * np.linalg.norm(h))
    ijk = np.minimum((g["centre"][big] / h).astype(int), cells - 1)
    at = material[ijk[:, 0], ijk[:, 1], ijk[:, 2]]
    offsets = np.unique(at - g["id"][big])
    phase_offsets = np.unique(phase[ijk[:, 0], ijk[:, 1], ijk[:, 2]] - g["phase"][big])
    if big.size == 0:
        print("rve.vti: no grain holds a whole voxel; centre voxels not checked")
    check(offsets.size <= 1 and phase_offsets.size <= 1,
          f"centre voxels of {big.size} grains hold their grain under material offsets "
          f"{offsets[:5]}, phase offsets {phase_offsets[:5]} (one each expected)")
    if fill == "grains":
        # No voxel is left over: at most one material per grain, none for a matrix.
        used = np.unique(material) - (offsets[0] if offsets.size else 0)
        check(np.all((used >= 0) & (used < n)), "a voxel belongs to no grain (fill = grains)")
    print(f"rve.vti (DAMASK): {tuple(cells.tolist())} cells, {grid.N_materials} materials, fill {fill}")


def check_rve_grains(path, rve, g, summary):
    """rve_grains.csv: a row per grain whose voxel counts are those of rve.vti."""
    import pyvista as pv
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    check([int(r["id"]) for r in rows] == list(g["id"]), f"{path}: ids differ from grains.csv")
    material = np.asarray(pv.read(rve).cell_data["material"])
    counts = np.bincount(material, minlength=len(rows))
    check(all(int(r["voxels"]) == counts[i] for i, r in enumerate(rows)),
          f"{path}: voxel counts differ from rve.vti")
    check(all(int(r["pieces"]) >= (1 if int(r["voxels"]) else 0) for r in rows),
          f"{path}: a grain with voxels has no piece")
    split = sum(int(r["pieces"]) > 1 for r in rows)
    check(split == summary["rve"]["split_grains"], f"{path}: {split} split grains, summary says otherwise")
    print(f"rve_grains.csv: {len(rows)} grains, voxel counts as in rve.vti, {split} split")


def check_png(path):
    """A PNG that Pillow decodes whole."""
    from PIL import Image
    with Image.open(path) as im:
        im.load()
        check(im.size[0] > 100 and im.size[1] > 100, f"{path}: {im.size} pixels")
    print(f"{os.path.basename(path)} (Pillow): {im.size[0]}x{im.size[1]}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("out", help="a directory pack wrote")
    parser.add_argument("--rve-fill", choices=["grains", "matrix"],
                        help="the scene's rve_fill (default: summary.json's, else grains)")
    args = parser.parse_args()
    out = args.out
    plane = exports_2d.is_2d(out)
    g = exports_2d.read_grains(out) if plane else read_grains(out)
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    box = np.array(summary["box"], float)
    n_phases = len(summary["phases"])
    check(len(g["id"]) == summary["grains"], "grains.csv rows != summary grains")
    check(np.array_equal(g["id"], np.arange(len(g["id"]))), "ids are not 0, 1, ...")
    checks = [("grains.vtu", lambda p: check_vtu(p, g, box, n_phases)),
              ("centers.vtp", lambda p: check_vtp(p, g))]
    if plane:
        checks = [("grains.vtu", lambda p: exports_2d.check_vtu(p, g, box, check, close)),
                  ("centers.vtp", lambda p: exports_2d.check_vtp(p, g, check, close))]
    for name, run in checks:
        path = os.path.join(out, name)
        if check(os.path.exists(path), f"{path} missing"):
            run(path)
    rve = os.path.join(out, "rve.vti")
    if plane:
        print("rve.vti: a 2D run's grid is checked by its own tools, not here")
    elif os.path.exists(rve):
        fill = args.rve_fill or summary.get("rve", {}).get("fill", "grains")
        check_vti(rve, g, box, n_phases, fill, summary["units"]["length"])
    else:
        print("rve.vti: not written, not checked")
    table = os.path.join(out, "rve_grains.csv")
    if not plane and os.path.exists(rve) and check(os.path.exists(table), f"{table} missing"):
        check_rve_grains(table, rve, g, summary)
    for name in ["statistics.png", "sections.png", "packing.png"]:
        path = os.path.join(out, name)
        if os.path.exists(path):
            check_png(path)
    print(f"check_exports: {passed[0]} passed, {len(failures)} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
