#!/usr/bin/env python3
"""Renders the user guide's pictures (docs/img/) from the actual output of `pack`.

    python tools/render_guide.py [--pack target/release/pack] [--work DIR] [--only SCENE ...]

Packs every scene of `configs/` as the tutorials and the gallery do (same seed, same
options), draws each packing's grains in 3D with PyVista off-screen (`grains.vtu`,
coloured by phase, the box outlined; a 2D scene's own `packing.png` instead), and copies the figures `pack` itself draws
(`sections.png`, `statistics.png`, `pole_figures.png`) that the pages show, each
scaled down and reduced to a palette so that all of docs/img stays a few hundred kB,
and the README's picture (the example's grains beside its RVE's mid-sections).
It prints the gallery's Markdown table of every scene's figures (grains, fraction
reached, stop reason: the same on any machine for a seed). Needs the pinned venv of
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
    # 2D scenes: pack's own picture of the packing stands for the 3D render.
    "fibres_2d": ("fibres", ["packing"]),
    "ellipses_2d": ("ellipses", ["packing"]),
}
# Scenes whose grains are drawn by pack itself (packing.png): no PyVista render.
PLANE = {"fibres_2d", "ellipses_2d"}
# Width in pixels of the 3D renders, and the widest a copied figure may be.
RENDER_PX = 400
FIGURE_MAX_PX = 900
# Colours of the palette a picture is reduced to (PNG size falls about 3-fold).
PALETTE_COLOURS = 48
# The grains of a one-phase scene (a light steel blue).
SINGLE_PHASE_COLOUR = "#8fb3d9"
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
    if len(np.unique(grains.cell_data["phase"])) > 1:
        plotter.add_mesh(grains, scalars="phase", cmap="tab10", clim=[0, 9], show_scalar_bar=False,
                         smooth_shading=True)
    else:
        plotter.add_mesh(grains, color=SINGLE_PHASE_COLOUR, smooth_shading=True)
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
    parser.add_argument("--only", nargs="+", metavar="SCENE", help="render only these scenes (stems)")
    args = parser.parse_args()
    pack = str(Path(args.pack).resolve())
    work = (args.work or Path(tempfile.mkdtemp(prefix="render_guide_"))).resolve()
    work.mkdir(parents=True, exist_ok=True)
    IMG.mkdir(parents=True, exist_ok=True)
    rows = []
    for stem, (name, figures) in SCENES.items():
        if args.only and stem not in args.only:
            continue
        out = work / stem
        status = subprocess.run([pack, str(ROOT / "configs" / f"{stem}.toml"), "--out", str(out), "--quiet"],
                                cwd=work).returncode
        if status not in (0, 3):  # 3: the target not reached, the densest packing written
            print(f"pack failed on {stem} with exit code {status}")
            return 1
        if stem not in PLANE:
            render(out, IMG / f"{name}-grains.png", VIEW.get(stem))
        for figure in figures:
            save_small(Image.open(out / f"{figure}.png"), IMG / f"{name}-{figure.replace('_', '-')}.png", FIGURE_MAX_PX)
        s = json.loads((out / "summary.json").read_text())
        rows.append(f"| [`{stem}.toml`](../configs/{stem}.toml) | {s['grains']} | {s['packing_fraction']:.4f} "
                    f"({s['target_fraction']:.4f}) | {s['stop_reason'].replace('_', ' ')} |")
    if args.only and "grains" not in args.only:
        print("\n".join(rows))
        return 0
    # The README's picture: the example's grains beside the mid-sections of its RVE.
    left, right = Image.open(IMG / "first-grains.png"), Image.open(work / "grains" / "sections.png")
    right = right.resize((round(right.width * left.height / right.height), left.height), Image.LANCZOS)
    both = Image.new("RGB", (left.width + right.width, left.height), "white")
    both.paste(left.convert("RGB"), (0, 0))
    both.paste(right.convert("RGB"), (left.width, 0))
    save_small(both, IMG / "readme.png", both.width)
    print("| scene | grains | fraction (target) | stop |")
    print("|---|---:|---:|---|")
    print("\n".join(rows))
    total = sum(p.stat().st_size for p in IMG.glob("*.png"))
    print(f"docs/img: {len(list(IMG.glob('*.png')))} pictures, {total / 1024:.0f} kB", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
