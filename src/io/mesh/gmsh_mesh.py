"""grainpack's conforming mesher: packed ellipsoids and their matrix meshed by gmsh.

`pack` runs this script (embedded in the binary) with the `python3` it finds, as
`python3 -c <this file> job.json`; the job (written by src/io/mesh/job.rs) holds the
box, the grains, the mesh options, the materials and the output paths. It writes
mesh.msh, mesh.inp and mesh.vtu to the temporary paths the job names (pack renames them
when everything succeeded) and a JSON of what it measured to job["stats"].

Pipeline (issue 29's findings): each grain an affinely transformed OCC sphere; the
images of the grains crossing the box cut to it and fragmented with it, the others
holes of the matrix (build_geometry); the packing's window is shifted so every
grain clears the box faces by a margin (thin caps mesh badly);
opposite faces paired by centre of mass and area, then setPeriodic; HXT for the
volume; a retry with curvature-driven sizes when gmsh's periodic copy of a curve fails;
periodic nodes paired by coordinates and snapped exactly onto their images plus the
box length.
"""

import json
import math
import sys
import time

# Exit code for "gmsh could not mesh this packing" (pack maps it to its message).
EXIT_MESH_FAILED = 3

# A face piece matches its opposite when its boundary, moved across the box, lies on
# the other's to this fraction of the box length (OCC's curves of the images of one
# grain agree to about 1e-9 L).
FACE_MATCH_TOL = 1e-6
# A mesh node is on a box face when within this fraction of the box length of it.
ON_FACE_TOL = 1e-7
# OCC's bounding boxes are loose (by 3e-5 L in issue 29, by 1.1e-4 L seen since): the
# slack of the coarse filter on them; the exact test is on boundary samples.
BOX_SLACK = 1e-2
# Points sampled per boundary curve to recognise and pair face pieces.
CURVE_SAMPLES = 8
# The window shift is searched on this many candidates per axis.
SHIFT_CANDIDATES = 4096
# A node on a far face and its image on the near ones lie this fraction of the box
# length apart at most after the translation (gmsh's copies: 1e-8 L, issue 29).
PAIR_TOL = 1e-6
# Curvature-driven sizing used on the retry (elements per 2 pi of curvature).
RETRY_CURVATURE = 24


def quaternion_matrix(q):
    w, x, y, z = q
    n = math.sqrt(w * w + x * x + y * y + z * z)
    w, x, y, z = w / n, x / n, y / n, z / n
    return [
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
    ]


def half_extents(grain):
    """Half-widths of the grain's axis-aligned bounding box (exact for an ellipsoid)."""
    r = quaternion_matrix(grain["quaternion"])
    a = grain["semi_axes"]
    return [math.sqrt(sum((r[i][k] * a[k]) ** 2 for k in range(3))) for i in range(3)]


def best_shift(lows, highs, length):
    """The shift s in [0, L) maximising the least distance from a face (0 mod L) to any
    grain's tangent planes, and that distance."""
    best, best_margin = 0.0, -1.0
    for i in range(SHIFT_CANDIDATES):
        s = length * i / SHIFT_CANDIDATES
        margin = math.inf
        for v in lows + highs:
            t = (v + s) % length
            margin = min(margin, t, length - t)
            if margin <= best_margin:
                break
        if margin > best_margin:
            best, best_margin = s, margin
    return best, best_margin


def window(job):
    """Origin of the meshed box: the packing's box shifted (periodic only) so that no
    grain's tangent plane lies near a face; and the margin reached per axis."""
    size = job["box"]
    if not job["periodic"]:
        return [0.0, 0.0, 0.0], [None, None, None]
    origin, margins = [], []
    for d in range(3):
        lows = [g["centre"][d] - g["extent"][d] for g in job["grains"]]
        highs = [g["centre"][d] + g["extent"][d] for g in job["grains"]]
        s, m = best_shift(lows, highs, size[d])
        # Shifting the grains by s is meshing the window [-s, L - s) of the packing.
        origin.append(-s)
        margins.append(m)
    return origin, margins


def images(grain, origin, size, periodic):
    """The grain's translations that meet the box [origin, origin + size)."""
    shifts = [[0.0]] * 3
    if periodic:
        shifts = []
        for d in range(3):
            c, e = grain["centre"][d], grain["extent"][d]
            # The copy nearest the window, then its neighbours if they reach in.
            k0 = math.floor((c - origin[d]) / size[d])
            base = c - k0 * size[d]
            options = [base - size[d], base, base + size[d]]
            shifts.append([p - c for p in options
                           if p + e > origin[d] and p - e < origin[d] + size[d]])
    return [(a, b, c) for a in shifts[0] for b in shifts[1] for c in shifts[2]]


def ellipsoid(occ, grain, shift):
    r = quaternion_matrix(grain["quaternion"])
    a = grain["semi_axes"]
    s = occ.addSphere(0, 0, 0, 1)
    m = []
    for i in range(3):
        m += [r[i][0] * a[0], r[i][1] * a[1], r[i][2] * a[2], grain["centre"][i] + shift[i]]
    occ.affineTransform([(3, s)], m)
    return s


def contains(box, lo, hi):
    return all(box[d] <= lo[d] and hi[d] <= box[d + 3] for d in range(3))


def build_geometry(gmsh, job, origin):
    """The box's volumes: {tag: grain, or None for the matrix}.

    OCC's fragment of the box with every ellipsoid is slow (issue 29: it dominates)
    and mostly needless, as the grains are disjoint. So each image of a grain that
    crosses the box is cut to the box alone, and only these pieces, which touch the
    box's faces but not one another, are fragmented with the box (in OCC's glue mode,
    3x faster than a plain fragment of the ellipsoids with the box). The grains
    inside are added as they are: their surfaces become holes of the matrix volume,
    which so shares them, and the mesh is conforming."""
    occ = gmsh.model.occ
    size = job["box"]
    box = occ.addBox(origin[0], origin[1], origin[2], size[0], size[1], size[2])
    tools, owner, inner = [], [], []
    for g in job["grains"]:
        shifts = images(g, origin, size, job["periodic"])
        crossing = job["periodic"] and (len(shifts) > 1 or any(
            g["centre"][d] + shifts[0][d] - g["extent"][d] < origin[d]
            or g["centre"][d] + shifts[0][d] + g["extent"][d] > origin[d] + size[d]
            for d in range(3)))
        for t in shifts:
            tag = ellipsoid(occ, g, t)
            if not crossing:
                inner.append((tag, g, t))
                continue
            # The image's piece in the box, alone: a boolean of one ellipsoid and a box.
            cutter = occ.addBox(origin[0], origin[1], origin[2], size[0], size[1], size[2])
            piece, _ = occ.intersect([(3, tag)], [(3, cutter)])
            for dim_tag in piece:
                tools.append(dim_tag)
                owner.append(g)
    children = [[(3, box)]]
    if tools:
        # The pieces only touch the box's faces and one another's never: OCC's glue
        # mode for arguments that share (parts of) faces is 3x faster.
        gmsh.option.setNumber("Geometry.OCCBooleanGlue", 1)
        _, children = occ.fragment([(3, box)], tools)
        gmsh.option.setNumber("Geometry.OCCBooleanGlue", 0)
    occ.synchronize()
    pieces = {tag for _, tag in children[0]}
    volumes = {tag: None for tag in pieces}
    for g, kids in zip(owner, children[1:]):
        for _, tag in kids:
            if tag not in pieces:
                raise MeshError(f"a piece of grain {g['id']} lies outside the box")
            volumes[tag] = g
    matrix = [t for t, g in volumes.items() if g is None]
    holes = {t: [] for t in matrix}
    # The matrix piece of an inner grain: of those whose bounding box holds the grain's,
    # the largest (the box's matrix; the others are pockets the crossing grains cut
    # off at the box's faces, too small to hold a grain).
    mass = {t: occ.getMass(3, t) for t in matrix}
    for tag, g, t in inner:
        lo = [g["centre"][d] + t[d] - g["extent"][d] for d in range(3)]
        hi = [g["centre"][d] + t[d] + g["extent"][d] for d in range(3)]
        home = [t for t in matrix if contains(gmsh.model.getBoundingBox(3, t), lo, hi)]
        if not home:
            raise MeshError(f"grain {g['id']} lies in no piece of the matrix")
        holes[max(home, key=mass.get)].append(tag)
        volumes[tag] = g
    # OCC's shape fixing would rebuild (copy) some trimmed faces of the new matrix
    # volume, which then no longer shares them with the grain pieces: cracks, which
    # the homogeneous CalculiX check of tools/check_mesh.py caught (E 3 % low).
    gmsh.option.setNumber("Geometry.OCCAutoFix", 0)
    for t in matrix:
        if not holes[t]:
            continue
        loops = [occ.addSurfaceLoop([s for _, s in gmsh.model.getBoundary([(3, v)],
                                                                          oriented=False)])
                 for v in [t] + holes[t]]
        occ.remove([(3, t)])
        new = occ.addVolume(loops)
        del volumes[t]
        volumes[new] = None
    occ.synchronize()
    return volumes


def face_pieces(gmsh, origin, size):
    """Per axis d: (near, far) lists of (surface tag, bounding box) of the box faces'
    pieces: the surfaces flat in d whose every boundary sample lies on the plane."""
    faces = [([], []) for _ in range(3)]
    length = max(size)
    for _, s in gmsh.model.getEntities(2):
        box = gmsh.model.getBoundingBox(2, s)
        points = boundary_samples(gmsh, s)
        for d in range(3):
            if box[d + 3] - box[d] > BOX_SLACK * length:
                continue
            for side in (0, 1):
                plane = origin[d] + side * size[d]
                if all(abs(p[d] - plane) < FACE_MATCH_TOL * length for p in points):
                    faces[d][side].append((s, box, points))
    return faces


def boundary_samples(gmsh, surface):
    """Points sampled along every boundary curve of a surface (ends excluded)."""
    points = []
    for _, c in gmsh.model.getBoundary([(2, surface)], oriented=False):
        lo, hi = gmsh.model.getParametrizationBounds(1, abs(c))
        ts = [lo[0] + (hi[0] - lo[0]) * (i + 0.5) / CURVE_SAMPLES for i in range(CURVE_SAMPLES)]
        xyz = gmsh.model.getValue(1, abs(c), ts)
        points += [xyz[3 * i:3 * i + 3] for i in range(len(ts))]
    return points


def distance_to_boundary(gmsh, surface, point):
    best = math.inf
    for _, c in gmsh.model.getBoundary([(2, surface)], oriented=False):
        q, _ = gmsh.model.getClosestPoint(1, abs(c), point)
        best = min(best, math.dist(q, point))
    return best


def make_periodic(gmsh, origin, size):
    """Pairs each far face piece with the near piece whose boundary it is translated
    from (every sampled boundary point of the far piece, moved back by the box length,
    lies on the near piece's boundary), and makes the far piece periodic of it."""
    faces = face_pieces(gmsh, origin, size)
    length = max(size)
    pairs = 0
    for d in range(3):
        near, far = faces[d]
        if len(near) != len(far):
            raise MeshError(f"the box faces normal to {'xyz'[d]} have {len(near)} and "
                            f"{len(far)} pieces: the geometry is not periodic")
        used = set()
        for s, box, points in far:
            match = None
            for t, nbox, _ in near:
                if t in used or any(abs(nbox[i] - box[i]) > BOX_SLACK * length
                                    or abs(nbox[i + 3] - box[i + 3]) > BOX_SLACK * length
                                    for i in range(3) if i != d):
                    continue
                moved = [[p[i] - (size[d] if i == d else 0.0) for i in range(3)]
                         for p in points]
                if all(distance_to_boundary(gmsh, t, p) < FACE_MATCH_TOL * length
                       for p in moved):
                    match = t
                    break
            if match is None:
                raise MeshError(f"face piece {s} on the far {'xyz'[d]} face has no partner "
                                "on the near face")
            used.add(match)
            affine = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]
            affine[4 * d + 3] = size[d]
            gmsh.model.mesh.setPeriodic(2, [s], [match], affine)
            pairs += 1
    return pairs


class MeshError(Exception):
    pass


def generate(gmsh, job):
    """Meshes in 3D; on gmsh's failure of a periodic curve copy, once more with sizes
    from curvature. Returns the retry flag."""
    try:
        gmsh.model.mesh.generate(3)
        return False
    except Exception as first:  # gmsh raises plain Exception
        text = str(first) + " " + " ".join(gmsh.logger.get()[-20:])
        if "correspondant" not in text and "corresponding" not in text:
            raise MeshError(str(first)) from None
        gmsh.model.mesh.clear()
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", RETRY_CURVATURE)
        try:
            gmsh.model.mesh.generate(3)
        except Exception as second:
            raise MeshError(f"{second} (after a retry with Mesh.MeshSizeFromCurvature = "
                            f"{RETRY_CURVATURE}; first: {first})") from None
        return True


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
        far = [d for d in range(3) if on_plane(p[d], origin[d] + size[d], length)]
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
        return {d for d in range(3) if on_plane(coords[n][d], origin[d] + size[d], length)}

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


def on_plane(x, plane, length):
    return abs(x - plane) < ON_FACE_TOL * length


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
    the box's origin corner first: the step template fixes node 1."""
    tags, xyz, _ = gmsh.model.mesh.getNodes()
    coords = {int(t): (float(xyz[3 * i]), float(xyz[3 * i + 1]), float(xyz[3 * i + 2]))
              for i, t in enumerate(tags)}
    used = sorted({n for _, _, conn in pieces for e in conn for n in e})
    corner = min(used, key=lambda n: sum((coords[n][d] - origin[d]) ** 2 for d in range(3)))
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


def percentile(sorted_values, q):
    if not sorted_values:
        return None
    i = min(len(sorted_values) - 1, max(0, int(math.floor(q * (len(sorted_values) - 1)))))
    return sorted_values[i]


def write_list(f, header, ids):
    f.write(header + "\n")
    ids = list(ids)
    for i in range(0, len(ids), 16):
        f.write(", ".join(str(n) for n in ids[i:i + 16]) + "\n")


# CalculiX reads at most 20 characters per number of a data line.
CCX_FIELD = 20


def num(x):
    """x in at most CCX_FIELD characters: repr when it fits (it reads back exactly),
    else fewer significant digits (a tiny coordinate such as -1.907386087041541e-05)."""
    text = repr(float(x))
    digits = 16
    while len(text) > CCX_FIELD:
        text = "%.*g" % (digits, x)
        digits -= 1
    return text


def write_inp(path, job, coords, elements, images, origin):
    """mesh.inp: the layout of rve.inp (src/io/decks/abaqus.rs) on the tetrahedra."""
    size = job["box"]
    order = job["order"]
    n_nodes = len(coords)
    rp = [n_nodes + 1, n_nodes + 2, n_nodes + 3]
    with open(path, "w") as f:
        f.write("*Heading\n")
        f.write(f"grainpack conforming mesh: {len(elements)} C3D{4 if order == 1 else 10} "
                f"elements, box {size[0]!r} x {size[1]!r} x {size[2]!r} "
                f"{job['length_unit']} from ({origin[0]!r}, {origin[1]!r}, {origin[2]!r}), "
                f"{'periodic' if job['periodic'] else 'not periodic'}\n")
        f.write(f"** units (the scene's [units]): lengths in {job['length_unit']}, "
                f"stresses and E in {job['stress_unit']}, forces in "
                f"{job['stress_unit']}*{job['length_unit']}^2\n")
        f.write("** nodes and elements numbered as in mesh.msh; element sets GRAIN_<id> "
                "(grains.csv's id), one per phase and the matrix\n*Node\n")
        for n in range(1, n_nodes + 1):
            x, y, z = coords[n]
            f.write(f"{n}, {num(x)}, {num(y)}, {num(z)}\n")
        for d in range(3):
            at = list(origin)
            at[d] += size[d]
            f.write(f"{rp[d]}, {num(at[0])}, {num(at[1])}, {num(at[2])}\n")
        f.write(f"*Element, type=C3D{4 if order == 1 else 10}\n")
        for e, (_, conn, _, _) in enumerate(elements):
            f.write(f"{e + 1}, " + ", ".join(str(n) for n in conn) + "\n")
        by_grain, by_phase = {}, {}
        for e, (grain, _, _, _) in enumerate(elements):
            key = None if grain is None else grain["id"]
            by_grain.setdefault(key, []).append(e + 1)
            phase = job["matrix_phase"] if grain is None else grain["phase"]
            by_phase.setdefault(phase, []).append(e + 1)
        for g in sorted(k for k in by_grain if k is not None):
            write_list(f, f"*Elset, elset=GRAIN_{g}", by_grain[g])
        for m in job["materials"]:
            if m["phase"] in by_phase:
                write_list(f, f"*Elset, elset={m['name']}", by_phase[m["phase"]])
        write_node_sets(f, coords, origin, size)
        for name, id_ in zip(["RPX", "RPY", "RPZ"], rp):
            f.write(f"*Nset, nset={name}\n{id_}\n")
        f.write("*Nset, nset=RP\nRPX, RPY, RPZ\n")
        if job["periodic"]:
            f.write("*Equation\n")
            for node in sorted(images):
                image, far = images[node]
                for dof in (1, 2, 3):
                    terms = [(node, 1.0), (image, -1.0)] + [(rp[d], -1.0) for d in far]
                    f.write(f"{len(terms)}\n")
                    for i in range(0, len(terms), 4):
                        f.write(", ".join(f"{n}, {dof}, {c!r}" for n, c in terms[i:i + 4])
                                + "\n")
        for m in job["materials"]:
            if m["phase"] not in by_phase:
                continue
            f.write(f"*Material, name={m['name']}\n*Elastic\n{m['young']!r}, {m['poisson']!r}\n")
            f.write(f"*Solid Section, elset={m['name']}, material={m['name']}\n")
        strain = job["strain"]
        f.write(f"{job['step_marker']}: uniaxial strain {strain:e} along x\n")
        f.write("*Boundary\n1, 1, 3, 0.0\n*Step\n*Static\n*Boundary\n")
        if job["periodic"]:
            f.write(f"RPX, 1, 1, {strain * size[0]!r}\n")
            f.write("RPX, 2, 3, 0.0\nRPY, 1, 1, 0.0\nRPY, 3, 3, 0.0\nRPZ, 1, 2, 0.0\n")
            f.write("*Node Print, nset=RP\nU\n*Node Print, nset=X1, totals=only\nRF\n")
        else:
            f.write("X0, 1, 1, 0.0\nY0, 2, 2, 0.0\nZ0, 3, 3, 0.0\n")
            f.write(f"X1, 1, 1, {strain * size[0]!r}\n")
            f.write("*Node Print, nset=X1, totals=only\nRF\n")
        f.write("*End Step\n")


def write_node_sets(f, coords, origin, size):
    """Faces X0 ... Z1, edges X0Y0 ..., corners X0Y0Z0 ..., as in rve.inp."""
    length = max(size)
    side = {}
    for n, p in coords.items():
        s = []
        for d in range(3):
            if on_plane(p[d], origin[d], length):
                s.append(1)
            elif on_plane(p[d], origin[d] + size[d], length):
                s.append(2)
            else:
                s.append(0)
        side[n] = s
    for fixed in (1, 2, 3):
        for mask in range(27):
            sides = [mask % 3, (mask // 3) % 3, mask // 9]
            if sum(1 for s in sides if s) != fixed:
                continue
            name = "".join(f"{'XYZ'[d]}{sides[d] - 1}" for d in range(3) if sides[d])
            ids = [n for n in sorted(coords)
                   if all(sides[d] == 0 or side[n][d] == sides[d] for d in range(3))]
            write_list(f, f"*Nset, nset={name}", ids)


def write_vtu(path, coords, elements, order, phases):
    """mesh.vtu: the tetrahedra with cell data grain (-1: matrix), phase (the matrix
    is phase `phases`, as in rve.vti) and SICN."""
    vtk_type = 10 if order == 1 else 24
    n_nodes = len(coords)
    with open(path, "w") as f:
        f.write('<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="1.0" '
                'byte_order="LittleEndian" header_type="UInt64">\n<UnstructuredGrid>\n')
        f.write(f'<Piece NumberOfPoints="{n_nodes}" NumberOfCells="{len(elements)}">\n')
        f.write('<Points>\n<DataArray type="Float64" NumberOfComponents="3" '
                'format="ascii">\n')
        for n in range(1, n_nodes + 1):
            f.write("%r %r %r\n" % coords[n])
        f.write("</DataArray>\n</Points>\n<Cells>\n")
        f.write('<DataArray type="Int64" Name="connectivity" format="ascii">\n')
        for _, conn, _, _ in elements:
            f.write(" ".join(str(n - 1) for n in conn) + "\n")
        f.write('</DataArray>\n<DataArray type="Int64" Name="offsets" format="ascii">\n')
        npe = 4 if order == 1 else 10
        f.write(" ".join(str(npe * (i + 1)) for i in range(len(elements))) + "\n")
        f.write('</DataArray>\n<DataArray type="UInt8" Name="types" format="ascii">\n')
        f.write(" ".join([str(vtk_type)] * len(elements)) + "\n")
        f.write("</DataArray>\n</Cells>\n<CellData>\n")
        f.write('<DataArray type="Int32" Name="grain" format="ascii">\n')
        f.write(" ".join(str(-1 if g is None else g["id"]) for g, _, _, _ in elements) + "\n")
        f.write('</DataArray>\n<DataArray type="Int32" Name="phase" format="ascii">\n')
        f.write(" ".join(str(phases if g is None else g["phase"]) for g, _, _, _ in elements)
                + "\n")
        f.write('</DataArray>\n<DataArray type="Float64" Name="sicn" format="ascii">\n')
        f.write(" ".join(repr(q) for _, _, q, _ in elements) + "\n")
        f.write("</DataArray>\n</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n")


def mesh(gmsh, job):
    """Everything after gmsh.initialize(); returns the stats."""
    size = job["box"]
    length = max(size)
    for g in job["grains"]:
        g["extent"] = half_extents(g)
    started = time.monotonic()
    origin, margins = window(job)
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.option.setNumber("General.NumThreads", job["threads"])
    gmsh.option.setNumber("Geometry.OCCParallel", 1)
    gmsh.model.add("grainpack")
    volumes = build_geometry(gmsh, job, origin)
    pairs = make_periodic(gmsh, origin, size) if job["periodic"] else 0
    for gid, tags in group_by_grain(volumes).items():
        p = gmsh.model.addPhysicalGroup(3, tags)
        gmsh.model.setPhysicalName(3, p, "matrix" if gid is None else f"grain_{gid}")
    geometry_seconds = time.monotonic() - started
    gmsh.option.setNumber("Mesh.MeshSizeMax", job["element_size"])
    gmsh.option.setNumber("Mesh.Algorithm3D", 10)
    gmsh.option.setNumber("Mesh.ElementOrder", job["order"])
    gmsh.option.setNumber("Mesh.SecondOrderLinear", 0)
    # Middle nodes moved onto the curved surfaces invert some thin elements (3 of 12k
    # seen): gmsh's elastic-and-optimisation pass untangles them.
    gmsh.option.setNumber("Mesh.HighOrderOptimize", 2)
    gmsh.logger.start()
    retried = generate(gmsh, job)
    pieces = extract(gmsh, volumes, job["order"])
    new, coords = number_nodes(gmsh, pieces, origin)
    images = {}
    if job["periodic"]:
        # The vertices by coordinates; the middle nodes of quadratic elements, which
        # gmsh's high-order optimisation moves on each side alike but not exactly,
        # by their edges (mid_images).
        vertices = {new[n] for _, _, conn in pieces for e in conn for n in e[:4]}
        images = pair_by_coordinates({n: coords[n] for n in vertices}, origin, size)
        worst = 0.0
        for node, (image, far) in images.items():
            target = list(coords[image])
            for d in far:
                target[d] += size[d]
            worst = max(worst, max(abs(target[i] - coords[node][i]) for i in range(3)))
            coords[node] = tuple(target)
            gmsh.model.mesh.setNode(node, target, [])
        if job["order"] == 2:
            conns = [[new[n] for n in e] for _, _, conn in pieces for e in conn]
            conns = [[e[i] for i in TET10_ORDER] for e in conns]
            middles = mid_images(conns, coords, images, origin, size)
            for node, (image, far) in middles.items():
                target = list(coords[image])
                for d in far:
                    target[d] += size[d]
                worst = max(worst, max(abs(target[i] - coords[node][i]) for i in range(3)))
                coords[node] = tuple(target)
                gmsh.model.mesh.setNode(node, target, [])
            images.update(middles)
        check_faces(coords, images, origin, size)
    else:
        worst = 0.0
    mesh_seconds = time.monotonic() - started - geometry_seconds
    elements = []
    npe = 4 if job["order"] == 1 else 10
    for grain, tags, conn in pieces:
        quality = gmsh.model.mesh.getElementQualities(tags, "minSICN")
        for e, q in zip(conn, quality):
            nodes = [new[n] for n in e]
            if npe == 10:
                nodes = [nodes[i] for i in TET10_ORDER]
            vol = tet_volume([coords[n] for n in nodes[:4]])
            elements.append((grain, nodes, float(q), vol))
    sicn = sorted(q for _, _, q, _ in elements)
    inverted = sum(1 for q in sicn if q <= 0.0)
    if inverted:
        raise MeshError(f"{inverted} of {len(sicn)} elements are inverted (SICN <= 0)")
    files = job["files"]
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    gmsh.write(files["msh"])
    write_inp(files["inp"], job, coords, elements, images, origin)
    write_vtu(files["vtu"], coords, elements, job["order"], job["matrix_phase"])
    box_volume = size[0] * size[1] * size[2]
    phases = {}
    for grain, _, _, vol in elements:
        p = job["matrix_phase"] if grain is None else grain["phase"]
        phases[p] = phases.get(p, 0.0) + vol
    exact = {}
    for g in job["grains"]:
        a = g["semi_axes"]
        exact[g["phase"]] = exact.get(g["phase"], 0.0) + 4.0 / 3.0 * math.pi * a[0] * a[1] * a[2]
    exact[job["matrix_phase"]] = box_volume - sum(exact.values())
    return {
        "elements": len(elements),
        "nodes": len(coords),
        "order": job["order"],
        "element_size": job["element_size"],
        "min_sicn": sicn[0],
        "p1_sicn": percentile(sicn, 0.01),
        "geometry_seconds": geometry_seconds,
        "mesh_seconds": mesh_seconds,
        "retried_with_curvature": retried,
        "origin": origin,
        "face_margin": margins if job["periodic"] else None,
        "periodic_face_pairs": pairs,
        "periodic_nodes": len(images),
        "largest_snap": worst,
        "phase_volume_fractions": [
            {"phase": p, "mesh": phases.get(p, 0.0) / box_volume,
             "exact": exact.get(p, 0.0) / box_volume}
            for p in sorted(set(phases) | set(exact))
        ],
        "gmsh": gmsh.__version__,
    }


def group_by_grain(volumes):
    out = {}
    for tag, grain in sorted(volumes.items()):
        out.setdefault(None if grain is None else grain["id"], []).append(tag)
    return out


def check_faces(coords, images, origin, size):
    """Every node on a far face is a dependent of a periodic equation."""
    length = max(size)
    for n, p in coords.items():
        far = [d for d in range(3) if on_plane(p[d], origin[d] + size[d], length)]
        if far and n not in images:
            raise MeshError(f"node {n} at {p} lies on a far box face but has no periodic "
                            "partner")


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
        stats = mesh(gmsh, job)
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
