#!/usr/bin/env python3
"""Renders the user guide's pictures (docs/img/) from the actual output of `pack`.

    python tools/render_guide.py [--pack target/release/pack] [--work DIR]

Packs every scene of `configs/` as the tutorials and the gallery do (same seed, same
options), draws each packing's grains in 3D with PyVista off-screen (`grains.vtu`,
coloured by phase, the box outlined), and copies the figures `pack` itself draws
(`sections.png`, `statistics.png`, `pole_figures.png`) that the pages show, each
scaled down and reduced to a palette so that all of docs/img stays a few hundred kB.
It prints a Markdown table of every scene's figures (grains, fraction reached, stop
reason, packing time) for the gallery. Needs the pinned venv of
tools/requirements-exports.txt (PyVista, VTK with its off-screen renderer; pillow).
Not run by CI: run it when a scene, or what `pack` draws, changes, and commit
docs/img.
"""

import argparse
import json
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import pyvista as pv
from PIL import Image

ROOT = Path(__file__).resolve().parent.parent
IMG = ROOT / "docs" / "img"

# scene stem -> (picture name, figures of pack's own to copy as <name>-<figure>.png).
SCENES = {
    "grains": ("first", ["sections", "statistics"]),
    "polycrystal": ("poly", ["sections", "pole_figures"]),
    "composite": ("composite", ["sections"]),
    "fuller_concrete": ("concrete", ["statistics"]),
    "measured_grains": ("measured", []),
    "rolled_pancakes": ("rolled", ["statistics"]),
    "textured": ("textured", []),
    "kanapy_elongated": ("kanapy", []),
    "density_spheres": ("spheres", []),
    "density_spheroids": ("spheroids", []),
}
# Width in pixels of the 3D renders, and the widest a copied figure may be.
RENDER_PX = 480
FIGURE_MAX_PX = 900
# Colours of the palette a picture is reduced to (PNG size falls about 3-fold).
PALETTE_COLOURS = 64
# Where the camera looks from, per scene: the rolled sheet along TD shows the pancakes
# edge-on; the others from an oblique corner.
VIEW = {"rolled_pancakes": "xz"}


def save_small(image: Image.Image, path: Path, width: int) -> None:
    if image.width > width:
        image = image.resize((width, round(image.height * width / image.width)), Image.LANCZOS)
    image.convert("RGB").quantize(PALETTE_COLOURS, method=Image.Quantize.MEDIANCUT).save(path, optimize=True)


def render(out_dir: Path, path: Path, view: str | None) -> None:
    grains = pv.read(out_dir / "grains.vtu")
    box = json.loads((out_dir / "summary.json").read_text())["box"]
    plotter = pv.Plotter(off_screen=True, window_size=(RENDER_PX, RENDER_PX))
    plotter.set_background("white")
    phases = np.unique(grains.cell_data["phase"])
    plotter.add_mesh(grains, scalars="phase", cmap="tab10" if len(phases) > 1 else None,
                     color=None if len(phases) > 1 else "#8fb3d9", show_scalar_bar=False,
                     clim=[0, 9] if len(phases) > 1 else None, smooth_shading=True)
    plotter.add_mesh(pv.Box(bounds=(0, box[0], 0, box[1], 0, box[2])).outline(), color="black", line_width=2)
    if view == "xz":
        plotter.view_xz()
    else:
        plotter.view_isometric()
    plotter.camera.zoom(1.1)
    shot = plotter.screenshot(return_img=True)
    plotter.close()
    save_small(Image.fromarray(shot), path, RENDER_PX)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--pack", default=str(ROOT / "target" / "release" / "pack"))
    parser.add_argument("--work", type=Path, help="pack into DIR/<scene> and keep it")
    args = parser.parse_args()
    pack = str(Path(args.pack).resolve())
    work = (args.work or Path(tempfile.mkdtemp(prefix="render_guide_"))).resolve()
    work.mkdir(parents=True, exist_ok=True)
    IMG.mkdir(parents=True, exist_ok=True)
    rows = []
    for stem, (name, figures) in SCENES.items():
        out = work / stem
        status = subprocess.run([pack, str(ROOT / "configs" / f"{stem}.toml"), "--out", str(out), "--quiet"],
                                cwd=work).returncode
        if status not in (0, 3):  # 3: the target not reached, the densest packing written
            print(f"pack failed on {stem} with exit code {status}")
            return 1
        render(out, IMG / f"{name}-grains.png", VIEW.get(stem))
        for figure in figures:
            save_small(Image.open(out / f"{figure}.png"), IMG / f"{name}-{figure.replace('_', '-')}.png", FIGURE_MAX_PX)
        s = json.loads((out / "summary.json").read_text())
        rows.append(f"| `configs/{stem}.toml` | {s['grains']} | {s['packing_fraction']:.4f} "
                    f"({s['target_fraction']:.4f}) | {s['stop_reason']} | {s['timings']['packing']:.2f} s |")
    print("| scene | grains | fraction (target) | stop | packing time |")
    print("|---|---:|---:|---|---:|")
    print("\n".join(rows))
    total = sum(p.stat().st_size for p in IMG.glob("*.png"))
    print(f"docs/img: {len(list(IMG.glob('*.png')))} pictures, {total / 1024:.0f} kB", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
