#!/usr/bin/env python3
"""Measurements of the conforming mesh for BENCHMARKS.md ("Conforming mesh ...").

    python tools/bench_mesh.py scale [--grains 50 200] [--fractions 0.3 0.5] [--order 1] \
        [--timeout 600] [--pack target/release/pack] [--work DIR]
    python tools/bench_mesh.py voxel [--resolutions 16 24 32 40] [--pack ...] [--work DIR]
    python tools/bench_mesh.py plane --resolutions 120 240 360 --meshes 0.3:1 0.15:2 [...]

Needs gmsh in the Python that `pack` runs ($GRAINPACK_PYTHON, else python3), CalculiX
`ccx` (voxel), and /usr/bin/time (scale). Only the standard library.

scale: packs and meshes ellipsoids (equivalent diameter uniform in [2.5, 4], aspect
ratio uniform in [1.2, 2], random orientations, gap 0.05, periodic cube, seed 1) with
the box edge chosen for about N grains at fraction F (mean grain volume 18.93), at the
default mesh_size 0.3, linear tetrahedra (--order 2: quadratic), `--threads 1`; prints one row per scene:
grains, fraction, box, elements, nodes, SICN, geometry and meshing seconds, wall and
CPU seconds, peak memory, the grains' mesh volume against the exact one. A run over
`--timeout` seconds is stopped and reported as such.

voxel: one composite (tools/check_mesh.py's: 20 ellipsoids at 0.3, E 100 and 0.3 in a
matrix of E 10 and 0.35, 10^3 box) written as the voxel deck rve.inp at several
resolutions (rve_fill = "matrix") and as the conforming mesh (by default C3D4 and
C3D10 at mesh_size 0.3, C3D4 at 0.15: --meshes 0.3:1 0.3:2 0.15:1); E along x, y and z of each by CalculiX
(tools/ccx_solve.py's steps); the voxel moduli extrapolated to zero voxel size by a
least-squares line in the voxel size h (first-order convergence of a staircase
interface), and each mesh's mean modulus against it.

plane: the same for a 2D scene (--scene, configs/fibres_2d.toml): its pixel deck at
--resolutions and its triangle meshes at --meshes, E'x, E'y, k and mu of each by
tools/ccx_plane.py, the pixels' extrapolated to zero pixel size from the 3 finest.
"""

import argparse
import json
import os
import re
import signal
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from ccx_plane import plane_moduli  # noqa: E402
from ccx_solve import solve  # noqa: E402

MEAN_GRAIN_VOLUME = 18.93  # pi/6 E[d^3], d uniform in [2.5, 4]

SCALE_SCENE = """
seed = 1
target_fraction = {fraction}
[box]
size = [{edge}, {edge}, {edge}]
boundary = "periodic"
[packing]
gap = 0.05
[[phase]]
name = "grains"
size = {{ distribution = "uniform", min = 2.5, max = 4.0 }}
aspect_ratio = {{ distribution = "uniform", min = 1.2, max = 2.0 }}
elastic = {{ E = 100.0, nu = 0.3 }}
[matrix]
elastic = {{ E = 10.0, nu = 0.35 }}
[output]
dir = "{name}"
vtk = false
centers = false
statistics_png = false
mesh = true
mesh_order = {order}
"""

VOXEL_SCENE = """
seed = 12
target_fraction = 0.3
[box]
size = [10.0, 10.0, 10.0]
boundary = "periodic"
[packing]
gap = 0.05
[[phase]]
name = "grains"
size = {{ distribution = "uniform", min = 2.5, max = 4.0 }}
aspect_ratio = {{ distribution = "uniform", min = 1.2, max = 2.0 }}
elastic = {{ E = 100.0, nu = 0.3 }}
[matrix]
elastic = {{ E = 10.0, nu = 0.35 }}
[output]
dir = "{name}"
vtk = false
centers = false
statistics_png = false
{keys}
"""


def run_pack(pack, work, name, text, timeout=None):
    """Packs `text` as `name`.toml in `work` under /usr/bin/time; returns (summary or
    None, wall, cpu, peak kB, stderr tail)."""
    with open(os.path.join(work, name + ".toml"), "w") as f:
        f.write(text)
    timing = os.path.join(work, name + ".time")
    cmd = ["/usr/bin/time", "-o", timing, "-f", "%e %U %S %M",
           pack, name + ".toml", "--quiet", "--threads", "1"]
    started = time.time()
    # A session of its own, so that a timeout stops pack and its Python with gmsh too.
    proc = subprocess.Popen(cmd, cwd=work, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True, start_new_session=True)
    try:
        _, err = proc.communicate(timeout=timeout)
        err = err.strip()
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.communicate()
        return None, time.time() - started, None, None, f"stopped after {timeout:.0f} s"
    run = proc
    with open(timing) as f:
        wall, user, system, peak = f.read().split()[-4:]
    path = os.path.join(work, name, "summary.json")
    summary = None
    if run.returncode == 0 and os.path.exists(path):
        with open(path) as f:
            summary = json.load(f)
    return summary, float(wall), float(user) + float(system), int(peak), err[-600:]


def scale(args, work):
    print("| grains | φ | box | tetrahedra | nodes | min SICN | 1st pct SICN | geometry | "
          "meshing | `pack` wall / CPU | peak memory | grains' volume, mesh / exact |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for n in args.grains:
        for fraction in args.fractions:
            edge = round((n * MEAN_GRAIN_VOLUME / fraction) ** (1.0 / 3.0), 1)
            name = f"n{n}_f{fraction}_o{args.order}"
            text = SCALE_SCENE.format(fraction=fraction, edge=edge, name=name, order=args.order)
            s, wall, cpu, peak, err = run_pack(args.pack, work, name, text, args.timeout)
            if s is None:
                mem = "" if peak is None else f", peak {peak / 1024:.0f} MB"
                print(f"| ~{n} | {fraction} | {edge}³ | failed: {err} ({wall:.0f} s wall{mem}) |")
                sys.stdout.flush()
                continue
            m = s["mesh"]
            grains = next(p for p in m["phase_volume_fractions"] if p["phase"] == 0)
            print(f"| {s['grains']} | {s['packing_fraction']:.3f} | {edge}³ | {m['elements']} | "
                  f"{m['nodes']} | {m['min_sicn']:.3f} | {m['p1_sicn']:.3f} | "
                  f"{m['geometry_seconds']:.1f} s | {m['mesh_seconds']:.1f} s | "
                  f"{wall:.0f} s / {cpu:.0f} s | {peak / 1024:.0f} MB | "
                  f"{grains['mesh']:.4f} / {grains['exact']:.4f} "
                  f"({grains['mesh'] / grains['exact'] - 1:+.1%}) |")
            sys.stdout.flush()
            # The mesh files are large; the row is what is kept.
            for f in ("mesh.msh", "mesh.inp", "mesh.vtu"):
                path = os.path.join(work, name, f)
                if os.path.exists(path):
                    os.remove(path)


def moduli(deck, size, work):
    es = []
    for d in range(3):
        force, strains = solve(deck, d, size, work, iterative=True)
        es.append(force / (size[(d + 1) % 3] * size[(d + 2) % 3]) / strains[d])
    return es


def line(rows):
    """Least-squares E0, c of E = E0 + c h over rows (h, E), and the largest residual."""
    k = len(rows)
    mh = sum(h for h, _ in rows) / k
    me = sum(e for _, e in rows) / k
    c = sum((h - mh) * (e - me) for h, e in rows) / sum((h - mh) ** 2 for h, _ in rows)
    e0 = me - c * mh
    return e0, c, max(abs(e - (e0 + c * h)) for h, e in rows)


def voxel(args, work):
    rows = []
    for n in args.resolutions:
        name = f"voxel{n}"
        keys = f'rve_resolution = {n}\nrve_fill = "matrix"\nabaqus = true'
        s, wall, cpu, peak, err = run_pack(args.pack, work, name, VOXEL_SCENE.format(
            name=name, keys=keys))
        if s is None:
            raise RuntimeError(err)
        started = time.time()
        es = moduli(os.path.join(work, name, "rve.inp"), s["box"], work)
        h = s["box"][0] / n
        rows.append((h, sum(es) / 3))
        print(f"voxels {n}^3 (h = {h:.4f}): E = {es[0]:.4f}, {es[1]:.4f}, {es[2]:.4f}, mean "
              f"{sum(es) / 3:.4f}; matrix fraction {s['rve']['matrix_fraction']:.4f}; 3 solves "
              f"in {time.time() - started:.0f} s")
        sys.stdout.flush()
    # Least squares E = E0 + c h, over every resolution and over the three finest (the
    # coarse grids bridge the films between grains and are off the line).
    for fit in (rows, rows[-3:]):
        e0, c, worst = line(fit)
        print(f"voxels extrapolated to h = 0 from {len(fit)} resolutions: E = {e0:.4f} "
              f"(slope {c:.3f} per unit h, largest residual {worst:.4f})")
    for spec in args.meshes:
        size, order = float(spec.split(":")[0]), int(spec.split(":")[1])
        name = f"mesh_{size}_{order}"
        keys = f"mesh = true\nmesh_size = {size}\nmesh_order = {order}"
        s, wall, cpu, peak, err = run_pack(args.pack, work, name, VOXEL_SCENE.format(
            name=name, keys=keys))
        if s is None:
            print(f"mesh size {size} order {order}: failed: {err}")
            continue
        m = s["mesh"]
        started = time.time()
        es = moduli(os.path.join(work, name, "mesh.inp"), s["box"], work)
        mean = sum(es) / 3
        grains = next(p for p in m["phase_volume_fractions"] if p["phase"] == 0)
        print(f"mesh size {size} order {order}: {m['elements']} elements, E = {es[0]:.4f}, "
              f"{es[1]:.4f}, {es[2]:.4f}, mean {mean:.4f} ({mean / e0 - 1:+.2%} from the voxels' "
              f"limit); grains' volume {grains['mesh']:.4f} / {grains['exact']:.4f}; meshed in "
              f"{wall:.0f} s, 3 solves in {time.time() - started:.0f} s")
        sys.stdout.flush()


def plane(args, work):
    """A 2D scene's packing (--scene, configs/fibres_2d.toml) as the pixel deck at
    several resolutions and as conforming triangle meshes; E'x, E'y, k and mu of each
    by tools/ccx_plane.py's four plane-strain steps."""
    with open(args.scene) as f:
        base = f.read().replace("damask = true", "damask = false")
    keys = ["E_x", "E_y", "k", "mu"]

    def moduli2(name, extra, deck, n=None):
        text = base.replace('dir = "out/fibres_2d"', f'dir = "{name}"\n{extra}')
        if n is not None:
            text = re.sub(r"rve_resolution = \d+", f"rve_resolution = {n}", text)
        s, wall, _, _, err = run_pack(args.pack, work, name, text)
        if s is None:
            raise RuntimeError(err)
        started = time.time()
        m, _, _ = plane_moduli(os.path.join(work, name, deck), work)
        print(f"{name}: " + ", ".join(f"{k} = {m[k]:.2f}" for k in keys)
              + f" (written in {wall:.1f} s, 4 solves in {time.time() - started:.0f} s)")
        sys.stdout.flush()
        return s, m

    rows = []
    for n in args.resolutions:
        s, m = moduli2(f"pixels{n}", "", "rve.inp", n)
        rows.append((s["box"][0] / n, m))
    for k in keys:
        fit = [(h, m[k]) for h, m in rows]
        e0, c, worst = line(fit[-3:])
        print(f"pixels, {k} extrapolated to h = 0 from the 3 finest: {e0:.2f} (residual "
              f"{worst:.3f})")
    for spec in args.meshes:
        size, order = float(spec.split(":")[0]), int(spec.split(":")[1])
        s, m = moduli2(f"mesh_{size}_{order}", f"mesh = true\nmesh_size = {size}\n"
                       f"mesh_order = {order}", "mesh.inp")
        print(f"  {s['mesh']['elements']} triangles")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("what", choices=["scale", "voxel", "plane"])
    parser.add_argument("--scene", default="configs/fibres_2d.toml", help="plane: the 2D scene")
    parser.add_argument("--grains", type=int, nargs="+", default=[50, 200])
    parser.add_argument("--fractions", type=float, nargs="+", default=[0.3, 0.5])
    parser.add_argument("--resolutions", type=int, nargs="+", default=[16, 24, 32, 40])
    parser.add_argument("--meshes", nargs="+", default=["0.3:1", "0.3:2", "0.15:1"],
                        help="mesh_size:mesh_order of the conforming meshes (voxel)")
    parser.add_argument("--order", type=int, default=1, choices=[1, 2],
                        help="scale: mesh_order (1: C3D4, 2: C3D10)")
    parser.add_argument("--timeout", type=float, default=600.0)
    parser.add_argument("--pack", default="target/release/pack")
    parser.add_argument("--work", default=None)
    args = parser.parse_args()
    args.pack = os.path.abspath(args.pack)
    work = args.work or tempfile.mkdtemp(prefix="bench_mesh_")
    os.makedirs(work, exist_ok=True)
    {"scale": scale, "voxel": voxel, "plane": plane}[args.what](args, work)
    return 0


if __name__ == "__main__":
    sys.exit(main())
