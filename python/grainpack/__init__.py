"""grainpack: packs ellipsoidal grains into a box without overlaps.

The Python face of the Rust library (one native module, no second implementation):

- the narrow phase on numpy arrays: :func:`contact_function`, :func:`overlaps`,
  :func:`contact_geometry`, with pw85's argument layout;
- scenes and packing: :class:`Scene` (``from_toml``, ``from_dict``), :func:`pack`
  returning a :class:`Packing` (numpy grain table, ``summary``, ``write``,
  ``voxelise``, ``to_pyvista``);
- :class:`SceneError`, raised with the CLI's message for a scene it would refuse.

Quadratic forms are given as the 6 entries of their upper triangle, row-major
(``q[0] q[1] q[2] / q[3] q[4] / q[5]``), as in pw85: ``Q = R diag(a1², a2², a3²) Rᵀ``
for an ellipsoid of semi-axes ``a`` along the columns of ``R``.
"""

from ._grainpack import Scene, SceneError, __version__
from . import scene as _scene  # noqa: F401  (adds Scene.from_toml and Scene.from_dict)
from .contact import (
    ContactGeometry,
    ContactResult,
    contact_function,
    contact_geometry,
    ellipse_form,
    overlaps,
    quadratic_form,
    rotation_matrices,
)
from .packing import Packing, pack

__all__ = [
    "ContactGeometry",
    "ContactResult",
    "Packing",
    "Scene",
    "SceneError",
    "contact_function",
    "contact_geometry",
    "ellipse_form",
    "overlaps",
    "pack",
    "quadratic_form",
    "rotation_matrices",
    "__version__",
]
