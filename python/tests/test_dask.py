"""examples/ensemble_dask.py on a LocalCluster: 4 small realisations as Dask tasks."""

from __future__ import annotations

import importlib.util
import json

import pytest

from conftest import REPO, SMALL_SCENE

pytest.importorskip("dask.distributed")


def load_example():
    spec = importlib.util.spec_from_file_location("ensemble_dask", REPO / "examples" / "ensemble_dask.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def small_scene_toml() -> str:
    s = SMALL_SCENE
    lines = [f"seed = {s['seed']}", f"target_fraction = {s['target_fraction']}", "[box]",
             f"size = {json.dumps(s['box']['size'])}", f"boundary = \"{s['box']['boundary']}\""]
    for phase in s["phase"]:
        lines += ["[[phase]]", f"name = \"{phase['name']}\"", f"share = {phase['share']}"]
        for table in ("size", "aspect_ratio", "orientation"):
            lines.append(f"[phase.{table}]")
            lines += [f"{k} = {json.dumps(v)}" for k, v in phase[table].items()]
    return "\n".join(lines) + "\n"


def test_the_dask_example_packs_four_seeds_on_a_local_cluster(tmp_path):
    import grainpack as gp

    scene = tmp_path / "small.toml"
    scene.write_text(small_scene_toml())
    table = tmp_path / "table.csv"
    example = load_example()
    rows = example.main(
        [str(scene), "--seeds", "4", "--workers", "2", "--table", str(table), "--out", str(tmp_path / "runs")]
    )
    assert [r["seed"] for r in rows] == [1, 2, 3, 4]
    assert all(r["stop_reason"] == "target_reached" for r in rows)
    assert table.read_text().splitlines()[0].startswith("seed,grains,packing_fraction")
    assert len(table.read_text().splitlines()) == 5
    # Each task's row is its realisation: the same as packing that seed here.
    for r in rows:
        local = gp.pack(gp.Scene.from_toml(scene), seed=r["seed"], progress=False).summary
        assert (r["grains"], r["packing_fraction"]) == (local["grains"], local["packing_fraction"])
        assert r["matrix.diameter.ks"] == local["phases"][0]["diameter"]["ks_distance"]
        assert (tmp_path / "runs" / f"seed-{r['seed']}" / "summary.json").is_file()
    # Different seeds, different realisations.
    assert len({r["packing_fraction"] for r in rows}) == 4
