"""The mesh's nodes and elements after gmsh: elements per volume, the nodes renumbered
from the origin corner, the periodic images found by coordinates (and, for quadratic
elements, by edges), and the tetrahedra's volumes."""

import math

from mesh_common import MeshError, on_plane

# A node on a far face and its image on the near ones lie this fraction of the box
# length apart at most after the translation (gmsh's copies: 1e-8 L, issue 29).
PAIR_TOL = 1e-6


def pair_by_coordinates(coords, origin, size):
    """For each node on a far face: (its image, far axes). The image is the node on
    no far face nearest to the node moved back across its far axes, within
    PAIR_TOL * L. (gmsh's own periodic node maps chained a node to one 0.17 L away
    on a 200-grain mesh; coordinates do not.)"""
    length = max(size)
    tol = PAIR_TOL * length
    cell = 100.0 * tol
    grid = {}
    far_of = {}
    for n, p in coords.items():
        far = [d for d in range(len(size)) if on_plane(p[d], origin[d] + size[d], length)]
        far_of[n] = far
        if not far:
            grid.setdefault(tuple(math.floor(c / cell) for c in p), []).append(n)
    images = {}
    for n, far in far_of.items():
        if not far:
            continue
        target = [coords[n][d] - (size[d] if d in far else 0.0) for d in range(3)]
        key = [math.floor(c / cell) for c in target]
        best, best_dist = None, tol
        for i in (-1, 0, 1):
            for j in (-1, 0, 1):
                for k in (-1, 0, 1):
                    for m in grid.get((key[0] + i, key[1] + j, key[2] + k), ()):
                        dist = math.dist(coords[m], target)
                        if dist <= best_dist:
                            best, best_dist = m, dist
        if best is None:
            raise MeshError(f"node {n} at {coords[n]} on a far box face has no node "
                            f"opposite it within {PAIR_TOL} L")
        images[n] = (best, far)
    return images


# Edges of a tetrahedron in Abaqus' (and VTK's) order of the middle nodes 4 to 9.
TET10_EDGES = [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)]


def mid_images(elements, coords, images, origin, size):
    """Images of the middle nodes of quadratic elements on the far faces, after the
    vertices were snapped: the middle node of edge (a, b) far along the axes F (those
    both ends are far along) has as image the middle node of the edge joining the
    images of a and b across F; found by the vertices' exact snapped coordinates."""
    length = max(size)
    at = {coords[n]: n for n in coords}
    middle = {}
    for conn in elements:
        for k, (i, j) in enumerate(TET10_EDGES):
            middle[frozenset((conn[i], conn[j]))] = conn[4 + k]

    def far_axes(n):
        return {d for d in range(len(size)) if on_plane(coords[n][d], origin[d] + size[d], length)}

    def across(n, axes):
        if n not in images:
            return n
        image, far = images[n]
        key = tuple(coords[image][d] + (size[d] if d in far and d not in axes else 0.0)
                    for d in range(3))
        return at[key]

    out = {}
    for edge, mid in middle.items():
        a, b = tuple(edge)
        axes = far_axes(a) & far_axes(b) & far_axes(mid)
        if not axes or mid in out:
            continue
        partner = middle.get(frozenset((across(a, axes), across(b, axes))))
        if partner is None:
            raise MeshError(f"the middle node {mid} of a far-face edge has no periodic image")
        out[mid] = (partner, sorted(axes))
    return out


# Gmsh's tetrahedron node order -> Abaqus' and VTK's (the last two edge nodes swap).
TET10_ORDER = [0, 1, 2, 3, 4, 5, 6, 7, 9, 8]


def extract(gmsh, volumes, order):
    """Elements per volume: list of (grain or None, element tags, node lists)."""
    etype = 4 if order == 1 else 11
    npe = 4 if order == 1 else 10
    out = []
    for tag, grain in sorted(volumes.items()):
        types, tags, nodes = gmsh.model.mesh.getElements(3, tag)
        for t, et, nt in zip(types, tags, nodes):
            if t != etype:
                raise MeshError(f"volume {tag} has gmsh elements of type {t}, not tetrahedra")
            conn = [[int(nt[i * npe + j]) for j in range(npe)] for i in range(len(et))]
            out.append((grain, [int(e) for e in et], conn))
    return out


def number_nodes(gmsh, pieces, origin):
    """Renumbers the used nodes 1..N in gmsh itself (so mesh.msh and mesh.inp agree),
    the box's origin corner first: the step template fixes node 1. A gmsh that
    returned without elements (seen after a retry that cleared the mesh) is an error."""
    if not any(conn for _, _, conn in pieces):
        log = [line for line in gmsh.logger.get() if "rror" in line][-3:]
        raise MeshError("gmsh returned no elements" + (": " + "; ".join(log) if log else ""))
    tags, xyz, _ = gmsh.model.mesh.getNodes()
    coords = {int(t): (float(xyz[3 * i]), float(xyz[3 * i + 1]), float(xyz[3 * i + 2]))
              for i, t in enumerate(tags)}
    used = sorted({n for _, _, conn in pieces for e in conn for n in e})
    corner = min(used, key=lambda n: sum((coords[n][d] - origin[d]) ** 2
                                         for d in range(len(origin))))
    order = [corner] + [n for n in used if n != corner]
    new = {old: i + 1 for i, old in enumerate(order)}
    unused = [int(t) for t in tags if int(t) not in new]
    old_tags = order + unused
    new_tags = list(range(1, len(old_tags) + 1))
    gmsh.model.mesh.renumberNodes(old_tags, new_tags)
    return new, {new[n]: coords[n] for n in order}


def tet_volume(p):
    a = [p[1][i] - p[0][i] for i in range(3)]
    b = [p[2][i] - p[0][i] for i in range(3)]
    c = [p[3][i] - p[0][i] for i in range(3)]
    return (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
            + a[2] * (b[0] * c[1] - b[1] * c[0])) / 6.0


def group_by_grain(volumes):
    out = {}
    for tag, grain in sorted(volumes.items()):
        out.setdefault(None if grain is None else grain["id"], []).append(tag)
    return out


def check_faces(coords, images, origin, size):
    """Every node on a far face is a dependent of a periodic equation."""
    length = max(size)
    for n, p in coords.items():
        far = [d for d in range(len(size)) if on_plane(p[d], origin[d] + size[d], length)]
        if far and n not in images:
            raise MeshError(f"node {n} at {p} lies on a far box face but has no periodic "
                            "partner")



def snap(gmsh, coords, images, size, worst=0.0):
    """Moves each image node exactly onto its partner plus the box lengths it is away
    (`images[node] = (partner, far axes)`), in `coords` and in gmsh; returns the
    largest move, at least `worst`."""
    for node, (image, far) in images.items():
        target = list(coords[image])
        for d in far:
            target[d] += size[d]
        worst = max(worst, max(abs(target[i] - coords[node][i]) for i in range(3)))
        coords[node] = tuple(target)
        gmsh.model.mesh.setNode(node, target, [])
    return worst
