#!/usr/bin/env python3
"""Checks the conforming mesh `pack` writes with `[output] mesh = true` (issue 29).

    python tools/check_mesh.py [--pack target/release/pack] [--work DIR]

Needs gmsh in the Python that `pack` runs (`$GRAINPACK_PYTHON`, else python3), and in
this one meshio, numpy and scipy (tools/requirements-exports.txt), and CalculiX `ccx`.
The scenes of SCENES (periodic at order 1 and 2, and walled) and PLANE_SCENES are packed
and meshed, then checked by programs other than gmsh:

- mesh.msh, read by meshio: every node on a far face of the box has a node on the
  opposite face at the same place moved by the box length, to PERIODIC_TOL of it,
  and the other way round;
- mesh.vtu, read by meshio: no two nodes at one place (a crack between a grain and
  the matrix would be one); cell data grain and phase; every tetrahedron positive; the
  volumes sum to the box's (VOLUME_TOL) and give summary.json's phase fractions;
- a grain crosses a corner of the box: its elements reach all six faces;
- mesh.inp, solved by CalculiX under its periodic equations in uniaxial tension along
  x, y and z (tools/ccx_solve.py's step; the quadratic scene along x only): a
  homogeneous RVE (grains and matrix of one material) gives back E and nu to
  HOMOGENEOUS_TOL, and a composite (stiff ellipsoids
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
from ccx_solve import (HOMOGENEOUS_TOL, STRAIN, check_plane_composite,  # noqa: E402
                       check_plane_homogeneous, hashin_shtrikman, kg, solve)

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
{matrix}
[output]
dir = "{name}"
vtk = false
centers = false
statistics_png = false
mesh = true
mesh_size = {mesh_size}
mesh_order = {order}
mesh_fill = "{fill}"
"""

# Homogeneous: grains and matrix of one material, so the periodic solution is the
# uniform strain. Composite: stiff grains (E 100) in a soft matrix (E 10, nu 0.35).
# The seeds are ones whose packing, in the window the mesher picks, has a grain across
# a corner of the box (10 and 20 grains; the check fails if none does).
SCENES = {
    "homogeneous": dict(seed=1, fraction=0.2, dmin=2.5, dmax=4.0, e_grain=210.0,
                        e_matrix=210.0, nu_matrix=0.3, boundary="periodic", order=1),
    "composite": dict(seed=12, fraction=0.3, dmin=2.5, dmax=4.0, e_grain=100.0,
                      e_matrix=10.0, nu_matrix=0.35, boundary="periodic", order=1),
    # Walls: no periodic equations; the deck is run as written (`ccx -i mesh`).
    "walled": dict(seed=2, fraction=0.25, dmin=2.5, dmax=3.5, e_grain=210.0,
                   e_matrix=210.0, nu_matrix=0.3, boundary="reflecting", order=1),
    # C3D10 in the periodic box (gmsh's own high-order route moved face nodes off their
    # partners): the homogeneous scene, coarser, solved along x only (E and both nu),
    # so that it costs CI seconds.
    "quadratic": dict(seed=1, fraction=0.2, dmin=2.5, dmax=4.0, e_grain=210.0,
                      e_matrix=210.0, nu_matrix=0.3, boundary="periodic", order=2,
                      mesh_size=0.5, directions=1),
    # The grains fill: the elements between the grains shared out among them, no
    # matrix; one material, so E and nu come back only if every element has it.
    "grains_fill": dict(seed=1, fraction=0.2, dmin=2.5, dmax=4.0, e_grain=210.0,
                        e_matrix=210.0, nu_matrix=0.3, boundary="periodic", order=1,
                        fill="grains", directions=1),
    # And the composite, on which that route failed: about 1 min of CPU, so only when
    # asked for (--only quadratic_composite).
    "quadratic_composite": dict(seed=12, fraction=0.3, dmin=2.5, dmax=4.0, e_grain=100.0,
                                e_matrix=10.0, nu_matrix=0.35, boundary="periodic",
                                order=2, slow=True),
}

# A 2D scene (a rectangle: two lengths): ellipses meshed as triangles for a
# plane-strain deck, at order 1 (CPE3) and 2 (CPE6).
PLANE_SCENE = """
seed = {seed}
target_fraction = 0.5
[box]
size = [10.0, 10.0]
boundary = "{boundary}"
[packing]
gap = 0.05
[[phase]]
name = "fibre"
size = {{ distribution = "uniform", min = 1.8, max = 2.8 }}
aspect_ratio = {{ distribution = "uniform", min = 1.0, max = 1.8 }}
elastic = {{ E = {e_grain}, nu = 0.3 }}
[matrix]
elastic = {{ E = {e_matrix}, nu = {nu_matrix} }}
[output]
dir = "{name}"
vtk = false
centers = false
statistics_png = false
packing_png = false
mesh = true
mesh_size = 0.3
mesh_order = {order}
"""

# Fibres (E 100) in a matrix (E 10, nu 0.35); solved as written (a composite, in the
# 2D Hashin-Shtrikman bounds of the mesh's own area fraction) and with every material
# replaced by one (E 210, nu 0.3: E/(1-nu^2) and nu/(1-nu) back). The seed is one with
# a grain across a corner of the window (13 ellipses). Walls: one material, run as
# written.
PLANE_SCENES = {
    "plane_linear": dict(seed=5, order=1, boundary="periodic", e_grain=100.0,
                         e_matrix=10.0, nu_matrix=0.35),
    "plane_quadratic": dict(seed=5, order=2, boundary="periodic", e_grain=100.0,
                            e_matrix=10.0, nu_matrix=0.35),
    "plane_walled": dict(seed=5, order=1, boundary="reflecting", e_grain=210.0,
                         e_matrix=210.0, nu_matrix=0.3),
}


def one_material(deck, out):
    """`deck` with every *Elastic line made E 210, nu 0.3, written to `out`."""
    with open(deck) as f:
        lines = f.read().split("\n")
    for i in range(1, len(lines)):
        if lines[i - 1] == "*Elastic":
            lines[i] = "210.0, 0.3"
    with open(out, "w") as f:
        f.write("\n".join(lines))
    return out


def check_plane(name, out, work, summary, failures):
    """The checks of a 2D mesh: the periodic ones solved by ccx (four plane-strain
    steps each) as a composite and as one material; the walled one as written."""
    if summary["boundary"] != "periodic":
        check_walled(out, summary, failures, plane=True)
        return
    check_periodic(out, summary, failures)
    phi = check_cells(out, summary, failures)
    deck = os.path.join(out, "mesh.inp")
    failures += check_plane_homogeneous(
        one_material(deck, os.path.join(out, "one_material.inp")), work)
    failures += check_plane_composite(deck, work, f2=phi, isotropy_tol=None)


def check_periodic(out, summary, failures):
    mesh = meshio.read(os.path.join(out, "mesh.msh"))
    origin = np.array(summary["mesh"]["origin"])
    axes = len(origin)  # 2 for a 2D scene's rectangle
    size = np.array(summary["box"][:axes])
    length = size.max()
    p = mesh.points[:, :axes]
    worst = 0.0
    for d in range(axes):
        near = np.flatnonzero(np.abs(p[:, d] - origin[d]) < ON_FACE_TOL * length)
        far = np.flatnonzero(np.abs(p[:, d] - origin[d] - size[d]) < ON_FACE_TOL * length)
        if len(near) == 0 or len(near) != len(far):
            failures.append(f"{out}: {len(near)} nodes on the near {'xyz'[d]} face, "
                            f"{len(far)} on the far one")
            continue
        shift = np.zeros(axes)
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
    """Volumes (areas in 2D), cell data, and a grain split at a corner; returns the
    grains' fraction of the mesh. Triangles must be counter-clockwise (CalculiX)."""
    mesh = meshio.read(os.path.join(out, "mesh.vtu"))
    origin = np.array(summary["mesh"]["origin"])
    axes = len(origin)
    kind = {(3, 1): "tetra", (3, 2): "tetra10", (2, 1): "triangle", (2, 2): "triangle6"}[
        (axes, summary["mesh"]["order"])]
    tets = mesh.cells_dict[kind]
    grain = mesh.cell_data_dict["grain"][kind]
    phase = mesh.cell_data_dict["phase"][kind]
    p = mesh.points
    if axes == 3:
        a, b, c = (p[tets[:, i]] - p[tets[:, 0]] for i in (1, 2, 3))
        vol = np.einsum("ij,ij->i", a, np.cross(b, c)) / 6.0
    else:
        a, b = (p[tets[:, i]] - p[tets[:, 0]] for i in (1, 2))
        vol = 0.5 * (a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0])
    size = np.array(summary["box"][:axes])
    box = size.prod()
    if vol.min() <= 0.0:
        failures.append(f"{out}: {np.sum(vol <= 0)} {kind} cells with volume <= 0")
    total = vol.sum()
    print(f"{out}: {len(tets)} {kind} cells, volume {total!r} of a box of {box!r}")
    if abs(total / box - 1.0) > VOLUME_TOL:
        failures.append(f"{out}: tetrahedra sum to {total}, the box is {box}")
    reported = {v["phase"]: v["mesh"] for v in summary["mesh"]["phase_volume_fractions"]}
    for ph, frac in reported.items():
        mine = vol[phase == ph].sum() / box
        if abs(mine - frac) > VOLUME_TOL:
            failures.append(f"{out}: phase {ph} fills {mine} of the mesh, summary says {frac}")
    length = size.max()
    corner = []
    for g in np.unique(grain[grain >= 0]):
        nodes = p[np.unique(tets[grain == g])]
        faces = [np.any(np.abs(nodes[:, d] - origin[d] - s * size[d]) < ON_FACE_TOL * length)
                 for d in range(axes) for s in (0, 1)]
        if all(faces):
            corner.append(int(g))
    print(f"{out}: grains split across all {2 * axes} faces (a corner): {corner}")
    if not corner:
        failures.append(f"{out}: no grain crosses a corner of the box")
    return vol[grain >= 0].sum() / box


def check_grains_fill(out, summary, phi, failures):
    """Every element is a grain's: in mesh.vtu (grain >= 0, fraction 1) and in
    mesh.msh (gmsh writes the elements of physical groups only: all of them there, in
    groups grain_<id>, no matrix group)."""
    msh = meshio.read(os.path.join(out, "mesh.msh"))
    names = set(msh.field_data)
    tagged = len(msh.cell_data_dict["gmsh:physical"]["tetra"])
    tets = summary["mesh"]["elements"]
    print(f"{out}: grains fill {phi!r} of the box; mesh.msh: {len(names)} groups, "
          f"{tagged} of {tets} tetrahedra in them")
    if abs(phi - 1.0) > VOLUME_TOL:
        failures.append(f"{out}: the grains fill {phi} of the mesh, not all of it")
    if tagged != tets or not all(n.startswith("grain_") for n in names):
        failures.append(f"{out}: mesh.msh's groups {sorted(names)[:5]} hold {tagged} of "
                        f"{tets} tetrahedra")


def check_walled(out, summary, failures, plane=False):
    """The deck as written, run by ccx: its template stretches the box by STRAIN along
    x on rollers, so a homogeneous box carries E * STRAIN * Ly * Lz; in 2D (plane
    strain, sections of thickness 1) a rectangle carries E / (1 - nu^2) * STRAIN * Ly."""
    run = subprocess.run(["ccx", "-i", "mesh"], cwd=out, capture_output=True, text=True)
    if run.returncode != 0 or "ERROR" in run.stdout:
        failures.append(f"{out}: ccx -i mesh failed:\n{run.stdout[-1500:]}")
        return
    with open(os.path.join(out, "mesh.dat")) as f:
        lines = [line.split() for line in f if line.strip()]
    i = next(i for i, w in enumerate(lines) if w[:2] == ["total", "force"])
    force = float(lines[i + 1][0])
    size = summary["box"]
    want = 210.0 / (1.0 - 0.3**2) * STRAIN * size[1] if plane else 210.0 * STRAIN * size[1] * size[2]
    print(f"{out}: ccx -i mesh as written: force {force!r} on X1 ({want!r})")
    if abs(force / want - 1.0) > HOMOGENEOUS_TOL:
        failures.append(f"{out}: force {force} on X1, not {want}")


def moduli(out, work, summary, iterative, directions=3):
    """E and the two Poisson ratios along the first `directions` of x, y, z."""
    deck = os.path.join(out, "mesh.inp")
    size = summary["box"]
    results = []
    for d in range(directions):
        force, strains = solve(deck, d, size, work, iterative=iterative)
        area = size[(d + 1) % 3] * size[(d + 2) % 3]
        e = force / area / strains[d]
        results.append((e, [-strains[o] / strains[d] for o in range(3) if o != d]))
    return results


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--pack", default="target/release/pack")
    parser.add_argument("--work", default=None)
    parser.add_argument("--only", default="", help="run only the scenes whose name starts "
                        "so (plane: the 2D ones)")
    args = parser.parse_args()
    pack = os.path.abspath(args.pack)
    work = args.work or tempfile.mkdtemp(prefix="check_mesh_")
    os.makedirs(work, exist_ok=True)
    failures = []
    for name, values in SCENES.items():
        if not name.startswith(args.only) or (values.get("slow") and not args.only):
            continue
        values = {"mesh_size": 0.3, "fill": "matrix", **values}
        values["matrix"] = ("" if values["fill"] == "grains" else
                            "[matrix]\nelastic = {{ E = {e_matrix}, nu = {nu_matrix} }}"
                            .format(**values))
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
        if values["fill"] == "grains":
            check_grains_fill(out, summary, phi, failures)
        started = time.time()
        # The slow scene by CalculiX's iterative solver (4x faster than SPOOLES; too
        # loose, 1e-3 on nu, for the homogeneous check).
        results = moduli(out, work, summary, iterative=values.get("slow", False),
                         directions=values.get("directions", 3))
        if values["e_grain"] == values["e_matrix"]:
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
        print(f"{name}: {len(results)} solves in {time.time() - started:.1f} s")
    for name, values in PLANE_SCENES.items():
        if not name.startswith(args.only):
            continue
        started = time.time()
        with open(os.path.join(work, name + ".toml"), "w") as f:
            f.write(PLANE_SCENE.format(name=name, **values))
        subprocess.run([pack, name + ".toml", "--quiet"], cwd=work, check=True)
        out = os.path.join(work, name)
        with open(os.path.join(out, "summary.json")) as f:
            summary = json.load(f)
        m = summary["mesh"]
        print(f"{name}: {summary['grains']} ellipses, {m['elements']} elements (order "
              f"{m['order']}), min SICN {m['min_sicn']:.3f}, 1st percentile "
              f"{m['p1_sicn']:.3f}, packed and meshed in {time.time() - started:.1f} s")
        check_conforming(out, summary, failures)
        check_plane(name, out, work, summary, failures)
        print(f"{name}: checked in {time.time() - started:.1f} s")
    if failures:
        print("FAILED:\n  " + "\n  ".join(failures))
        return 1
    print("all mesh checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
