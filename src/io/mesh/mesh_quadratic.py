"""Quadratic tetrahedra (C3D10) made from the linear mesh, periodic in a periodic box.

gmsh's own route (Mesh.ElementOrder 2 during generate, then its high-order optimiser)
moved nodes of the box faces within the faces, so that they lost their partners across
the box, and sometimes aborted ("Failed to reach critical value", SIGABRT; BENCHMARKS.md,
"Conforming mesh, second round"). Here instead: the linear mesh is made and its
periodic vertices snapped; gmsh adds the middle nodes (setOrder, no optimiser), which
lie on the curved surfaces and curves; the middle nodes of far-face edges are snapped
onto their images plus the box length; and where a middle node pulled onto a curved
surface inverts an element, that element's curved edges are made straight again
(straighten), with their periodic partners, until no element is inverted: a tetrahedron
with straight edges is its valid linear one.
"""

from mesh_common import MeshError
from mesh_nodes import TET10_EDGES, TET10_ORDER, extract, mid_images, number_nodes, snap

# A middle node is "curved" when it lies farther than this fraction of the box length
# from its edge's straight midpoint (the rounding of a midpoint is ~1e-16 L).
CURVED_TOL = 1e-12


def elevate(gmsh, volumes, origin, size, coords, images, periodic):
    """The linear mesh (its vertices at `coords`, snapped; `images` their periodic
    partners) made quadratic. Returns (pieces, coords, images with the
    middle nodes', largest snap of a middle node, number of edges straightened)."""
    gmsh.option.setNumber("Mesh.HighOrderOptimize", 0)
    gmsh.option.setNumber("Mesh.SecondOrderLinear", 0)
    try:
        gmsh.model.mesh.setOrder(2)
    except Exception as e:  # gmsh raises plain Exception
        raise MeshError(f"gmsh could not make the elements quadratic: {e}") from None
    pieces = extract(gmsh, volumes, 2)
    new, quadratic = number_nodes(gmsh, pieces, origin)
    # setOrder renumbers the vertices (it keeps their coordinates): found by these.
    at = {p: n for n, p in quadratic.items()}
    images = {at[coords[n]]: (at[coords[m]], far) for n, (m, far) in images.items()}
    coords = quadratic
    pieces = [(grain, tags, [[new[n] for n in (e[i] for i in TET10_ORDER)] for e in conn])
              for grain, tags, conn in pieces]
    conns = [e for _, _, conn in pieces for e in conn]
    worst = 0.0
    if periodic:
        middles = mid_images(conns, coords, images, origin, size)
        worst = snap(gmsh, coords, middles, size)
        images.update(middles)
    straightened = straighten(gmsh, pieces, coords, images, size)
    return pieces, coords, images, worst, straightened


def midpoint(coords, a, b):
    return tuple(0.5 * (coords[a][i] + coords[b][i]) for i in range(3))


def straighten(gmsh, pieces, coords, images, size):
    """Moves the middle nodes of the curved edges of inverted elements (gmsh's minSICN
    <= 0) to the straight midpoints, with the middle nodes periodic with them, until no
    element is inverted; returns how many middle nodes moved. Each round straightens at
    least one curved edge, so it ends (at worst with the linear mesh's geometry)."""
    length = max(size)
    edge_of = {}
    for _, _, conn in pieces:
        for e in conn:
            for k, (i, j) in enumerate(TET10_EDGES):
                edge_of[e[4 + k]] = (e[i], e[j])
    # Middle nodes tied by periodic equations: a node, its master and the master's other
    # images move together (the master straight, the others onto it plus L).
    def root(n):
        while n in images:
            n = images[n][0]
        return n

    group = {}
    for n in images:
        if n in edge_of:
            m = root(n)
            group.setdefault(m, {m}).add(n)
            group[n] = group[m]
    moved = 0
    while True:
        bad = []
        for _, tags, conn in pieces:
            quality = gmsh.model.mesh.getElementQualities(tags, "minSICN")
            bad += [e for e, q in zip(conn, quality) if q <= 0.0]
        if not bad:
            return moved
        todo = set()
        for e in bad:
            for k in range(6):
                mid = e[4 + k]
                a, b = edge_of[mid]
                off = max(abs(x - y) for x, y in zip(coords[mid], midpoint(coords, a, b)))
                if off > CURVED_TOL * length:
                    todo |= group.get(mid, {mid})
        if not todo:
            raise MeshError(f"{len(bad)} quadratic elements stay inverted with straight "
                            "edges (the linear mesh's are not)")
        for n in todo:
            if n not in images:
                a, b = edge_of[n]
                coords[n] = midpoint(coords, a, b)
                gmsh.model.mesh.setNode(n, list(coords[n]), [])
        # Images in the order of their chains (an image of an image after it).
        depth = {n: 0 for n in todo}
        for n in todo:
            m = n
            while m in images:
                m = images[m][0]
                depth[n] += 1
        snap(gmsh, coords, {n: images[n] for n in sorted(todo, key=depth.get)
                            if n in images}, size)
        moved += len(todo)
