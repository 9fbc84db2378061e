"""The public surface: docstrings that help() shows, stubs that match the native module,
and the default progress display."""

from __future__ import annotations

import ast
import importlib.util
import pydoc
import subprocess
import sys
from pathlib import Path

import grainpack as gp
from grainpack import _grainpack
from conftest import EXAMPLE


def test_every_public_name_has_a_docstring_that_help_shows():
    for name in gp.__all__:
        if name == "__version__":
            continue
        obj = getattr(gp, name)
        assert obj.__doc__ and len(obj.__doc__) > 40, name
        assert obj.__doc__.strip().splitlines()[0] in pydoc.render_doc(obj), name
    for method in ("from_toml", "from_dict"):
        assert "SceneError" in getattr(gp.Scene, method).__doc__
    assert "KeyboardInterrupt" in pydoc.render_doc(gp.pack)


def test_the_stubs_declare_what_the_native_module_has():
    stub = Path(gp.__file__).with_name("_grainpack.pyi")
    tree = ast.parse(stub.read_text())
    declared = {n.name for n in tree.body if isinstance(n, (ast.FunctionDef, ast.ClassDef))}
    declared |= {n.target.id for n in tree.body if isinstance(n, ast.AnnAssign)}
    native = {n for n in dir(_grainpack) if not n.startswith("__") or n == "__version__"}
    assert declared == native
    classes = {n.name: n for n in tree.body if isinstance(n, ast.ClassDef)}
    for cls in ("Scene", "_Packing"):
        members = {m.name for m in classes[cls].body if isinstance(m, ast.FunctionDef)}
        runtime = {m for m in dir(getattr(gp, cls) if cls == "Scene" else _grainpack._Packing) if not m.startswith("__")}
        assert members - {"__len__", "__reduce__"} == runtime, cls


def test_the_default_progress_display_when_stderr_is_not_a_terminal():
    script = (
        "import grainpack as gp, sys; "
        f"gp.pack(gp.Scene.from_toml({str(EXAMPLE)!r}), seed=3)"
    )
    run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    if importlib.util.find_spec("tqdm") is None:
        # No tqdm and no terminal: nothing drawn.
        assert run.stderr == ""
    else:
        assert "grains" in run.stderr


def runs_alongside(work) -> bool:
    """Whether a second Python thread runs in the middle half of the time `work` takes
    in this one: it cannot if `work` holds the GIL throughout."""
    import threading
    import time

    done = threading.Event()
    ticks: list[float] = []

    def spin():
        while not done.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    t = threading.Thread(target=spin)
    t.start()
    time.sleep(0.01)
    try:
        start = time.perf_counter()
        work()
        end = time.perf_counter()
    finally:
        done.set()
        t.join()
    quarter = (end - start) / 4
    return any(start + quarter < tick < end - quarter for tick in ticks)


def test_the_gil_is_released_while_contact_functions_and_pack_run():
    import numpy as np

    rng = np.random.default_rng(0)
    n = 400_000
    r12 = rng.uniform(-3, 3, (n, 3))
    q = np.tile([1.0, 0.1, 0.0, 2.0, 0.0, 0.5], (n, 1))
    assert runs_alongside(lambda: gp.contact_function(r12, q, q))
    assert runs_alongside(lambda: gp.overlaps(r12, q, q))
    assert runs_alongside(lambda: gp.contact_geometry(r12, q, q))
    scene = gp.Scene.from_toml(EXAMPLE)
    assert runs_alongside(lambda: gp.pack(scene, progress=False))
