"""Type stubs of the native module `grainpack._grainpack` (PyO3). Users import from
`grainpack`; the functions ending in `_rows` take checked C-contiguous float64 arrays
and are wrapped there."""

from __future__ import annotations

import os
from typing import Any, Callable

import numpy as np
import numpy.typing as npt

__version__: str

class SceneError(ValueError):
    """A scene `pack` would refuse, with the CLI's message."""

    file: str | None
    line: int | None
    column: int | None
    key: str | None
    value: str | None

class Scene:
    """A validated scene (box, phases, packing parameters, outputs). Immutable."""

    @staticmethod
    def from_toml(path_or_text: str | os.PathLike[str]) -> Scene: ...
    @staticmethod
    def from_dict(scene: dict[str, Any]) -> Scene: ...
    @staticmethod
    def _from_path(path: str | os.PathLike[str]) -> Scene: ...
    @staticmethod
    def _from_text(text: str, name: str | None = None) -> Scene: ...
    @staticmethod
    def _from_json(json: str) -> Scene: ...
    def __reduce__(self) -> tuple[Any, tuple[str, str]]: ...
    @property
    def toml(self) -> str: ...
    @property
    def seed(self) -> int: ...
    @property
    def box_size(self) -> tuple[float, ...]: ...
    @property
    def dimension(self) -> int: ...
    @property
    def boundary(self) -> str: ...
    @property
    def phases(self) -> list[str]: ...
    @property
    def expected_count(self) -> float: ...
    @property
    def units(self) -> dict[str, str]: ...
    @property
    def warnings(self) -> list[str]: ...
    @property
    def output_dir(self) -> str: ...

class _Packing:
    def _grain_table(self) -> dict[str, npt.NDArray[Any] | list[str]]: ...
    def _summary_json(self) -> str: ...
    def _write(self, dir: str | os.PathLike[str]) -> list[str]: ...
    def _voxelise(
        self, cells: list[int], fill: str
    ) -> tuple[npt.NDArray[np.uint32], npt.NDArray[np.uint32], tuple[int, int, int]]: ...
    def _mesh(
        self, dir: str | os.PathLike[str], size: float, order: int, fill: str, python: str
    ) -> tuple[list[str], str]: ...
    @property
    def box_size(self) -> tuple[float, float, float]: ...
    @property
    def seed(self) -> int: ...
    @property
    def stop_reason(self) -> str: ...
    @property
    def phase_names(self) -> list[str]: ...
    def __len__(self) -> int: ...

def contact_function_rows(
    r12: npt.NDArray[np.float64], q1: npt.NDArray[np.float64], q2: npt.NDArray[np.float64]
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]: ...
def overlaps_rows(
    r12: npt.NDArray[np.float64], q1: npt.NDArray[np.float64], q2: npt.NDArray[np.float64]
) -> npt.NDArray[np.bool_]: ...
def contact_geometry_rows(
    r12: npt.NDArray[np.float64], q1: npt.NDArray[np.float64], q2: npt.NDArray[np.float64]
) -> tuple[
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
]: ...
def pack_scene(
    scene: Scene,
    seed: int | None = None,
    threads: int | None = None,
    progress: Callable[[int, float, float, int], Any] | None = None,
) -> _Packing: ...
def _rust_batch_seconds(
    r12: npt.NDArray[np.float64],
    q1: npt.NDArray[np.float64],
    q2: npt.NDArray[np.float64],
    rounds: int,
) -> list[float]: ...
