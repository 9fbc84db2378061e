#!/usr/bin/env python3
"""Checks the DAMASK input set `pack` wrote (`[output] damask = true`) with DAMASK's
own Python package (damask, pinned in tools/requirements-exports.txt).

    python tools/check_damask.py OUT_DIR

- `material.yaml`: `damask.ConfigMaterial.load` gives a complete and valid
  configuration; its number of materials is `summary.json`'s `rve.materials` and covers
  every id of `rve.vti` (read by `damask.GeomGrid.load`, whose cells are the summary's
  and whose size is the summary's box converted to metres from its `units.length`);
  every isotropic Hooke phase written from `[phase.elastic]` has C_11 in pascals
  (at least STIFFNESS_PA_MIN); entry k has grain k's phase (grains.csv) and its orientation `O` equals the
  CSV's o0..o3 and DAMASK's own quaternion of the CSV's Bunge Euler angles
  (`damask.Rotation.from_Euler_angles`, degrees) to ORIENTATION_TOL; the matrix, if
  any, is last.
- `rve.vti` as DAMASK reads it: `damask.VTK.load` sees its cell arrays, and the
  `material` array equals `GeomGrid.load`'s (x fastest); when the run wrote
  orientations, the scalar arrays `phi1`, `Phi`, `phi2` hold each cell's material's
  Bunge angles: the CSV's phi1, Phi, phi2 for a grain, exactly, 0 for the matrix; no
  array has more than one component (damask 3.0.x's `GeomGrid.load` reshapes each
  to the cells). Each
  array's base64 text is alone on the line after its `<DataArray>` tag, the layout
  DAMASK's Fortran reader (src/grid/VTI.f90, `VTI_readDataset_raw`) takes.
- `centers.vtp` and `grains.vtu` (PyVista): the point data and cell data
  `crystal_quaternion` and `euler_angles` are the CSV's, exactly.
- `load.yaml`: `damask.LoadcaseGrid.load` reads it, with one load step.
- A 2D RVE (the summary's `rve.layer_thickness`): `rve.vti` has one cell along z, its
  size is the rectangle's and the layer's thickness; the load step holds F_zz (plane
  strain, no rate and no stress condition on zz); `centers.vtp` and `grains.vtu` are
  checked when present.

Exit code 0 when every check passes, 1 with the failures listed otherwise.
"""

import csv
import os
import sys

import damask
import numpy as np
from checklist import Checklist

# The brief's agreement of orientations with DAMASK's (the Euler angles are printed with
# 17 significant digits, so the conversion's rounding, ~1e-16, is all that differs).
ORIENTATION_TOL = 1e-12
# Box size from the grid's spacing × cells, against the summary's (printed to 17 digits).
SIZE_TOL = 1e-12
# Units of length per metre, by summary.json's `units.length`.
PER_METRE = {"m": 1.0, "mm": 1e3, "um": 1e6, "nm": 1e9}
# The least C_11 a crystal's Hooke phase has in pascals: caesium's is 2.5 GPa, so a
# value below 1e8 was left in MPa or GPa (as DAMASK would read it as pascals).
STIFFNESS_PA_MIN = 1e8
# Characters of base64 text.
BASE64 = set("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/=")


def main():
    check = Checklist(__doc__)
    out, summary = check.out, check.summary
    with open(os.path.join(out, "grains.csv")) as f:
        grains = list(csv.DictReader(f))
    cfg = damask.ConfigMaterial.load(os.path.join(out, "material.yaml"))
    check(cfg.is_complete, "material.yaml is not complete for DAMASK")
    check(cfg.is_valid, "material.yaml is not valid for DAMASK")
    grid = damask.GeomGrid.load(os.path.join(out, "rve.vti"))
    rve = summary["rve"]
    check(list(grid.cells) == rve["cells"], f"rve.vti cells {grid.cells} != {rve['cells']}")
    unit = summary["units"]["length"]
    thickness = rve.get("layer_thickness")
    plane = thickness is not None
    box = [*summary["box"][:2], thickness] if plane else summary["box"]
    check(not plane or rve["cells"][2] == 1, f"2D rve.vti with {rve['cells'][2]} cells along z")
    metres = np.array(box, dtype=float) / PER_METRE[unit]
    check(np.allclose(grid.size, metres, rtol=SIZE_TOL, atol=0),
          f"rve.vti size {grid.size} m != box {box} {unit} = {metres} m")
    for name, phase in cfg["phase"].items():
        elastic = phase.get("mechanical", {}).get("elastic", {})
        if elastic.get("type") == "Hooke" and "C_11" in elastic:
            check(float(elastic["C_11"]) >= STIFFNESS_PA_MIN,
                  f"phase {name}: C_11 = {elastic['C_11']} is not in pascals")
    materials = cfg["material"]
    check(len(materials) == rve["materials"],
          f"{len(materials)} materials in material.yaml, {rve['materials']} in the RVE")
    check(int(grid.material.max()) < len(materials),
          f"rve.vti uses material {grid.material.max()}, material.yaml has {len(materials)}")
    names = [p["name"] for p in summary["phases"]]
    worst = 0.0
    for k, row in enumerate(grains):
        entry = materials[k]["constituents"][0]
        check(entry["phase"] == names[int(row["phase"])],
              f"material {k}: phase {entry['phase']}, grain's is {names[int(row['phase'])]}")
        o = np.array(entry["O"], dtype=float)
        csv_o = np.array([float(row[c]) for c in ("o0", "o1", "o2", "o3")])
        euler = [float(row[c]) for c in ("phi1", "Phi", "phi2")]
        theirs = damask.Rotation.from_Euler_angles(euler, degrees=True).quaternion
        # q and -q are one rotation; DAMASK and grainpack both pick q0 >= 0, which is
        # ambiguous only at q0 = 0.
        d = min(np.abs(o - theirs).max(), np.abs(o + theirs).max())
        worst = max(worst, d, np.abs(o - csv_o).max())
        check(np.abs(o - csv_o).max() <= ORIENTATION_TOL, f"material {k}: O {o} != grains.csv {csv_o}")
        check(d <= ORIENTATION_TOL, f"material {k}: O {o} != DAMASK's from the Euler angles {theirs}")
    if rve["fill"] == "matrix":
        last = materials[-1]["constituents"][0]["phase"]
        check(last not in names or last == "matrix_fill", f"the last material's phase {last} is not the matrix")
    # The same orientations in the VTK files (PyVista, VTK's own reader).
    import pyvista
    csv_o = np.array([[float(r[c]) for c in ("o0", "o1", "o2", "o3")] for r in grains])
    csv_e = np.array([[float(r[c]) for c in ("phi1", "Phi", "phi2")] for r in grains])
    vtk_files = [os.path.join(out, n) for n in ("centers.vtp", "grains.vtu")]
    if plane and not all(os.path.exists(f) for f in vtk_files):
        check_grid_and_load(check, out, grid, len(materials), len(grains), csv_e, plane, worst)
        return check.exit_code()
    centers = pyvista.read(os.path.join(out, "centers.vtp"))
    check(np.array_equal(centers.point_data["crystal_quaternion"], csv_o),
          "centers.vtp crystal_quaternion != grains.csv o0..o3")
    check(np.array_equal(centers.point_data["euler_angles"], csv_e),
          "centers.vtp euler_angles != grains.csv phi1, Phi, phi2")
    surfaces = pyvista.read(os.path.join(out, "grains.vtu"))
    ids = surfaces.cell_data["grain_id"]
    check(np.array_equal(surfaces.cell_data["crystal_quaternion"], csv_o[ids]),
          "grains.vtu crystal_quaternion != grains.csv o0..o3 of each triangle's grain")
    check(np.array_equal(surfaces.cell_data["euler_angles"], csv_e[ids]),
          "grains.vtu euler_angles != grains.csv of each triangle's grain")
    check_grid_and_load(check, out, grid, len(materials), len(grains), csv_e, plane, worst)
    return check.exit_code()


def check_grid_and_load(check, out, grid, materials, grains, csv_e, plane, worst):
    """rve.vti through DAMASK's VTK reader, its layout, and load.yaml."""
    vti = damask.VTK.load(os.path.join(out, "rve.vti"))
    labels = vti.labels["Cell Data"]
    check(np.array_equal(vti.get("material").reshape(-1), grid.material.reshape(-1, order="F")),
          "rve.vti: damask.VTK's material array != GeomGrid.load's")
    for label in labels:
        check(vti.get(label).ndim == 1 or vti.get(label).shape[1:] == (1,),
              f"rve.vti: cell array {label} has {vti.get(label).shape[1:]} components")
    if "phi1" in labels:
        m = vti.get("material").reshape(-1)
        want = np.vstack([csv_e, np.zeros((materials - grains, 3))])[m]
        for a, name in enumerate(("phi1", "Phi", "phi2")):
            check(np.array_equal(vti.get(name).reshape(-1), want[:, a]),
                  f"rve.vti {name} != grains.csv {name} of each cell's material")
    with open(os.path.join(out, "rve.vti")) as f:
        lines = f.read().splitlines()
    for i, line in enumerate(lines):
        if "<DataArray" in line:
            data = lines[i + 1].strip()
            check(line.rstrip().endswith(">") and data and set(data) <= BASE64
                  and lines[i + 2].strip() == "</DataArray>",
                  f"rve.vti line {i + 1}: the data is not alone on the line after the tag")
    load = damask.LoadcaseGrid.load(os.path.join(out, "load.yaml"))
    check(len(load["loadstep"]) == 1, "load.yaml has no single load step")
    if plane:
        bc = load["loadstep"][0]["boundary_conditions"]["mechanical"]
        rate = bc.get("dot_F", bc.get("F"))
        check(rate[2][2] == 0 and bc["P"][2][2] == "x",
              f"2D load.yaml: F_zz not held (dot_F zz {rate[2][2]}, P zz {bc['P'][2][2]})")
    print(f"material.yaml: {materials} materials, complete and valid; rve.vti {[int(c) for c in grid.cells]} "
          f"cells{' (2D)' if plane else ''}, cell arrays {labels}; orientations agree with DAMASK's "
          f"to {worst:.1e}")


if __name__ == "__main__":
    sys.exit(main())
