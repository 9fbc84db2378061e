#!/usr/bin/env python3
"""Writes the scenes of this folder: 10 000 grains of three classes in a periodic box
sized so that the grains at full size would fill FRACTION of it, for FRACTION from 0.60
to 0.72 in steps of 0.02 (issue 27: the time of a packing should not depend on where
its request starts relative to the jamming point).

  python3 benches/density/start/make_scenes.py

Classes (the grains are the same draws as the scenes one folder up, seed 1):
- mono: equal spheres of diameter 2 (mono_periodic.toml);
- lognormal: lognormal diameters, sigma 0.25 (lognormal_periodic.toml; their total
  volume is that of lognormal_periodic_064.toml, whose box of side 44.1803 holds them at
  0.64);
- spheroids_frozen: prolate spheroids of aspect 1.5, volume of a sphere of diameter 2,
  orientations frozen as drawn (density_spheroids_frozen.toml, 10 000 of them).
"""
import math
import pathlib

HERE = pathlib.Path(__file__).resolve().parent
GRAINS = 10_000
SPHERE = 4.0 / 3.0 * math.pi  # a sphere of diameter 2
VOLUMES = {
    "mono": GRAINS * SPHERE,
    "lognormal": 0.64 * 44.1803**3,
    "spheroids_frozen": GRAINS * SPHERE,
}
PHASES = {
    "mono": 'size = { distribution = "constant", value = 2.0 }',
    "lognormal": 'size = { distribution = "lognormal", sigma = 0.25, scale = 2.0, '
    "min = 0.5, max = 8.0 }",
    "spheroids_frozen": 'size = { distribution = "constant", value = 2.0 }\n'
    'aspect_ratio = { distribution = "constant", value = 1.5 }',
}
FRACTIONS = [0.60, 0.62, 0.64, 0.66, 0.68, 0.70, 0.72]

for name, volume in VOLUMES.items():
    for phi in FRACTIONS:
        side = (volume / phi) ** (1.0 / 3.0)
        text = f"""# Written by make_scenes.py: {GRAINS} grains ({name}) in a periodic box that they
# would fill to {phi:.2f} at full size.
seed = 1
grains = {GRAINS}

[box]
size = [{side:.4f}, {side:.4f}, {side:.4f}]
boundary = "periodic"

[[phase]]
name = "{name}"
{PHASES[name]}

[output]
grains_csv = false
vtk = false
centers = false
statistics_png = false
"""
        (HERE / f"{name}_{round(phi * 100):03d}.toml").write_text(text)
