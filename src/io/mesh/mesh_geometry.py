"""The OCC geometry of a 3D packing: the window, the grains' images, the box
fragmented with the grains that cross it, the matrix with the others as holes, and
the pairing of opposite face pieces for setPeriodic."""

import math

from mesh_common import MeshError, quaternion_matrix

# A face piece matches its opposite when its boundary, moved across the box, lies on
# the other's to this fraction of the box length (OCC's curves of the images of one
# grain agree to about 1e-9 L).
FACE_MATCH_TOL = 1e-6
# OCC's bounding boxes are loose (by 3e-5 L in issue 29, by 1.1e-4 L seen since): the
# slack of the coarse filter on them; the exact test is on boundary samples.
BOX_SLACK = 1e-2
# Points sampled per boundary curve to recognise and pair face pieces.
CURVE_SAMPLES = 8
# The window shift is searched on this many candidates per axis.
SHIFT_CANDIDATES = 4096


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
    grain's tangent plane lies near a face; and the margin reached per axis (the
    rectangle's two in 2D)."""
    size = job["box"]
    if not job["periodic"]:
        return [0.0] * len(size), [None] * len(size)
    origin, margins = [], []
    for d in range(len(size)):
        lows = [g["centre"][d] - g["extent"][d] for g in job["grains"]]
        highs = [g["centre"][d] + g["extent"][d] for g in job["grains"]]
        s, m = best_shift(lows, highs, size[d])
        # Shifting the grains by s is meshing the window [-s, L - s) of the packing.
        origin.append(-s)
        margins.append(m)
    return origin, margins


def images(grain, origin, size, periodic):
    """The grain's translations that meet the box [origin, origin + size) (in 2D the
    rectangle: the shift along z is 0)."""
    shifts = [[0.0]] * 3
    if periodic:
        shifts = [[0.0]] * (3 - len(size))
        for d in reversed(range(len(size))):
            c, e = grain["centre"][d], grain["extent"][d]
            # The copy nearest the window, then its neighbours if they reach in.
            k0 = math.floor((c - origin[d]) / size[d])
            base = c - k0 * size[d]
            options = [base - size[d], base, base + size[d]]
            shifts.insert(0, [p - c for p in options
                              if p + e > origin[d] and p - e < origin[d] + size[d]])
    return [(a, b, c) for a in shifts[0] for b in shifts[1] for c in shifts[2]]


def frame(u):
    """An orthonormal basis (columns) whose third vector is the unit vector u."""
    helper = [1.0, 0.0, 0.0] if abs(u[0]) < 0.9 else [0.0, 1.0, 0.0]
    e1 = [helper[(i + 1) % 3] * u[(i + 2) % 3] - helper[(i + 2) % 3] * u[(i + 1) % 3]
          for i in range(3)]
    n = math.sqrt(sum(x * x for x in e1))
    e1 = [x / n for x in e1]
    e2 = [u[(i + 1) % 3] * e1[(i + 2) % 3] - u[(i + 2) % 3] * e1[(i + 1) % 3] for i in range(3)]
    return [[e1[i], e2[i], u[i]] for i in range(3)]


def ellipsoid_map(grain, origin, size):
    """The affine map (3 x 3 matrix, the centre apart) taking OCC's unit sphere to the
    grain, with the sphere's poles (degenerate points of its parametrization, where
    gmsh's surface meshes of cut pieces failed: issue 29's "HXT 3D mesh failed" and
    "curve X has n vertices, whereas correspondant Y has m") put on the grain's two
    tangent points along the axis whose poles lie farthest from every box face. The
    sphere turned first is the same sphere, so the grain is the same."""
    r = quaternion_matrix(grain["quaternion"])
    a = grain["semi_axes"]
    m = [[r[i][k] * a[k] for k in range(3)] for i in range(3)]
    best, best_clear = None, -1.0
    for d in range(3):
        # The tangent points along d: c +- M u with u = M^T e_d / |M^T e_d|.
        mt = [m[d][k] for k in range(3)]
        n = math.sqrt(sum(x * x for x in mt))
        u = [x / n for x in mt]
        offset = [sum(m[i][k] * u[k] for k in range(3)) for i in range(3)]
        clear = math.inf
        for sign in (1.0, -1.0):
            for i in range(len(size)):
                t = (grain["centre"][i] + sign * offset[i] - origin[i]) % size[i]
                clear = min(clear, t, size[i] - t)
        if clear > best_clear:
            best, best_clear = u, clear
    p = frame(best)
    return [[sum(m[i][k] * p[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def ellipsoid(occ, grain, shift, linear):
    """The grain moved by `shift` as an OCC volume; `linear` from ellipsoid_map."""
    s = occ.addSphere(0, 0, 0, 1)
    m = []
    for i in range(3):
        m += linear[i] + [grain["centre"][i] + shift[i]]
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
        linear = ellipsoid_map(g, origin, size)
        for t in shifts:
            tag = ellipsoid(occ, g, t, linear)
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
