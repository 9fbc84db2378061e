"""Shared paths and helpers of the pytest suite (run from anywhere: `pytest python/tests`)."""

from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
DATA = REPO / "tests" / "data"
EXAMPLE = REPO / "configs" / "grains.toml"


def pack_binary() -> Path:
    """The CLI built from this checkout (`cargo build --release`), or `$GRAINPACK_PACK`."""
    path = Path(os.environ.get("GRAINPACK_PACK", REPO / "target" / "release" / "pack"))
    if not path.is_file():
        cargo = shutil.which("cargo")
        assert cargo, f"no CLI at {path} and no cargo to build it"
        subprocess.run(
            [cargo, "build", "--release", "--quiet", "--bin", "pack"],
            cwd=REPO,
            check=True,
            stdin=subprocess.DEVNULL,
        )
    return path


@pytest.fixture(scope="session")
def pack_cli() -> Path:
    return pack_binary()


# A small scene for quick packs: about 60 grains, two phases, every output on.
SMALL_SCENE = {
    "seed": 5,
    "target_fraction": 0.5,
    "box": {"size": [30.0, 30.0, 30.0], "boundary": "periodic"},
    "phase": [
        {
            "name": "matrix",
            "share": 0.7,
            "size": {"distribution": "lognormal", "sigma": 0.3, "scale": 7.0, "min": 4.0, "max": 12.0},
            "aspect_ratio": {"distribution": "uniform", "min": 1.0, "max": 1.5},
            "orientation": {"kind": "random"},
        },
        {
            "name": "needles",
            "share": 0.3,
            "size": {"distribution": "normal", "mean": 6.0, "std": 1.0, "min": 4.0, "max": 8.0},
            "aspect_ratio": {"distribution": "constant", "value": 3.0},
            "orientation": {"kind": "aligned"},
        },
    ],
}
