"""The grains fill (`mesh_fill = "grains"`): the elements between the grains shared out
among them, as `rve_fill = "grains"` shares the voxels (src/io/voxel/mod.rs): each goes
to the grain that must be scaled least to reach its centroid, the smallest
t = sqrt((x - c)^T Q^-1 (x - c)) over the grains and, in a periodic box, their images;
ties to the lower id. The grains' own elements stay theirs; in mesh.msh the shared-out
elements move to discrete entities of their grain's physical group, and the matrix group
is gone."""

import math

from mesh_common import quaternion_matrix


def inverse_form(grain, dims):
    """Q^-1 = R diag(1/a^2) R^T in the first `dims` coordinates (a 2D grain turns
    about z only, so its in-plane block is the ellipse's), as the upper triangle with
    the off-diagonal entries doubled: t^2 = sum of form[k] * v_i * v_j over i <= j."""
    r = quaternion_matrix(grain["quaternion"])
    a = grain["semi_axes"]
    q = [[sum(r[i][k] * r[j][k] / (a[k] * a[k]) for k in range(dims)) for j in range(dims)]
         for i in range(dims)]
    return tuple(q[i][j] * (1.0 if i == j else 2.0) for i in range(dims) for j in range(i, dims))


def squared_scale(form, v):
    if len(v) == 3:
        x, y, z = v
        return (x * (form[0] * x + form[1] * y + form[2] * z)
                + y * (form[3] * y + form[4] * z) + form[5] * z * z)
    x, y = v
    return x * (form[0] * x + form[1] * y) + form[2] * y * y


class Grains:
    """The grains' centres and images in cells of edge 2 * reach (reach: the largest
    semi-axis), for the query of `nearest`."""

    def __init__(self, job, origin):
        self.dims = dims = len(job["box"])
        size = job["box"]
        self.origin = origin
        self.reach = max(max(g["semi_axes"][:dims]) for g in job["grains"])
        self.cell = 2.0 * self.reach
        shifts = [()]
        for _ in range(dims):
            shifts = [s + (k,) for s in shifts for k in ((-1, 0, 1) if job["periodic"] else (0,))]
        self.table = {}
        for g in job["grains"]:
            form = inverse_form(g, dims)
            for s in shifts:
                c = [g["centre"][d] + s[d] * size[d] for d in range(dims)]
                if any(c[d] < origin[d] - self.cell or c[d] > origin[d] + size[d] + self.cell
                       for d in range(dims)):
                    continue
                self.table.setdefault(self.key(c), []).append((g, c, form))
        self.rings = 1 + max(math.ceil(size[d] / self.cell) for d in range(dims))
        self.shells = [self.shell(r) for r in range(2)]

    def key(self, x):
        return tuple(math.floor((x[d] - self.origin[d]) / self.cell) for d in range(self.dims))

    def shell(self, r):
        """The offsets of the cells at Chebyshev distance exactly r."""
        cells = [()]
        for _ in range(self.dims):
            cells = [c + (k,) for c in cells for k in range(-r, r + 1)]
        return [c for c in cells if max(abs(k) for k in c) == r]

    def nearest(self, x):
        """The grain of smallest t at x. A grain of centre c has t >= |x - c| / reach,
        and the cells within ring r hold every centre nearer x than r cells: once the
        best t is at most r * cell / reach, no grain further out can beat it."""
        here = self.key(x)
        dims = self.dims
        best, best_t2 = None, math.inf
        for r in range(self.rings + 1):
            offsets = self.shells[r] if r < len(self.shells) else self.shell(r)
            for o in offsets:
                k = tuple(here[d] + o[d] for d in range(dims))
                for g, c, form in self.table.get(k, ()):
                    t2 = squared_scale(form, [x[d] - c[d] for d in range(dims)])
                    if t2 < best_t2 or (t2 == best_t2 and g["id"] < best["id"]):
                        best, best_t2 = g, t2
            if best is not None and math.sqrt(best_t2) * self.reach <= r * self.cell:
                break
        return best


def share_out(gmsh, job, entities, pieces, coords, origin, etype):
    """`pieces` (grain or None, element tags, node lists in gmsh's numbering) with the
    matrix's elements given to grains, and gmsh's model regrouped to match for
    mesh.msh. `entities`: gmsh's volumes (surfaces in 2D) and their grain or None;
    `etype`: gmsh's element type of the mesh."""
    dims = len(job["box"])
    corners = dims + 1
    grains = Grains(job, origin)
    kept = [p for p in pieces if p[0] is not None]
    shared = {}
    for grain, tags, conn in pieces:
        if grain is not None:
            continue
        for tag, nodes in zip(tags, conn):
            x = [sum(coords[n][d] for n in nodes[:corners]) / corners for d in range(dims)]
            g = grains.nearest(x)
            entry = shared.setdefault(g["id"], (g, [], []))
            entry[1].append(tag)
            entry[2].append(nodes)
    for tag, grain in entities.items():
        if grain is None:
            gmsh.model.mesh.removeElements(dims, tag)
    own = {}
    for tag, grain in entities.items():
        if grain is not None:
            own.setdefault(grain["id"], []).append(tag)
    for gid, (g, tags, conn) in sorted(shared.items()):
        entity = gmsh.model.addDiscreteEntity(dims)
        flat = [n for nodes in conn for n in nodes]
        gmsh.model.mesh.addElements(dims, entity, [etype], [tags], [flat])
        own.setdefault(gid, []).append(entity)
        kept.append((g, tags, conn))
    gmsh.model.removePhysicalGroups()
    # The name outlives its group in mesh.msh's $PhysicalNames otherwise.
    gmsh.model.removePhysicalName("matrix")
    for gid, tags in sorted(own.items()):
        p = gmsh.model.addPhysicalGroup(dims, tags)
        gmsh.model.setPhysicalName(dims, p, f"grain_{gid}")
    return kept
