"""The argument checks of the Python package under hypothesis: any argument either works
or raises a typed error that names it (ValueError, TypeError, ArithmeticError,
SceneError), never another exception, a crash or a NaN in a result. As the Rust
fuzz targets (fuzz/README.md) do for files; a few seconds in all."""

from __future__ import annotations

import copy
import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

import grainpack as gp

# Reproducible (derandomized, no example database written) and quick.
QUICK = settings(
    max_examples=150,
    deadline=None,
    derandomize=True,
    database=None,
    suppress_health_check=[HealthCheck.too_slow],
)

# Doubles of every class half the time, moderate ones the other half (definite forms).
DOUBLES = st.floats(allow_nan=True, allow_infinity=True) | st.floats(-4.0, 4.0)

# Four small spheres: valid arguments pack in milliseconds.
TINY = {
    "seed": 1,
    "grains": 4,
    "box": {"size": [20.0, 20.0, 20.0]},
    "phase": [{"size": {"distribution": "constant", "value": 3.0}}],
}


def rows(n: int) -> st.SearchStrategy:
    return st.tuples(*(hnp.arrays(np.float64, (n, k), elements=DOUBLES) for k in (3, 6, 6)))


ANY_SHAPE = hnp.arrays(np.float64, hnp.array_shapes(min_dims=0, max_dims=3, max_side=7), elements=DOUBLES)


@QUICK
@given(st.one_of(st.integers(1, 5).flatmap(rows), st.tuples(ANY_SHAPE, ANY_SHAPE, ANY_SHAPE)))
def test_contact_functions_answer_finitely_or_raise_naming_the_row_or_argument(args):
    for function in (gp.contact_function, gp.overlaps, gp.contact_geometry):
        try:
            answer = function(*args)
        except (ValueError, ArithmeticError) as e:
            message = str(e)
            assert any(word in message for word in ("row", "r12", "q1", "q2", "shape")), message
            continue
        if function is gp.overlaps:
            assert np.asarray(answer).dtype == bool
            continue
        mu2, lam = np.asarray(answer[0]), np.asarray(answer[1])
        assert np.all(np.isfinite(mu2)) and np.all(mu2 >= 0), answer
        assert np.all((lam >= 0) & (lam <= 1)), answer
        if function is gp.contact_geometry:
            assert all(np.all(np.isfinite(np.asarray(x))) for x in answer), answer


JSON_LEAVES = (
    st.none()
    | st.booleans()
    | st.integers(-(2**70), 2**70)
    | st.floats()
    | st.text(max_size=8)
    | st.sampled_from(["constant", "uniform", "lognormal", "periodic", "fixed", "x"])
)
VALUES = st.recursive(
    JSON_LEAVES,
    lambda inner: st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=6), inner, max_size=3),
    max_leaves=6,
)
PATHS = st.sampled_from(
    [
        ("seed",),
        ("grains",),
        ("target_fraction",),
        ("box",),
        ("box", "size"),
        ("box", "boundary"),
        ("phase",),
        ("phase", 0, "size"),
        ("phase", 0, "size", "value"),
        ("phase", 0, "size", "distribution"),
        ("phase", 0, "share"),
        ("phase", 0, "orientation"),
        ("phase", 0, "texture"),
        ("packing",),
        ("packing", "effort"),
        ("output",),
        ("unknown",),
    ]
)


def accepted_or_named(make) -> None:
    try:
        scene = make()
    except gp.SceneError as e:
        assert str(e).startswith(("<dict>:", "<string>:", "cannot read")), str(e)
        return
    except (ValueError, TypeError) as e:
        assert str(e), repr(e)
        return
    assert isinstance(scene, gp.Scene)


@QUICK
@given(st.lists(st.tuples(PATHS, VALUES), max_size=3))
def test_scene_dicts_are_accepted_or_refused_with_a_typed_error(edits):
    scene = copy.deepcopy(TINY)
    for path, value in edits:
        target = scene
        for key in path[:-1]:
            target = target[key] if isinstance(target, dict) and key in target else None
            if isinstance(target, list):
                target = target[0] if target else None
            if not isinstance(target, (dict, list)):
                break
        else:
            if isinstance(target, dict):
                target[path[-1]] = value
    accepted_or_named(lambda: gp.Scene.from_dict(scene))


@QUICK
@given(st.text(max_size=200))
def test_toml_text_is_accepted_or_refused_with_a_typed_error(text):
    accepted_or_named(lambda: gp.Scene.from_toml(text + "\n"))


ARGUMENTS = (
    st.none()
    | st.booleans()
    | st.integers(-(2**70), 2**70)
    | st.integers(-3, 4)
    | st.floats()
    | st.text(max_size=4)
    | st.sampled_from([np.int64(2), np.uint64(2**64 - 1), np.float64(math.nan), [1, 2], ()])
)


@QUICK
@given(seed=ARGUMENTS, threads=ARGUMENTS.filter(lambda t: not (isinstance(t, int) and 4 < t < 2**64)))
def test_pack_arguments_pack_or_raise_naming_the_argument(seed, threads):
    scene = gp.Scene.from_dict(TINY)
    try:
        packing = gp.pack(scene, seed=seed, threads=threads, progress=False)
    except (ValueError, TypeError, OverflowError) as e:
        message = str(e)
        assert "seed" in message or "threads" in message, repr(e)
        return
    assert len(packing) == 4 and np.all(np.isfinite(packing.centres))


@pytest.fixture(scope="module")
def tiny_packing():
    return gp.pack(gp.Scene.from_dict(TINY), progress=False)


# Valid grids of more than 32³ cells are left out for time only (1000³ takes a minute);
# from 2048 per edge on, the library's cell limit refuses them at once.
LARGE_BUT_VALID = range(33, 2048)


@QUICK
@given(
    resolution=st.integers(-2, 24)
    | st.tuples(st.integers(-1, 9), st.integers(-1, 9), st.integers(-1, 9))
    | ARGUMENTS.filter(lambda r: not (isinstance(r, int) and r in LARGE_BUT_VALID)),
    fill=st.sampled_from(["grains", "matrix", "", "Grains", 3]),
    field=st.sampled_from(["material", "phase", "x", None]),
)
def test_voxelise_arguments_give_a_grid_or_raise_naming_the_argument(tiny_packing, resolution, fill, field):
    try:
        grid = tiny_packing.voxelise(resolution, fill, field=field)
    except (ValueError, TypeError, OverflowError) as e:
        message = str(e)
        assert any(word in message for word in ("resolution", "fill", "field", "voxels")), repr(e)
        return
    assert grid.ndim == 3 and grid.size > 0
