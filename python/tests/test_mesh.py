"""Packing.mesh: the conforming mesh through gmsh (skipped without gmsh), the same
files as `pack` with `[output] mesh = true`, and its refusals."""

from __future__ import annotations

import os

import numpy as np
import pytest

import grainpack as gp

SCENE = """
seed = 1
target_fraction = 0.2
[box]
size = [10.0, 10.0, 10.0]
[packing]
gap = {gap}
[[phase]]
size = {{ distribution = "uniform", min = 2.5, max = 4.0 }}
aspect_ratio = {{ distribution = "uniform", min = 1.2, max = 2.0 }}
elastic = {{ E = 210.0, nu = 0.3 }}
"""


def test_a_packing_without_the_gap_is_refused_naming_packing_gap():
    p = gp.pack(gp.Scene.from_toml(SCENE.format(gap=0.0)), progress=False)
    with pytest.raises(ValueError, match="packing.gap = 0: a mesh needs a gap"):
        p.mesh("unused")


def test_bad_sizes_and_orders_are_refused():
    p = gp.pack(gp.Scene.from_toml(SCENE.format(gap=0.05)), progress=False)
    with pytest.raises(ValueError, match="size = 5"):
        p.mesh("unused", size=5.0)
    with pytest.raises(ValueError, match="order = 3"):
        p.mesh("unused", order=3)
    with pytest.raises(ValueError, match="fill = 'voids'"):
        p.mesh("unused", fill="voids")


def test_the_mesh_holds_every_grain_and_fills_the_box(tmp_path):
    pytest.importorskip("gmsh")
    p = gp.pack(gp.Scene.from_toml(SCENE.format(gap=0.05)), progress=False)
    out = p.mesh(tmp_path / "m", size=0.3)
    assert [os.path.basename(f) for f in out["files"]] == ["mesh.msh", "mesh.inp", "mesh.vtu"]
    assert all(os.path.getsize(f) > 0 for f in out["files"])
    summary = out["summary"]
    assert summary["elements"] > 0 and summary["min_sicn"] > 0
    grid = out["grid"]
    if grid is None:
        return
    assert grid.n_cells == summary["elements"]
    # Every grain has elements; the cells' volumes fill the box (periodic, no gaps).
    assert set(np.unique(grid.cell_data["grain"])) == set(p.ids.tolist()) | {-1}
    volume = grid.compute_cell_sizes(length=False, area=False)["Volume"].sum()
    assert abs(volume / 1000.0 - 1.0) < 1e-9


PLANE_SCENE = """
seed = 5
target_fraction = 0.5
[box]
size = [10.0, 8.0]
[packing]
gap = 0.05
[[phase]]
size = { distribution = "uniform", min = 1.8, max = 2.8 }
aspect_ratio = { distribution = "uniform", min = 1.0, max = 1.8 }
elastic = { E = 100.0, nu = 0.3 }
"""


def test_a_2d_packing_is_meshed_as_plane_strain_triangles(tmp_path):
    pytest.importorskip("gmsh")
    p = gp.pack(gp.Scene.from_toml(PLANE_SCENE), progress=False)
    out = p.mesh(tmp_path / "m", size=0.3, order=2)
    summary = out["summary"]
    assert summary["order"] == 2 and summary["min_sicn"] > 0
    assert len(summary["origin"]) == 2
    with open(out["files"][1]) as f:
        deck = f.read()
    assert "*Element, type=CPE6" in deck and "*Nset, nset=RPY" in deck
    assert "*Nset, nset=RPZ" not in deck
    grid = out["grid"]
    if grid is None:
        return
    assert grid.n_cells == summary["elements"]
    assert set(np.unique(grid.cell_data["grain"])) == set(p.ids.tolist()) | {-1}
    # The triangles fill the rectangle (curved or not: their edges are shared).
    area = grid.compute_cell_sizes(length=False, area=True, volume=False)["Area"].sum()
    assert abs(area / 80.0 - 1.0) < 1e-9


def test_the_grains_fill_gives_every_element_to_a_grain(tmp_path):
    pytest.importorskip("gmsh")
    p = gp.pack(gp.Scene.from_toml(PLANE_SCENE), progress=False)
    out = p.mesh(tmp_path / "m", fill="grains")
    fractions = out["summary"]["phase_volume_fractions"]
    assert [f["phase"] for f in fractions] == [0]
    assert abs(fractions[0]["mesh"] - 1.0) < 1e-9
    with open(out["files"][1]) as f:
        deck = f.read()
    assert "MATRIX" not in deck
    grid = out["grid"]
    if grid is None:
        return
    assert set(np.unique(grid.cell_data["grain"])) == set(p.ids.tolist())
