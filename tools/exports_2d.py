"""The checks of tools/check_exports.py for a 2D run (ellipses in a rectangle).

`grains.csv` has the columns `id,phase,x,y,a1,a2,angle` (angle in degrees from x).

- `grains.vtu`, read with meshio and PyVista: one polygon (VTK_POLYGON) per ellipse and
  per periodic copy, of 8·2^n vertices (n = vtk_resolution) on the ellipse of the CSV
  row at z = 0, counter-clockwise, enclosing the inscribed polygon's share
  (n/2π)·sin(2π/n) of the ellipse's area; cell data equal to what the CSV gives.
- `centers.vtp`, read with PyVista: one vertex per grain at (x, y, 0), semi-axes
  (a1, a2, 0), and the flat tensors R diag(a1, a2, 0) R^T and its square.
"""

import csv
import math
import os

import numpy as np

VTU_ARRAYS = ["grain_id", "phase", "area", "equivalent_diameter", "aspect_ratio", "angle",
              "periodic_image"]
VTP_ARRAYS = ["grain_id", "phase", "semi_axes", "shape_tensor", "quadratic_form"]

# grains.vtu's points are single precision: a coordinate x moves by at most |x| 2**-24.
F32_ROUNDING = 2.0**-24

# VTK's cell type of a polygon.
VTK_POLYGON = 7


def is_2d(out):
    """Whether grains.csv has the 2D columns."""
    with open(os.path.join(out, "grains.csv"), newline="") as f:
        return "z" not in next(csv.reader(f))


def read_grains(out):
    with open(os.path.join(out, "grains.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    col = lambda *names: np.array([[float(r[n]) for n in names] for r in rows])
    theta = np.radians(col("angle")[:, 0])
    c, s = np.cos(theta), np.sin(theta)
    return {
        "id": np.array([int(r["id"]) for r in rows]),
        "phase": np.array([int(r["phase"]) for r in rows]),
        "centre": col("x", "y"),
        "axes": col("a1", "a2"),
        "angle": col("angle")[:, 0],
        # Column k: the direction of semi-axis k.
        "R": np.stack([np.stack([c, -s], -1), np.stack([s, c], -1)], 1),
    }


def check_vtu(path, g, box, check, close):
    import meshio
    import pyvista as pv

    mesh = meshio.read(path)
    check([b.type for b in mesh.cells] == ["polygon"], f"{path}: cells {[b.type for b in mesh.cells]}")
    poly = mesh.cells[0].data
    cells, m = poly.shape
    level = round(math.log2(m / 8)) if m >= 8 else -1
    if not check(m == 8 * 2**level and 1 <= level <= 6, f"{m} vertices per polygon, not 8*2^n"):
        return
    data = {k: np.asarray(v[0]) for k, v in mesh.cell_data.items()}
    if not check(all(k in data for k in VTU_ARRAYS), f"{path}: cell data {sorted(data)}"):
        return
    gid, image = data["grain_id"], data["periodic_image"]
    check(np.array_equal(gid[image == 0], g["id"]), "the polygons' grain_id != the CSV's ids")
    a = g["axes"]
    for name, want in [("phase", g["phase"]), ("area", math.pi * a.prod(1)),
                       ("equivalent_diameter", 2 * np.sqrt(a.prod(1))),
                       ("aspect_ratio", a[:, 0] / a[:, 1]), ("angle", g["angle"])]:
        check(close(data[name], want[gid]), f"cell data {name} differs from grains.csv")

    pts = np.asarray(mesh.points, dtype=float)
    check(mesh.points.dtype == np.float32, f"grains.vtu points are {mesh.points.dtype}")
    check(np.all(pts[:, 2] == 0), "a point is off the plane z = 0")
    p = pts[poly][:, :, :2]
    centre = g["centre"][gid]
    shift = np.round((p.mean(1) - centre) / box[:2]) * box[:2]
    check(np.all((shift == 0).all(1) == (image == 0)),
          "a copy is not shifted by whole box lengths, or a grain is")
    local = np.einsum("gpi,gik->gpk", p - shift[:, None] - centre[:, None], g["R"][gid])
    radius = np.linalg.norm(local / a[gid][:, None], axis=2)
    on_curve = math.sqrt(2) * np.abs(pts).max() * F32_ROUNDING / a.min()
    check(np.all(np.abs(radius - 1) <= on_curve),
          f"points off their ellipse by {np.abs(radius - 1).max():.2e} > {on_curve:.2e}")
    # Counter-clockwise (shoelace area positive), the inscribed polygon's share.
    q = p - p.mean(1, keepdims=True)
    signed = 0.5 * (q[:, :, 0] * np.roll(q[:, :, 1], -1, 1) - np.roll(q[:, :, 0], -1, 1) * q[:, :, 1]).sum(1)
    ratio = signed / (math.pi * a.prod(1)[gid])
    share = m / (2 * math.pi) * math.sin(2 * math.pi / m)
    check(np.all(np.abs(ratio - share) < 1e-5), f"polygon/ellipse area {ratio.min():.6f}..{ratio.max():.6f}, "
          f"want {share:.6f}")
    print(f"grains.vtu (meshio): {len(g['id'])} ellipses, {int((image == 1).sum())} periodic copies, "
          f"{m} vertices each, counter-clockwise, area {share:.5f} x the ellipses'")

    grid = pv.read(path)
    check(grid.n_cells == cells and grid.n_points == len(pts), "PyVista counts differ")
    check(np.all(np.asarray(grid.celltypes) == VTK_POLYGON), "PyVista: cells are not polygons")
    check(all(k in grid.cell_data for k in VTU_ARRAYS), "PyVista cell data missing")
    check(np.array_equal(np.asarray(grid.points), pts), "PyVista points differ")
    sizes = np.asarray(grid.compute_cell_sizes(length=False, volume=False).cell_data["Area"])
    check(close(sizes, signed, 1e-6), "PyVista's polygon areas differ from the shoelace areas")
    print(f"grains.vtu (PyVista): {grid.n_cells} polygons, area {sizes.sum():.6g}")


def check_vtp(path, g, check, close):
    import pyvista as pv

    n = len(g["id"])
    poly = pv.read(path)
    check(poly.n_points == n and poly.n_verts == n, f"{path}: {poly.n_points} points for {n} grains")
    if not check(all(k in poly.point_data for k in VTP_ARRAYS),
                 f"{path}: point data {list(poly.point_data.keys())}"):
        return
    d = {k: np.asarray(poly.point_data[k]) for k in VTP_ARRAYS}
    flat = lambda x: np.column_stack([x, np.zeros(n)])
    check(np.array_equal(np.asarray(poly.points), flat(g["centre"])), "points != (x, y, 0)")
    check(np.array_equal(d["grain_id"], g["id"]), "grain_id != CSV ids")
    check(np.array_equal(d["semi_axes"], flat(g["axes"])), "semi_axes != (a1, a2, 0)")
    R, a = g["R"], g["axes"]
    S = np.zeros((n, 3, 3))
    S[:, :2, :2] = np.einsum("nik,nk,njk->nij", R, a, R)
    scale = a.max(1)[:, None, None]
    check(np.all(np.abs(d["shape_tensor"].reshape(-1, 3, 3) - S) <= 1e-9 * scale),
          "shape_tensor != R diag(a1, a2, 0) R^T")
    check(np.all(np.abs(d["quadratic_form"].reshape(-1, 3, 3) - S @ S) <= 1e-9 * scale**2),
          "quadratic_form != its square")
    print(f"centers.vtp (PyVista): {n} points at (x, y, 0), flat tensors agree")
