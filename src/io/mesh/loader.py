"""Runs grainpack's mesher from sources pack hands it: `python3 -c <this file> job.json`
with a JSON object {module name: source} on stdin (src/io/mesh/mod.rs embeds them).
Each becomes an importable module (and its lines show in tracebacks), then
gmsh_mesh.main() runs on job.json."""

import importlib.abc
import importlib.util
import json
import linecache
import sys


class Embedded(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Imports the modules of `sources` before anything on sys.path."""

    def __init__(self, sources):
        self.sources = sources

    def find_spec(self, name, path=None, target=None):
        if name not in self.sources:
            return None
        return importlib.util.spec_from_loader(name, self, origin=f"<grainpack>/{name}.py")

    def create_module(self, spec):
        return None

    def exec_module(self, module):
        origin = module.__spec__.origin
        source = self.sources[module.__name__]
        linecache.cache[origin] = (len(source), None, source.splitlines(True), origin)
        exec(compile(source, origin, "exec"), module.__dict__)


sys.meta_path.insert(0, Embedded(json.load(sys.stdin)))
import gmsh_mesh  # noqa: E402

sys.exit(gmsh_mesh.main())
