"""grainpack's conforming mesher: packed ellipsoids and their matrix meshed by gmsh.

`pack` runs this script (embedded in the binary, with the modules it imports) with the
`python3` it finds, through loader.py (`python3 -c <loader.py> job.json`, the modules'
sources on stdin); run from this directory as `python3 gmsh_mesh.py job.json` it does
the same. The job (written by src/io/mesh/job.rs) holds the
box, the grains, the mesh options, the materials and the output paths. It writes
mesh.msh, mesh.inp and mesh.vtu to the temporary paths the job names (pack renames them
when everything succeeded) and a JSON of what it measured to job["stats"].

Pipeline (issue 29's findings): each grain an affinely transformed OCC sphere; the
images of the grains crossing the box cut to it and fragmented with it, the others
holes of the matrix (build_geometry); the packing's window is shifted so every
grain clears the box faces by a margin (thin caps mesh badly);
opposite faces paired by centre of mass and area, then setPeriodic; the surface mesh,
repaired where gmsh fails on it (mesh_surface.py); HXT for the volume; when gmsh fails,
a second attempt on the geometry rebuilt, with sizes from curvature;
periodic nodes paired by coordinates and snapped exactly onto their images plus the
box length; for quadratic elements, the middle nodes added to this linear mesh
afterwards and made periodic in turn (mesh_quadratic.py).
"""

import json
import re
import sys
import time

from mesh_common import MeshError
from mesh_fill import share_out
from mesh_geometry import build_geometry, half_extents, make_periodic, window
from mesh_nodes import (check_faces, extract, group_by_grain, number_nodes,
                        pair_by_coordinates, snap, tet_volume)
from mesh_quadratic import elevate
from mesh_plane import mesh_plane
from mesh_surface import surface_mesh
from mesh_write import finish

# Exit code for "gmsh could not mesh this packing" (pack maps it to its message).
EXIT_MESH_FAILED = 3
# Sizes from curvature (elements per 2 pi of curvature) of the second attempt: small cut
# curves (thin caps, at 500 grains) get short elements, and so do the grains' most
# curved parts (1.8x the tetrahedra on tools/check_mesh.py's composite).
RETRY_CURVATURE = 12


def where(gmsh, volumes):
    """The surfaces gmsh's log blames (invalid elements, periodic
    copies), each with the grains (or the matrix) on its sides: for the message of a
    failed mesh."""
    found = []
    for line in gmsh.logger.get():
        for tag in re.findall(r"surface (\d+)", line):
            if ("rror" in line or "invalid" in line) and int(tag) not in found:
                found.append(int(tag))
    parts = []
    for tag in found[-4:]:
        try:
            up, _ = gmsh.model.getAdjacencies(2, tag)
        except Exception:  # gmsh raises plain Exception
            continue
        sides = ["the matrix" if volumes.get(int(v)) is None
                 else f"grain {volumes[int(v)]['id']}" for v in up]
        parts.append(f"surface {tag} (of {' and '.join(sides)})")
    return "; gmsh's log blames " + ", ".join(parts) if parts else ""


def configure(gmsh, job):
    """gmsh's options for a 3D job, and its log started."""
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.option.setNumber("General.NumThreads", job["threads"])
    gmsh.option.setNumber("Geometry.OCCParallel", 1)
    gmsh.option.setNumber("Mesh.MeshSizeMax", job["element_size"])
    gmsh.option.setNumber("Mesh.Algorithm3D", 10)
    # Linear first, quadratic after the periodic snapping (mesh_quadratic.py).
    gmsh.option.setNumber("Mesh.ElementOrder", 1)
    gmsh.logger.start()


def tetrahedra(gmsh):
    """gmsh's 3D mesh on the repaired surface mesh; returns the repairs. One without
    an element is a failure (gmsh's generate returned without an exception and without
    elements after an HXT failure)."""
    repairs = surface_mesh(gmsh)
    gmsh.model.mesh.generate(3)
    types, tags, _ = gmsh.model.mesh.getElements(3)
    if not any(len(t) for t in tags):
        log = [line for line in gmsh.logger.get() if "rror" in line][-2:]
        raise Exception("gmsh returned no elements" + (": " + "; ".join(log) if log else ""))
    return repairs


def model(gmsh, job, origin):
    """The geometry in a new gmsh model, its face pieces paired and its volumes in
    physical groups per grain: (volumes, pairs)."""
    gmsh.model.add("grainpack")
    volumes = build_geometry(gmsh, job, origin)
    pairs = make_periodic(gmsh, origin, job["box"]) if job["periodic"] else 0
    for gid, tags in group_by_grain(volumes).items():
        p = gmsh.model.addPhysicalGroup(3, tags)
        gmsh.model.setPhysicalName(3, p, "matrix" if gid is None else f"grain_{gid}")
    return volumes, pairs


def generate(gmsh, job, origin, volumes):
    """Meshes in 3D. When gmsh fails (HXT refusing a surface mesh with invalid
    triangles, a periodic curve meshed differently on its two sides), once more in a
    new gmsh session on the geometry rebuilt, with sizes from curvature (in the same
    session, some of gmsh's errors leave it locked: every later generate does nothing;
    mesh_surface.py). Returns (volumes, the first attempt's error if the
    second was needed, the second's geometry seconds, the surface repairs of the
    attempt kept). A failure of both names gmsh's messages and the
    surfaces its log blames (`where`)."""
    try:
        return volumes, None, 0.0, tetrahedra(gmsh)
    except Exception as e:  # gmsh raises plain Exception
        first = f"{e}{where(gmsh, volumes)}"
    gmsh.finalize()
    gmsh.initialize(["grainpack"], readConfigFiles=False)
    configure(gmsh, job)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", RETRY_CURVATURE)
    started = time.monotonic()
    volumes, _ = model(gmsh, job, origin)
    rebuilt = time.monotonic() - started
    try:
        repairs = tetrahedra(gmsh)
    except Exception as second:
        raise MeshError(f"{second}{where(gmsh, volumes)} (in a second attempt with "
                        f"Mesh.MeshSizeFromCurvature = {RETRY_CURVATURE}; the first: "
                        f"{first})") from None
    return volumes, first, rebuilt, repairs


def mesh(gmsh, job):
    """Everything after gmsh.initialize(); returns the stats."""
    size = job["box"]
    for g in job["grains"]:
        g["extent"] = half_extents(g)
    started = time.monotonic()
    origin, margins = window(job)
    configure(gmsh, job)
    volumes, pairs = model(gmsh, job, origin)
    geometry_seconds = time.monotonic() - started
    volumes, first, rebuilt, repairs = generate(gmsh, job, origin, volumes)
    geometry_seconds += rebuilt
    pieces = extract(gmsh, volumes, 1)
    new, coords = number_nodes(gmsh, pieces, origin)
    pieces = [(grain, tags, [[new[n] for n in e] for e in conn]) for grain, tags, conn in pieces]
    images, worst, straightened = {}, 0.0, 0
    if job["periodic"]:
        images = pair_by_coordinates(coords, origin, size)
        worst = snap(gmsh, coords, images, size)
    if job["order"] == 2:
        pieces, coords, images, mid_worst, straightened = elevate(
            gmsh, volumes, origin, size, coords, images, job["periodic"])
        worst = max(worst, mid_worst)
    if job["periodic"]:
        check_faces(coords, images, origin, size)
    if job.get("fill") == "grains":
        pieces = share_out(gmsh, job, volumes, pieces, coords, origin,
                           4 if job["order"] == 1 else 11)
    mesh_seconds = time.monotonic() - started - geometry_seconds
    elements = []
    for grain, tags, conn in pieces:
        quality = gmsh.model.mesh.getElementQualities(tags, "minSICN")
        for nodes, q in zip(conn, quality):
            vol = tet_volume([coords[n] for n in nodes[:4]])
            elements.append((grain, nodes, float(q), vol))
    report = {"geometry_seconds": geometry_seconds, "mesh_seconds": mesh_seconds,
              "retried": first is not None, "first_error": first, "repairs": repairs,
              "margins": margins, "pairs": pairs, "worst": worst,
              "straightened": straightened}
    return finish(gmsh, job, coords, elements, images, origin, report)


def main():
    with open(sys.argv[1]) as f:
        job = json.load(f)
    try:
        import gmsh
    except ImportError as e:
        print(f"gmsh is not importable: {e}", file=sys.stderr)
        return 2
    gmsh.initialize(["grainpack"], readConfigFiles=False)
    try:
        # A 2D scene's job: triangles of the rectangle (mesh_plane.py).
        stats = (mesh_plane if job.get("dimension") == 2 else mesh)(gmsh, job)
    except MeshError as e:
        print(f"{e}", file=sys.stderr)
        return EXIT_MESH_FAILED
    except Exception as e:  # gmsh's own errors are plain Exceptions
        if type(e) is not Exception:
            raise
        print(f"gmsh: {e}", file=sys.stderr)
        return EXIT_MESH_FAILED
    finally:
        gmsh.finalize()
    with open(job["stats"], "w") as f:
        json.dump(stats, f)
    return 0


if __name__ == "__main__":
    sys.exit(main())
