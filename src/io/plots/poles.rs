//! `pole_figures.png`: per phase, the pole figure of the grains' crystal orientations.
//!
//! Each phase gets a panel: the poles of its grains, in the sample frame, in the
//! equal-area (Schmidt) projection of the upper hemisphere onto the x–y plane (a pole
//! `p` with `p_z < 0` is drawn as `−p`; `(x, y)·√(1/(1 + z))` on the unit disc). For a
//! fibre texture the poles are the fibre's crystal direction, so a sharp fibre along z
//! is a spot at the centre; for the other kinds the three {100} poles (the crystal's
//! axes), so a random texture covers the disc evenly.

use super::draw::{failed, register_font, FONT};
use super::{encode_rgb, PlotError};
use crate::packing::PackedGrain;
use crate::scene::{rotate, Phase, Texture};
use plotters::prelude::*;
use std::io::Write;

/// Panel size in pixels.
const PANEL: u32 = 480;
/// Radius of the projection disc in pixels.
const DISC: f64 = 200.0;
/// Height of a panel's title strip in pixels.
const TITLE: u32 = 50;
/// The most panels (phases) drawn in one row; more phases wrap.
const PER_ROW: usize = 4;

/// The upper-hemisphere equal-area projection of the unit vector `p` onto the unit
/// disc.
pub fn equal_area(p: [f64; 3]) -> (f64, f64) {
    let p = if p[2] < 0.0 { p.map(|v| -v) } else { p };
    let s = (1.0 / (1.0 + p[2])).sqrt();
    (p[0] * s, p[1] * s)
}

/// Draws the pole figures of `grains` (phases index `phases`) with crystal
/// orientations `crystals[i]` for `grains[i]`, and writes them as PNG to `out`.
pub fn render_pole_figures_png(
    out: &mut dyn Write,
    phases: &[Phase],
    grains: &[PackedGrain],
    crystals: &[[f64; 4]],
) -> Result<(), PlotError> {
    if phases.is_empty() {
        return Err(PlotError::NoPhases);
    }
    register_font()?;
    let columns = phases.len().min(PER_ROW);
    let rows = phases.len().div_ceil(PER_ROW);
    let (width, height) = (PANEL * columns as u32, (PANEL + TITLE) * rows as u32);
    let mut rgb = vec![0u8; 3 * width as usize * height as usize];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, (width, height)).into_drawing_area();
        root.fill(&WHITE).map_err(failed("the background"))?;
        let areas = root.split_evenly((rows, columns));
        for (p, (phase, area)) in phases.iter().zip(&areas).enumerate() {
            let (poles, label): (Vec<[f64; 3]>, String) = match &phase.texture.texture {
                Texture::Fibre { crystal, .. } => (
                    vec![*crystal],
                    format!(
                        "[{:.2} {:.2} {:.2}] poles",
                        crystal[0], crystal[1], crystal[2]
                    ),
                ),
                _ => (
                    vec![[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
                    "{100} poles".to_owned(),
                ),
            };
            let mine: Vec<[f64; 4]> = grains
                .iter()
                .zip(crystals)
                .filter(|(g, _)| g.phase == p)
                .map(|(_, &q)| q)
                .collect();
            let title = format!(
                "{}: {} of {} grains ({})",
                phase.name,
                label,
                mine.len(),
                phase.texture.texture.kind()
            );
            let area = area
                .titled(&title, (FONT, 18))
                .map_err(failed("a pole figure's title"))?;
            let (w, h) = area.dim_in_pixel();
            let centre = (f64::from(w) / 2.0, f64::from(h) / 2.0);
            let at = |x: f64, y: f64| {
                (
                    (centre.0 + DISC * x).round() as i32,
                    (centre.1 - DISC * y).round() as i32,
                )
            };
            let c = at(0.0, 0.0);
            area.draw(&Circle::new(c, DISC as i32, BLACK.stroke_width(2)))
                .map_err(failed("the projection's circle"))?;
            for (text, x, y) in [("x", 1.06, 0.0), ("y", 0.0, 1.08)] {
                area.draw(&Text::new(text, at(x, y), (FONT, 18)))
                    .map_err(failed("an axis label"))?;
            }
            let dot = RGBColor(31, 119, 180).mix(0.6).filled();
            for q in &mine {
                for h in &poles {
                    let (x, y) = equal_area(rotate(*q, *h));
                    area.draw(&Circle::new(at(x, y), 2, dot))
                        .map_err(failed("a pole"))?;
                }
            }
        }
        root.present().map_err(failed("the pole figures"))?;
    }
    encode_rgb(out, (width, height), &rgb)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_projection_keeps_areas_and_maps_the_hemisphere_on_the_disc() {
        assert_eq!(equal_area([0.0, 0.0, 1.0]), (0.0, 0.0));
        assert_eq!(equal_area([0.0, 0.0, -1.0]), (0.0, 0.0));
        // The equator is the unit circle.
        let (x, y) = equal_area([0.6, 0.8, 0.0]);
        assert!((x * x + y * y - 1.0).abs() < 1e-15);
        // A cap of polar angle θ has area 2π(1 − cos θ) on the sphere; its image, a disc
        // of radius r, has π r² × 2 (the disc is the hemisphere's 2π over π): r² = 1 − cos θ.
        let theta = 0.7f64;
        let (x, _) = equal_area([theta.sin(), 0.0, theta.cos()]);
        assert!((x * x - (1.0 - theta.cos())).abs() < 1e-15);
    }
}
