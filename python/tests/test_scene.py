"""Scenes from TOML and dicts: the CLI's validation, its messages, located errors."""

from __future__ import annotations

import copy
import subprocess
from pathlib import Path

import numpy as np
import pytest

import grainpack as gp
from conftest import EXAMPLE, SMALL_SCENE

TOML = """seed = 5
grains = 60

[box]
size = [30.0, 30.0, 30.0]
boundary = "periodic"

[[phase]]
name = "matrix"
share = 1.0
size = { distribution = "lognormal", sigma = 0.3, scale = 6.0, min = 4.0, max = 9.0 }
aspect_ratio = { distribution = "uniform", min = 1.0, max = 2.0 }
orientation = { kind = "random" }
"""

# (name, bad text, line, key path): as tests/cli_pack/main.rs's bad scenes.
BAD = [
    ("syntax", TOML.replace("grains = 60", "grains = = 60"), 2, None),
    ("unknown_key", TOML.replace('boundary = "periodic"', 'boundery = "periodic"'), 6, "box.boundery"),
    ("negative_size", TOML.replace("[30.0, 30.0, 30.0]", "[30.0, -30.0, 30.0]"), 5, "box.size"),
    ("reversed_cutoffs", TOML.replace("min = 4.0, max = 9.0", "min = 9.0, max = 4.0"), 11, "phase[0].size.max"),
    ("fraction_0_9", TOML.replace("grains = 60", "target_fraction = 0.9"), 2, "target_fraction"),
]


def test_the_example_reads_from_a_path_a_str_path_and_text():
    by_path = gp.Scene.from_toml(EXAMPLE)
    by_str = gp.Scene.from_toml(str(EXAMPLE))
    by_text = gp.Scene.from_toml(EXAMPLE.read_text())
    for s in (by_path, by_str, by_text):
        assert s.seed == 1 and s.phases == ["matrix", "needles"]
        assert s.box_size == (65.0, 65.0, 65.0) and s.boundary == "periodic"
    assert "target_fraction=0.6" in repr(by_path)


def test_from_dict_is_the_same_scene_as_its_toml():
    scene = copy.deepcopy(SMALL_SCENE)
    scene["box"]["size"] = np.array([30.0, 30.0, 30.0])  # numpy values are accepted
    a = gp.pack(gp.Scene.from_dict(scene), progress=False)
    b = gp.pack(gp.Scene.from_toml(TOML_OF_SMALL), progress=False)
    np.testing.assert_array_equal(a.centres, b.centres)
    assert a.summary["grains"] == b.summary["grains"]


TOML_OF_SMALL = """seed = 5
target_fraction = 0.5
[box]
size = [30.0, 30.0, 30.0]
boundary = "periodic"
[[phase]]
name = "matrix"
share = 0.7
size = { distribution = "lognormal", sigma = 0.3, scale = 7.0, min = 4.0, max = 12.0 }
aspect_ratio = { distribution = "uniform", min = 1.0, max = 1.5 }
orientation = { kind = "random" }
[[phase]]
name = "needles"
share = 0.3
size = { distribution = "normal", mean = 6.0, std = 1.0, min = 4.0, max = 8.0 }
aspect_ratio = { distribution = "constant", value = 3.0 }
orientation = { kind = "aligned" }
"""


@pytest.mark.parametrize("name, text, line, key", BAD, ids=[b[0] for b in BAD])
def test_bad_scenes_raise_scene_error_with_the_clis_message(tmp_path, pack_cli, name, text, line, key):
    path = tmp_path / "scene.toml"
    path.write_text(text)
    with pytest.raises(gp.SceneError) as caught:
        gp.Scene.from_toml(path)
    e = caught.value
    assert isinstance(e, ValueError)
    assert (e.file, e.line, e.key) == (str(path), line, key)
    assert str(e).startswith(f"{path}:{line}:")
    # The CLI, on the same file: exit code 2 and the same message.
    run = subprocess.run([pack_cli, path, "--out", tmp_path / "out"], capture_output=True, text=True)
    assert run.returncode == 2
    assert run.stderr.strip() == f"pack: error: {e}"
    assert not (tmp_path / "out").exists()


def test_errors_in_text_and_dicts_are_located_by_key():
    with pytest.raises(gp.SceneError, match=r"^<string>:5:8: box.size = \[30.0, -30.0, 30.0\]"):
        gp.Scene.from_toml(BAD[2][1])
    scene = copy.deepcopy(SMALL_SCENE)
    scene["phase"][1]["size"]["std"] = -1.0
    with pytest.raises(gp.SceneError) as caught:
        gp.Scene.from_dict(scene)
    assert caught.value.key == "phase[1].size.std" and caught.value.file == "<dict>"
    assert caught.value.value == "-1.0"
    scene = copy.deepcopy(SMALL_SCENE)
    scene["box"]["colour"] = "red"
    with pytest.raises(gp.SceneError, match="box.colour"):
        gp.Scene.from_dict(scene)
    with pytest.raises(ValueError, match=r"^box.boundary = None"):
        gp.Scene.from_dict({**SMALL_SCENE, "box": {"size": [30.0] * 3, "boundary": None}})
    with pytest.raises(ValueError, match="TOML cannot"):
        gp.Scene.from_dict({**SMALL_SCENE, "target_fraction": float("nan")})
    with pytest.raises(TypeError):
        gp.Scene.from_dict([("seed", 1)])


def test_a_missing_file_is_a_scene_error_naming_it(tmp_path):
    missing = tmp_path / "nowhere.toml"
    with pytest.raises(gp.SceneError, match=f"^cannot read scene file {missing}: ") as caught:
        gp.Scene.from_toml(missing)
    assert caught.value.file == str(missing) and caught.value.line is None


def test_scenes_pickle_as_their_toml_and_are_validated_again(tmp_path):
    import pickle

    for scene in (gp.Scene.from_toml(EXAMPLE), gp.Scene.from_dict(SMALL_SCENE), gp.Scene.from_toml(TOML)):
        copy_ = pickle.loads(pickle.dumps(scene))
        assert repr(copy_) == repr(scene) and copy_.toml == scene.toml
        a = gp.pack(scene, seed=3, progress=False) if scene.expected_count < 100 else None
        if a is not None:
            np.testing.assert_array_equal(gp.pack(copy_, seed=3, progress=False).centres, a.centres)
    assert gp.Scene.from_toml(EXAMPLE).toml == EXAMPLE.read_text()


def test_units_are_read_repeated_in_the_summary_and_warned_about():
    default = gp.Scene.from_toml(TOML)
    assert default.units == {"length": "um", "stress": "MPa"} and default.warnings == []
    stated = TOML + '[units]\nlength = "mm"\nstress = "GPa"\n'
    scene = gp.Scene.from_dict({**SMALL_SCENE, "units": {"length": "mm", "stress": "GPa"}})
    assert gp.Scene.from_toml(stated).units == {"length": "mm", "stress": "GPa"} == scene.units
    packing = gp.pack(scene, progress=False)
    assert packing.summary["units"] == {"length": "mm", "stress": "GPa"}
    assert packing.summary["warnings"] == []
    # A box of 30 m: allowed, with a warning naming the key, repeated in the summary.
    big = gp.Scene.from_toml(TOML + '[units]\nlength = "m"\n')
    assert len(big.warnings) == 1 and "box.size = [30.0, 30.0, 30.0]" in big.warnings[0]
    assert gp.pack(big, progress=False).summary["warnings"] == big.warnings
    # A unit that is not one is a SceneError naming the key.
    with pytest.raises(gp.SceneError, match=r'units\.stress = "mpa"') as e:
        gp.Scene.from_toml(TOML + '[units]\nstress = "mpa"\n')
    assert e.value.key == "units.stress"


def test_2d_scenes_read_with_their_dimension_and_rectangle():
    fibres = gp.Scene.from_toml(Path(__file__).parents[2] / "configs" / "fibres_2d.toml")
    assert fibres.dimension == 2 and fibres.box_size == (60.0, 60.0)
    assert "box=(60, 60)" in repr(fibres)
    assert gp.Scene.from_toml(TOML).dimension == 3
    flat = TOML.replace("[30.0, 30.0, 30.0]", "[30.0, 20.0]").replace("grains = 60", "grains = 10")
    scene = gp.Scene.from_toml(flat)
    assert scene.dimension == 2 and scene.box_size == (30.0, 20.0)
    # The same scene as a dict, and a 3D-only key refused naming it.
    as_dict = {
        "grains": 10,
        "box": {"size": [30.0, 20.0]},
        "phase": [{"size": {"distribution": "constant", "value": 4.0}}],
    }
    assert gp.Scene.from_dict(as_dict).dimension == 2
    bad = flat.replace('kind = "random"', 'kind = "fisher"')
    refused = r'phase\[0\]\.orientation\.kind = "fisher": has no meaning in a 2D scene'
    with pytest.raises(gp.SceneError, match=refused) as caught:
        gp.Scene.from_toml(bad)
    assert caught.value.key == "phase[0].orientation.kind"
