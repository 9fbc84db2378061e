"""Packing.voxelise on a 2D scene: a pixel image one cell thick, as the CLI's rve.vti."""

from __future__ import annotations

import numpy as np
import pytest

import grainpack as gp

PLANE = {
    "seed": 3,
    "target_fraction": 0.4,
    "box": {"size": [20.0, 10.0], "boundary": "periodic"},
    "phase": [{"name": "discs", "size": {"distribution": "constant", "value": 3.0}}],
}


@pytest.fixture(scope="module")
def plane_packing():
    return gp.pack(gp.Scene.from_dict(PLANE), progress=False)


def test_voxelise_of_a_2d_scene_is_one_cell_thick(plane_packing):
    p = plane_packing
    grid = p.voxelise(40, "matrix")
    # 40 along the longer side, 20 along the other, one layer.
    assert grid.shape == (40, 20, 1)
    assert np.array_equal(p.voxelise((40, 20), "matrix"), grid)
    # The matrix's share of the pixels is about 1 − the area fraction (0.5 per pixel).
    matrix = np.mean(grid == len(p))
    assert abs(matrix - (1 - p.summary["packing_fraction"])) < 0.05, matrix
    for bad in ((40, 20, 1), (4,) * 4):
        with pytest.raises(ValueError, match="resolution"):
            p.voxelise(bad)
