//! `statistics.png`: per phase, histograms of the packed grains' equivalent diameter,
//! aspect ratio and orientation angle against the densities of the scene's laws.
//!
//! One row per phase, three panels per row:
//! - **equivalent diameter** `2 (a1 a2 a3)^{1/3}` and **aspect ratio** `a1/a2`, measured
//!   as `summary.json` measures them ([`equivalent_diameter`], [`aspect_ratio`]),
//!   against the pdf of the law truncated and renormalised by its cutoffs
//!   ([`Distribution::pdf`](crate::laws::Distribution::pdf));
//! - the **angle**: for a tilt orientation, the tilt angle ([`tilt_angle`]) against the
//!   von Mises pdf; for any other orientation, the angle of the first semi-axis to z
//!   ([`axis_polar_angle`]) against the isotropic density `sin θ` (random orientations)
//!   or a single value (aligned, fixed). The panel is never left out, so every figure has
//!   three columns and a random orientation's isotropy can be checked by eye;
//! - the **crystal texture**, when textures are given ([`TextureMeasure`]): the angle
//!   that measures the phase's texture against its law under the target, with the KS
//!   distance of `summary.json`, first on the phase's lines of extra panels below.
//!
//! Histograms are densities (total area 1) on Freedman–Diaconis bins
//! ([`freedman_diaconis_bins`]) whose edges fall on the law's cutoffs ([`aligned_bins`]). A constant or fixed law is a vertical line at its
//! value. Voxel samples, when given, are drawn as a second histogram outline on the
//! same bins. Legends give mean ± standard deviation.
//!
//! [`equivalent_diameter`]: crate::contact::equivalent_diameter
//! [`aspect_ratio`]: crate::scene::aspect_ratio
//! [`tilt_angle`]: crate::scene::tilt_angle
//!
//! ```no_run
//! use grainpack::io::plots::write_statistics_png;
//! use grainpack::scene::Scene;
//! # fn packed() -> Vec<grainpack::packing::PackedGrain> { vec![] }
//! let scene = Scene::from_path("configs/grains.toml".as_ref())?;
//! write_statistics_png("out/statistics.png".as_ref(), &scene.phases, &packed(), None, &[])?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod angles;
mod cdf;
mod draw;
mod extra;
mod figure;
mod histogram;
mod packing;
mod panel;
mod poles;
mod rows;
mod target;
mod texture;

pub use angles::axis_polar_angle;
pub use histogram::{aligned_bins, freedman_diaconis_bins, Histogram, MAX_BINS, MIN_BINS};
pub use packing::{
    packing_png_size, phase_colour, render_packing_png, PACKING_PNG_LONG_SIDE, PACKING_PNG_MARGIN,
    PACKING_PNG_TITLE_HEIGHT,
};
pub use poles::{equal_area, render_pole_figures_png};

use crate::contact::Dimension;
use crate::io::atomic::write_atomically;
use crate::io::texture::TextureMeasure;
use crate::packing::PackedGrain;
use crate::run::PhaseStatistics;
use crate::scene::Phase;
use std::io::{self, Write};
use std::path::{Path, PathBuf};

/// Width of one panel, in pixels.
pub const PANEL_WIDTH: u32 = 600;

/// Height of one row (its heading and its panels), in pixels.
pub const ROW_HEIGHT: u32 = 470;

/// Height of the figure's title strip, in pixels.
pub const TITLE_HEIGHT: u32 = 60;

/// The tallest figure drawn, in pixels: 34 phases. Its RGB buffer takes
/// `3 · 1800 · 16384` bytes, 88 MB.
pub const MAX_HEIGHT: u32 = 1 << 14;

/// Panels per line: equivalent diameter, aspect ratio, angle on a phase's first line;
/// its extra panels (crystal texture, third shape ratio, spin, size CDF) on lines below.
pub const COLUMNS: u32 = 3;

/// One grain measured in a voxel RVE, to compare with the packed grain it renders.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VoxelSample {
    /// Index of the grain's phase in the scene.
    pub phase: usize,
    /// Equivalent-sphere diameter of the voxel grain (box units).
    pub equivalent_diameter: f64,
    /// Aspect ratio, in the convention of the packed grains: the axis of revolution
    /// over the equatorial semi-axis (`a1/a2`, above 1 prolate).
    pub aspect_ratio: f64,
    /// The angle of the third column, in radians: for a phase with a tilt law, the tilt
    /// angle in the law's window (as [`tilt_angle`] measures it); otherwise the angle of
    /// the axis of revolution to z, in `[0, π/2]` (as [`axis_polar_angle`]). `None`
    /// when not measured (e.g. a grain too small to have an axis).
    ///
    /// [`tilt_angle`]: crate::scene::tilt_angle
    pub tilt: Option<f64>,
    /// The moment ellipsoid's semi-axis ratios sorted `a ≥ b ≥ c`: `[b/a, c/a, c/b]`,
    /// compared with a triaxial phase's shape-ratio laws; `None` when not measured.
    pub shape_ratios: Option<[f64; 3]>,
    /// For a `fisher` phase, the spin (radians) of the moment ellipsoid's middle axis
    /// about its first axis, as the packed grains' spin is measured; else `None`.
    pub spin: Option<f64>,
}

/// Why the statistics figure could not be made.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PlotError {
    /// The scene has no phase: there is no row to draw.
    #[error("the statistics figure needs at least one phase; the scene has none")]
    NoPhases,
    /// A packed grain names a phase the scene does not have.
    #[error("grain {id} has phase index {phase}, but the scene has {phases} phases")]
    GrainPhase {
        /// The grain's id.
        id: u32,
        /// Its phase index.
        phase: usize,
        /// Phases in the scene.
        phases: usize,
    },
    /// A voxel sample names a phase the scene does not have.
    #[error("voxel sample {index} has phase index {phase}, but the scene has {phases} phases")]
    VoxelPhase {
        /// Index of the sample in the slice given.
        index: usize,
        /// Its phase index.
        phase: usize,
        /// Phases in the scene.
        phases: usize,
    },
    /// The figure would be taller than a PNG allows.
    #[error("{phases} phases make a figure {height} pixels tall, above the limit of {MAX_HEIGHT}")]
    TooLarge {
        /// Phases in the scene.
        phases: usize,
        /// Height the figure would need.
        height: u64,
    },
    /// The embedded font could not be loaded.
    #[error("the embedded font assets/fonts/DejaVuSans.ttf could not be loaded")]
    Font,
    /// Plotting failed.
    #[error("cannot draw {what}: {message}")]
    Draw {
        /// The part of the figure being drawn.
        what: String,
        /// What the plotting library said.
        message: String,
    },
    /// The pixels could not be encoded as PNG.
    #[error("cannot encode the statistics figure as PNG")]
    Encode(#[from] png::EncodingError),
    /// The file could not be written (nothing was left under its name).
    #[error("cannot write {}", path.display())]
    Write {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        #[source]
        source: io::Error,
    },
}

/// The size in pixels `(width, height)` of the figure with `lines` lines of panels:
/// [`COLUMNS`] panels of [`PANEL_WIDTH`] across, a [`TITLE_HEIGHT`] strip and one
/// [`ROW_HEIGHT`] line down per phase, plus one per [`COLUMNS`] extra panels of a
/// phase (its crystal texture, third shape ratio, spin, or tabulated size CDF).
pub fn statistics_png_size(lines: usize) -> (u64, u64) {
    (
        u64::from(COLUMNS * PANEL_WIDTH),
        u64::from(TITLE_HEIGHT) + lines as u64 * u64::from(ROW_HEIGHT),
    )
}

/// Writes the statistics figure to `path` as PNG: into a temporary file beside it,
/// renamed over `path` when complete ([`write_atomically`]).
///
/// `packed` are the grains as packed (their phase indices into `phases`); `voxel`, the
/// same grains measured in a voxel RVE, adds a second outline to each panel;
/// `textures` (from [`measure_textures`](crate::io::texture::measure_textures)) add
/// a texture panel to the extra panels of each phase they measure.
pub fn write_statistics_png(
    path: &Path,
    phases: &[Phase],
    packed: &[PackedGrain],
    voxel: Option<&[VoxelSample]>,
    textures: &[TextureMeasure],
) -> Result<(), PlotError> {
    let mut png = Vec::new();
    render_statistics_png(&mut png, phases, packed, voxel, textures)?;
    write_atomically(path, |w| w.write_all(&png)).map_err(|source| PlotError::Write {
        path: path.to_owned(),
        source,
    })
}

/// Draws the statistics figure and writes it as PNG to `out` (see
/// [`write_statistics_png`]); a write error of `out` comes back as
/// [`PlotError::Encode`].
pub fn render_statistics_png(
    out: &mut dyn Write,
    phases: &[Phase],
    packed: &[PackedGrain],
    voxel: Option<&[VoxelSample]>,
    textures: &[TextureMeasure],
) -> Result<(), PlotError> {
    render_run_statistics_png(out, phases, packed, voxel, None, textures, Dimension::Three)
}

/// [`render_statistics_png`] for a run: the legends also give the KS distances of the
/// run's statistics (`summary.json`'s, in `statistics`, one per phase). In 2D
/// (`dimension`), the first panel is the equivalent-circle diameter, the shares are of
/// the grains' area, and the third panel is the angle of the first semi-axis from x
/// (against the tilt law about z when the phase has one).
pub fn render_run_statistics_png(
    out: &mut dyn Write,
    phases: &[Phase],
    packed: &[PackedGrain],
    voxel: Option<&[VoxelSample]>,
    statistics: Option<&[PhaseStatistics]>,
    textures: &[TextureMeasure],
    dimension: Dimension,
) -> Result<(), PlotError> {
    if phases.is_empty() {
        return Err(PlotError::NoPhases);
    }
    let mut rows = rows::rows(phases, packed, voxel, dimension)?;
    let mut extras = extra::complete(&mut rows, phases, packed, voxel, statistics);
    for m in textures {
        if let Some(phase) = extras.get_mut(m.phase) {
            phase.insert(0, extra::Extra::Density(texture::texture_panel(m)));
        }
    }
    let (width, height) = statistics_png_size(figure::line_count(&extras));
    let height = u32::try_from(height)
        .ok()
        .filter(|&h| h <= MAX_HEIGHT)
        .ok_or(PlotError::TooLarge {
            phases: phases.len(),
            height,
        })?;
    let width = width as u32;
    let mut rgb = vec![0u8; 3 * width as usize * height as usize];
    figure::figure(&mut rgb, (width, height), &rows, &extras, packed.len())?;
    encode_rgb(out, (width, height), &rgb)
}

/// Encodes an RGB buffer of `width × height` pixels as PNG.
fn encode_rgb(
    out: &mut dyn Write,
    (width, height): (u32, u32),
    rgb: &[u8],
) -> Result<(), PlotError> {
    let mut encoder = png::Encoder::new(out, width, height);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header()?;
    writer.write_image_data(rgb)?;
    writer.finish()?;
    Ok(())
}

#[cfg(test)]
mod tests;
