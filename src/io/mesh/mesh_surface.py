"""The surface mesh, repaired where gmsh's 2D mesh fails on a packing (issue 29's
fourth round, at 500 grains):

- gmsh leaves triangles invalid on a grain piece's curved surface ("n elements remain
  invalid in surface S"), recovers the surface's edges by splitting every segment of
  a curve, and the curve's periodic copy then mismatches ("curve X has 2k+1 vertices,
  whereas correspondant Y has k"). Repair: Delaunay on the surfaces gmsh names (the
  mismatch goes with them); if that is not enough, the named pair of curves given one
  node count.
- A small piece whose two surfaces share one closed curve (a cap cut off by a box face)
  is meshed on both surfaces with the curve's nodes only: the same triangles twice,
  which HXT refuses ("two overlapping facets"). Repair: twice the segments on the
  shared curves, so both surfaces get inner nodes.

Each repair clears the 2D mesh and meshes again on the same geometry (seconds, against
minutes to rebuild it). Some of gmsh's errors ("Can't find periodic counterpart of mesh
edge") leave it locked: every later generate() of the session answers "I'm busy! Ask me
that later..." and does nothing. The loop then stops with the error, and generate() in
gmsh_mesh.py starts its second attempt in a new session."""

import collections
import re

# gmsh's Delaunay 2D algorithm (Mesh.Algorithm = 5), for the surfaces gmsh reports
# invalid: it recovers the curves' edges where the default (6, Frontal-Delaunay) does
# not on those surfaces.
DELAUNAY_2D = 5
# Rounds of repairs before giving up on the surface mesh (each names new surfaces or
# curves; one or two were enough at 500 grains).
MAX_REPAIRS = 8

MISMATCH = re.compile(r"curve (\d+) has (\d+) vertices, whereas correspondant (\d+) has (\d+)")
INVALID = re.compile(r"invalid in surface (\d+)")
# What gmsh logs, and does nothing else, when an earlier error left it locked.
BUSY = "I'm busy"


def master(gmsh, curve):
    """The curve whose mesh gmsh copies onto `curve` (itself when not periodic)."""
    return int(gmsh.model.mesh.getPeriodic(1, [curve])[0])


def nodes_on(gmsh, curve):
    return len(gmsh.model.mesh.getNodes(1, curve, includeBoundary=True)[0])


def duplicated(gmsh):
    """Pairs of surfaces holding the same triangle (by its three nodes)."""
    seen = collections.defaultdict(set)
    for _, surface in gmsh.model.getEntities(2):
        _, _, nodes = gmsh.model.mesh.getElements(2, surface)
        if not len(nodes):
            continue
        flat = nodes[0]
        for k in range(0, len(flat), 3):
            seen[frozenset(int(n) for n in flat[k:k + 3])].add(surface)
    return {tuple(sorted(s)) for s in seen.values() if len(s) > 1}


def shared_curves(gmsh, a, b):
    def curves(s):
        return {abs(int(t)) for _, t in gmsh.model.getBoundary([(2, s)], oriented=False)}
    return curves(a) & curves(b)


def attempt(gmsh):
    """One 2D mesh: (gmsh's error or None, the surfaces its log calls invalid)."""
    gmsh.logger.stop()
    gmsh.logger.start()
    try:
        gmsh.model.mesh.generate(2)
        error = None
    except Exception as e:  # gmsh raises plain Exception
        error = str(e)
    log = gmsh.logger.get()
    if any(BUSY in line for line in log):
        error = error or BUSY
    invalid = {int(s) for line in log for s in INVALID.findall(line)}
    return error, invalid


def repair(gmsh, error, invalid, delaunay):
    """The repairs for one failed attempt, made on the model; their words."""
    fixes = []
    for s in sorted(invalid - delaunay):
        gmsh.model.mesh.setAlgorithm(2, s, DELAUNAY_2D)
        delaunay.add(s)
        fixes.append(f"Delaunay on surface {s}")
    if fixes or BUSY in (error or ""):
        return fixes
    match = MISMATCH.search(error or "")
    if match:
        a, na, b, nb = map(int, match.groups())
        count = max(na, nb)
        for c in {master(gmsh, a), master(gmsh, b), a, b}:
            gmsh.model.mesh.setTransfiniteCurve(c, count)
        fixes.append(f"{count} nodes on curves {a} and {b}")
    if error is None:
        for s1, s2 in sorted(duplicated(gmsh)):
            for c in sorted(shared_curves(gmsh, s1, s2)):
                count = 2 * nodes_on(gmsh, c) - 1
                for m in {master(gmsh, c), c}:
                    gmsh.model.mesh.setTransfiniteCurve(m, count)
                fixes.append(f"{count} nodes on curve {c} (surfaces {s1} and {s2})")
    return fixes


def surface_mesh(gmsh):
    """Meshes every surface, repairing as above; returns the repairs made (words for
    summary.json). When nothing is left to repair, or the repairs run out, the last
    2D mesh stands, or gmsh's error is raised (the one before the lock, if locked)."""
    repairs = []
    delaunay = set()
    last = None
    for n in range(MAX_REPAIRS + 1):
        error, invalid = attempt(gmsh)
        if error == BUSY:
            raise Exception(f"{last} (and gmsh then refused to mesh again)")
        fixes = repair(gmsh, error, invalid, delaunay) if n < MAX_REPAIRS else []
        if not fixes:
            if error is not None:
                raise Exception(error)
            return repairs
        repairs += fixes
        last = error
        gmsh.model.mesh.clear()
