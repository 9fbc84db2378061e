"""What every part of grainpack's mesher shares: its error, the on-a-face test, the
rotation of a grain and a percentile."""

import math

# A mesh node is on a box face when within this fraction of the box length of it.
ON_FACE_TOL = 1e-7


class MeshError(Exception):
    """gmsh, or the pipeline around it, could not mesh the packing (pack reports the
    message; no mesh file is left)."""


def on_plane(x, plane, length):
    return abs(x - plane) < ON_FACE_TOL * length


def quaternion_matrix(q):
    w, x, y, z = q
    n = math.sqrt(w * w + x * x + y * y + z * z)
    w, x, y, z = w / n, x / n, y / n, z / n
    return [
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
    ]



def percentile(sorted_values, q):
    if not sorted_values:
        return None
    i = min(len(sorted_values) - 1, max(0, int(math.floor(q * (len(sorted_values) - 1)))))
    return sorted_values[i]

