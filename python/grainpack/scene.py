"""Scene.from_toml and Scene.from_dict: the argument handling around the native readers."""

from __future__ import annotations

import json
import os
from typing import Any

import numpy as np

from ._grainpack import Scene


def _from_toml(path_or_text: str | os.PathLike[str]) -> Scene:
    """A scene from a TOML file or TOML text, validated as ``pack SCENE.toml`` does.

    A ``pathlib.Path`` (any ``os.PathLike``) is a file; a ``str`` is TOML text if it
    holds a newline or an ``=`` (every scene has a key), and a file name otherwise.
    Raises :class:`SceneError` with the CLI's message (``file:line:column: key = value:
    reason``; text is named ``<string>``).
    """
    if isinstance(path_or_text, os.PathLike):
        return Scene._from_path(os.fspath(path_or_text))
    if not isinstance(path_or_text, str):
        raise TypeError(f"expected a path or TOML text, got {type(path_or_text).__name__}")
    if "\n" in path_or_text or "=" in path_or_text:
        return Scene._from_text(path_or_text)
    return Scene._from_path(path_or_text)


def _from_dict(scene: dict[str, Any]) -> Scene:
    """A scene from a dict shaped like the TOML file (``{"seed": 1, "box": {...},
    "phase": [{...}, ...]}``), validated as ``pack SCENE.toml`` does.

    Raises :class:`SceneError` naming the key (``<dict>:line:column: phase[0].size.sigma
    = -0.8: must be positive``; the line is that of the dict written as TOML), and
    ``ValueError`` for values TOML cannot hold (None, NaN).
    """
    if not isinstance(scene, dict):
        raise TypeError(f"expected a dict, got {type(scene).__name__}")
    try:
        text = json.dumps(scene, allow_nan=False, default=_plain)
    except ValueError as e:
        raise ValueError(f"the scene holds a value TOML cannot: {e}") from None
    if "null" in text:
        _reject_none(scene, "")
    return Scene._from_json(text)


def _plain(value: Any) -> Any:
    """numpy scalars and arrays, tuples and paths as JSON values."""
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    raise TypeError(f"{type(value).__name__} is not a scene value")


def _reject_none(value: Any, key: str) -> None:
    if value is None:
        raise ValueError(f"{key or 'scene'} = None: TOML has no null; leave the key out")
    if isinstance(value, dict):
        for k, v in value.items():
            _reject_none(v, f"{key}.{k}" if key else str(k))
    elif isinstance(value, (list, tuple)):
        for i, v in enumerate(value):
            _reject_none(v, f"{key}[{i}]")


Scene.from_toml = staticmethod(_from_toml)  # type: ignore[attr-defined]
Scene.from_dict = staticmethod(_from_dict)  # type: ignore[attr-defined]
