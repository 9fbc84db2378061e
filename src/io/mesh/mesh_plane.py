"""The 2D mesher: packed ellipses and their matrix as conforming triangles of the
rectangle, periodic across opposite edges, for a plane-strain deck (CPE3/CPE6).

A 2D grain comes as the ellipsoid it is packed as (docs/design-2d.md): its first two
semi-axes and its turn about z are the ellipse's; the mesh lies in the plane z = 0.
Pipeline, the 3D one's in the plane: the window shifted so every ellipse clears the
edges by a margin; each ellipse an exact OCC ellipse (addDisk, turned) with its
periodic images; all fragmented with the rectangle (cheap in 2D) and the pieces outside
removed; pieces of opposite edges paired by their ends and made periodic; gmsh's
Frontal-Delaunay triangles; periodic nodes paired by coordinates and snapped exactly
onto their images plus the rectangle's length.
"""

import math
import time

from mesh_common import MeshError
from mesh_fill import share_out
from mesh_geometry import half_extents, images, window
from mesh_nodes import check_faces, number_nodes, pair_by_coordinates, snap
from mesh_write import finish

# Two pieces of opposite edges are images of each other when the ends of one, moved
# across the rectangle, lie on the other's to this fraction of its length (OCC's
# intersections of the images of one ellipse with the edges agree to about 1e-12 L).
EDGE_MATCH_TOL = 1e-6
# Points sampled inside a curve to decide it lies on an edge of the rectangle.
CURVE_SAMPLES = 5
# gmsh's 2D algorithm: Frontal-Delaunay, the best triangles of its 2D meshers.
ALGORITHM_2D = 6
# gmsh's triangle types by order, and the nodes per element.
TRIANGLE = {1: (2, 3), 2: (9, 6)}
# A triangle's node order reversed (counter-clockwise, as CalculiX wants it): the
# vertices 0, 2, 1 and the middle nodes of edges (0, 2), (2, 1), (1, 0).
REVERSED = {3: [0, 2, 1], 6: [0, 2, 1, 5, 4, 3]}


def angle(q):
    """The turn about z of the quaternion (w, x, y, z) of a turn about z."""
    return 2.0 * math.atan2(q[3], q[0])


def ellipse(occ, grain, shift):
    """The ellipse of `grain` moved by `shift`, as an OCC surface (exact conic)."""
    a1, a2 = grain["semi_axes"][:2]
    theta = angle(grain["quaternion"])
    if a1 < a2:
        # OCC's ellipse wants its major radius along its local x.
        a1, a2, theta = a2, a1, theta + 0.5 * math.pi
    cx, cy = grain["centre"][0] + shift[0], grain["centre"][1] + shift[1]
    tag = occ.addDisk(cx, cy, 0.0, a1, a2)
    if theta != 0.0:
        occ.rotate([(2, tag)], cx, cy, 0.0, 0.0, 0.0, 1.0, theta)
    return tag


def build_plane(gmsh, job, origin):
    """The rectangle's surfaces: {tag: grain, or None for the matrix}."""
    occ = gmsh.model.occ
    size = job["box"]
    rect = occ.addRectangle(origin[0], origin[1], 0.0, size[0], size[1])
    tools, owner = [], []
    for g in job["grains"]:
        for t in images(g, origin, size, job["periodic"]):
            tools.append((2, ellipse(occ, g, t)))
            owner.append(g)
    _, children = occ.fragment([(2, rect)], tools)
    occ.synchronize()
    inside = {tag for _, tag in children[0]}
    surfaces = {tag: None for tag in inside}
    outside = set()
    for g, kids in zip(owner, children[1:]):
        for _, tag in kids:
            if tag in inside:
                surfaces[tag] = g
            else:
                outside.add(tag)
    if outside:
        occ.remove([(2, t) for t in sorted(outside)], recursive=True)
        occ.synchronize()
    return surfaces


def edge_curves(gmsh, origin, size):
    """Per axis d: (near, far) lists of (curve, its end points) of the curves lying on
    the rectangle's edges normal to d."""
    length = max(size)
    edges = [([], []) for _ in range(2)]
    for _, c in gmsh.model.getEntities(1):
        lo, hi = gmsh.model.getParametrizationBounds(1, c)
        ts = [lo[0] + (hi[0] - lo[0]) * i / (CURVE_SAMPLES + 1)
              for i in range(CURVE_SAMPLES + 2)]
        xyz = gmsh.model.getValue(1, c, ts)
        points = [xyz[3 * i:3 * i + 3] for i in range(len(ts))]
        for d in range(2):
            for side in (0, 1):
                plane = origin[d] + side * size[d]
                if all(abs(p[d] - plane) < EDGE_MATCH_TOL * length for p in points):
                    edges[d][side].append((c, [points[0], points[-1]]))
    return edges


def make_periodic_plane(gmsh, origin, size):
    """Makes each piece of a far edge periodic of the near piece whose ends are its
    own moved back across the rectangle; returns the number of pairs."""
    length = max(size)
    pairs = 0
    for d, (near, far) in enumerate(edge_curves(gmsh, origin, size)):
        if len(near) != len(far) or not near:
            raise MeshError(f"the rectangle's edges normal to {'xy'[d]} have {len(near)} "
                            f"and {len(far)} pieces: the geometry is not periodic")
        used = set()
        for c, ends in far:
            moved = [[p[i] - (size[d] if i == d else 0.0) for i in range(3)] for p in ends]
            match = None
            for n, nends in near:
                if n in used:
                    continue
                if all(min(math.dist(p, q) for q in nends) < EDGE_MATCH_TOL * length
                       for p in moved):
                    match = n
                    break
            if match is None:
                raise MeshError(f"curve {c} on the far {'xy'[d]} edge has no partner on the "
                                "near edge")
            used.add(match)
            affine = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]
            affine[4 * d + 3] = size[d]
            gmsh.model.mesh.setPeriodic(1, [c], [match], affine)
            pairs += 1
    return pairs


def triangle_area(p):
    return 0.5 * ((p[1][0] - p[0][0]) * (p[2][1] - p[0][1])
                  - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]))


def mesh_plane(gmsh, job):
    """Everything after gmsh.initialize() for a 2D job; returns the stats."""
    size = job["box"]
    order = job["order"]
    for g in job["grains"]:
        g["extent"] = half_extents(g)
    started = time.monotonic()
    origin, margins = window(job)
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.option.setNumber("General.NumThreads", job["threads"])
    gmsh.model.add("grainpack")
    surfaces = build_plane(gmsh, job, origin)
    pairs = make_periodic_plane(gmsh, origin, size) if job["periodic"] else 0
    groups = {}
    for tag, grain in sorted(surfaces.items()):
        groups.setdefault(None if grain is None else grain["id"], []).append(tag)
    for gid, tags in groups.items():
        p = gmsh.model.addPhysicalGroup(2, tags)
        gmsh.model.setPhysicalName(2, p, "matrix" if gid is None else f"grain_{gid}")
    geometry_seconds = time.monotonic() - started
    gmsh.option.setNumber("Mesh.MeshSizeMax", job["element_size"])
    gmsh.option.setNumber("Mesh.Algorithm", ALGORITHM_2D)
    gmsh.option.setNumber("Mesh.ElementOrder", order)
    gmsh.option.setNumber("Mesh.SecondOrderLinear", 0)
    gmsh.option.setNumber("Mesh.HighOrderOptimize", 2)
    gmsh.logger.start()
    try:
        gmsh.model.mesh.generate(2)
    except Exception as e:  # gmsh raises plain Exception
        raise MeshError(str(e)) from None
    etype, npe = TRIANGLE[order]
    pieces = []
    for tag, grain in sorted(surfaces.items()):
        types, tags, nodes = gmsh.model.mesh.getElements(2, tag)
        for t, et, nt in zip(types, tags, nodes):
            if t != etype:
                raise MeshError(f"surface {tag} has gmsh elements of type {t}, not triangles")
            conn = [[int(nt[i * npe + j]) for j in range(npe)] for i in range(len(et))]
            pieces.append((grain, [int(e) for e in et], conn))
    new, coords = number_nodes(gmsh, pieces, origin)
    pieces = [(grain, tags, [[new[n] for n in e] for e in conn]) for grain, tags, conn in pieces]
    images_ = {}
    worst = 0.0
    if job["periodic"]:
        # Vertices and middle nodes alike: on the rectangle's straight edges the middle
        # nodes of matched edges are matched too.
        images_ = pair_by_coordinates(coords, origin, size)
        worst = snap(gmsh, coords, images_, size)
        check_faces(coords, images_, origin, size)
    if job.get("fill") == "grains":
        pieces = share_out(gmsh, job, surfaces, pieces, coords, origin, etype)
    mesh_seconds = time.monotonic() - started - geometry_seconds
    elements = []
    for grain, tags, conn in pieces:
        quality = gmsh.model.mesh.getElementQualities(tags, "minSICN")
        for nodes, q in zip(conn, quality):
            area = triangle_area([coords[n] for n in nodes[:3]])
            if area < 0.0:
                nodes = [nodes[i] for i in REVERSED[npe]]
                area = -area
            elements.append((grain, nodes, float(q), area))
    report = {"geometry_seconds": geometry_seconds, "mesh_seconds": mesh_seconds,
              "retried": False, "margins": margins, "pairs": pairs, "worst": worst}
    return finish(gmsh, job, coords, elements, images_, origin, report)
