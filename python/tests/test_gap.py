"""`packing.gap` through the Python package: Scene.from_toml reads it, the packing keeps
it by the independent check of overlap_check.py (numpy only), and a bad gap is a
SceneError naming the key."""

from __future__ import annotations

import math

import numpy as np
import pytest

import grainpack as gp
from overlap_check import check

GAP = 0.1

# About 90 spheroids of aspect 1-2 at 0.4 of a periodic cube, kept 0.1 of each pair's
# size apart: as grains, the loop packs them at 0.4 * 1.1^3 = 0.53.
SCENE = f"""
seed = 3
target_fraction = 0.4
[box]
size = [30.0, 30.0, 30.0]
[[phase]]
size = {{ distribution = "lognormal", sigma = 0.2, scale = 5.0, min = 3.0, max = 8.0 }}
aspect_ratio = {{ distribution = "uniform", min = 1.0, max = 2.0 }}
[packing]
gap = {GAP}
"""


def test_the_gap_is_kept_between_every_pair_by_an_independent_check():
    p = gp.pack(gp.Scene.from_toml(SCENE), progress=False)
    assert p.stop_reason == "target_reached"
    # Two grains keep the gap when, each scaled by 1 + gap about its centre, they do not
    # overlap: the independent check, on the grains so scaled.
    candidates, overlapping, min_mu2 = check(
        p.centres, p.semi_axes * (1 + GAP), p.quaternions, p.box_size, periodic=True
    )
    assert overlapping == 0 and candidates > 0
    s = p.summary
    assert s["gap"] == GAP and s["checked_pairs"] == candidates
    # μ of the grains is (1 + gap) μ of the scaled ones. The summary's smallest gap is
    # over these pairs and a few further out (up to 5 % beyond the gap), so at most
    # theirs; golden section and the exact function both within 1e-13 of the truth, so
    # 1e-9 is generous.
    assert GAP <= s["min_gap"] <= math.sqrt(min_mu2) * (1 + GAP) - 1 + 1e-9
    # The fraction is of the grains themselves, not of the scaled ones.
    volume = np.sum(4 / 3 * np.pi * np.prod(p.semi_axes, axis=1)) / 30.0**3
    assert abs(volume - s["packing_fraction"]) <= 1e-12
    assert abs(s["packing_fraction"] - 0.4) < 0.02


@pytest.mark.parametrize("gap", ["-0.1", "nan"])
def test_a_bad_gap_is_a_scene_error_naming_the_key(gap):
    with pytest.raises(gp.SceneError, match=rf"^<string>:10:7: packing.gap = {gap}: must be a finite number"):
        gp.Scene.from_toml(SCENE.replace(f"gap = {GAP}", f"gap = {gap}"))
