//! Three orthogonal mid-sections of a voxel grid, as one PNG.

use super::{VoxelError, VoxelGrid};
use crate::contact::Dimension;
use crate::scene::RveFill;
use plotters::prelude::*;
use std::path::{Path, PathBuf};

/// Pixels for the longest box edge in each panel.
const PANEL_PIXELS: f64 = 420.0;

/// Matrix colour: dark grey, apart from every grain colour (lightness ≥ 0.45).
const MATRIX: RGBColor = RGBColor(45, 45, 45);

/// Draws the sections `xy` at `z = Lz/2`, `xz` at `y = Ly/2` and `yz` at `x = Lx/2` side
/// by side (in 2D only the one layer, `xy`), each voxel coloured by its material (a fixed colour per material number,
/// the matrix dark grey), with axes in box units, to the PNG `path` (written under a
/// temporary name and renamed, so a reader never sees half a file).
///
/// The section at `z = Lz/2` is cell layer `Nz / 2` (integer division), the layer whose
/// lower face is `Lz/2` when `Nz` is even and the one containing it when odd.
pub fn write_sections_png(grid: &VoxelGrid, path: &Path) -> Result<(), VoxelError> {
    register_font()?;
    let tmp = temporary_name(path);
    let result = draw(grid, &tmp);
    match result {
        Ok(()) => std::fs::rename(&tmp, path).map_err(VoxelError::Io),
        Err(e) => {
            let _ = std::fs::remove_file(&tmp);
            Err(e)
        }
    }
}

/// One panel: the two in-plane axes, the fixed axis and its cell layer.
struct Section {
    axes: [usize; 2],
    fixed: usize,
}

const NAMES: [&str; 3] = ["x", "y", "z"];

fn draw(grid: &VoxelGrid, file: &Path) -> Result<(), VoxelError> {
    let plot = |e: &dyn std::fmt::Display| VoxelError::Plot(e.to_string());
    let sections = [
        Section {
            axes: [0, 1],
            fixed: 2,
        },
        Section {
            axes: [0, 2],
            fixed: 1,
        },
        Section {
            axes: [1, 2],
            fixed: 0,
        },
    ];
    // A 2D grid (one layer) has only the xy section.
    let sections = match grid.dimension {
        Dimension::Two => &sections[..1],
        Dimension::Three => &sections[..],
    };
    let longest = sections
        .iter()
        .flat_map(|s| s.axes.map(|a| grid.size[a]))
        .fold(0.0, f64::max);
    let scale = PANEL_PIXELS / longest;
    let (left, bottom, top, pad) = (55u32, 45u32, 40u32, 25u32);
    let widths: Vec<u32> = sections
        .iter()
        .map(|s| (grid.size[s.axes[0]] * scale).ceil() as u32 + left + pad)
        .collect();
    let tallest = sections
        .iter()
        .map(|s| (grid.size[s.axes[1]] * scale).ceil() as u32)
        .max()
        .unwrap_or(1);
    let title_height = 40;
    let size = (
        widths.iter().sum::<u32>() + pad,
        tallest + bottom + top + title_height,
    );
    let root = BitMapBackend::new(file, size).into_drawing_area();
    root.fill(&WHITE).map_err(|e| plot(&e))?;
    let [nx, ny, nz] = grid.cells;
    let fill = match grid.fill {
        RveFill::Matrix => "matrix",
        RveFill::Grains => "grains",
    };
    let title = format!(
        "Voxel RVE, {nx}×{ny}×{nz} cells, {} grains, fill = {fill}",
        grid.grains
    );
    let (head, body) = root.split_vertically(title_height);
    head.titled(&title, ("sans-serif", 22))
        .map_err(|e| plot(&e))?;
    let mut rest = body;
    for (s, &w) in sections.iter().zip(&widths) {
        let (panel, right) = rest.split_horizontally(w);
        rest = right;
        draw_section(grid, s, &panel, (left, bottom, top, pad)).map_err(|e| plot(&e))?;
    }
    root.present().map_err(|e| plot(&e))
}

fn draw_section(
    grid: &VoxelGrid,
    s: &Section,
    panel: &DrawingArea<BitMapBackend, plotters::coord::Shift>,
    (left, bottom, top, pad): (u32, u32, u32, u32),
) -> Result<(), Box<dyn std::error::Error>> {
    let [u, v] = s.axes;
    let h = grid.spacing();
    let layer = grid.cells[s.fixed] / 2;
    let caption = format!(
        "{}{} section at {} = {}",
        NAMES[u],
        NAMES[v],
        NAMES[s.fixed],
        short(grid.size[s.fixed] / 2.0)
    );
    let mut chart = ChartBuilder::on(panel)
        .caption(caption, ("sans-serif", 17))
        .margin_top(top.saturating_sub(30))
        .margin_right(pad)
        .x_label_area_size(bottom)
        .y_label_area_size(left)
        .build_cartesian_2d(0.0..grid.size[u], 0.0..grid.size[v])?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(NAMES[u])
        .y_desc(NAMES[v])
        .label_style(("sans-serif", 13))
        .draw()?;
    let cell = |a: usize, b: usize| {
        let mut idx = [0; 3];
        idx[u] = a;
        idx[v] = b;
        idx[s.fixed] = layer;
        grid.material[grid.index(idx[0], idx[1], idx[2])]
    };
    let (nu, nv) = (grid.cells[u], grid.cells[v]);
    let matrix = grid.matrix_material();
    chart.draw_series((0..nv).flat_map(|b| {
        (0..nu).map(move |a| {
            let m = cell(a, b);
            let colour = if m == matrix { MATRIX } else { colour_of(m) };
            let lo = (a as f64 * h[u], b as f64 * h[v]);
            let hi = ((a + 1) as f64 * h[u], (b + 1) as f64 * h[v]);
            Rectangle::new([lo, hi], colour.filled())
        })
    }))?;
    Ok(())
}

/// `x` with at most 4 decimals and no trailing zeros: 46, 12.5, 0.3333.
fn short(x: f64) -> String {
    let s = format!("{x:.4}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// A fixed colour per material: hue, saturation and lightness from a hash of the number.
fn colour_of(material: u32) -> RGBColor {
    // splitmix64 (Steele, Lea and Flood 2014): its increment, then its finaliser, so
    // nearby numbers get unrelated colours.
    const GOLDEN_GAMMA: u64 = 0x9E37_79B9_7F4A_7C15;
    const MIX: [u64; 2] = [0xBF58_476D_1CE4_E5B9, 0x94D0_49BB_1331_11EB];
    let mut z = (material as u64).wrapping_add(GOLDEN_GAMMA);
    z = (z ^ (z >> 30)).wrapping_mul(MIX[0]);
    z = (z ^ (z >> 27)).wrapping_mul(MIX[1]);
    z ^= z >> 31;
    let unit = |bits: u64| (bits & 0xFFFF) as f64 / 65535.0;
    let hue = unit(z);
    let saturation = 0.5 + 0.4 * unit(z >> 16);
    let lightness = 0.45 + 0.25 * unit(z >> 32);
    let (r, g, b) = HSLColor(hue, saturation, lightness).rgb();
    RGBColor(r, g, b)
}

fn register_font() -> Result<(), VoxelError> {
    let font = include_bytes!("../../../assets/fonts/DejaVuSans.ttf");
    plotters::style::register_font("sans-serif", FontStyle::Normal, font)
        .map_err(|_| VoxelError::Plot("the embedded DejaVuSans.ttf is not a valid font".into()))
}

/// `dir/.name.tmp-PID.png`: hidden, beside the target so the rename is atomic, and
/// ending in `.png` so that the backend picks the format.
fn temporary_name(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    path.with_file_name(format!(".{name}.tmp-{}.png", std::process::id()))
}
