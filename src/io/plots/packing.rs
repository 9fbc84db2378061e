//! `packing.png`: a picture of a 2D packing, each ellipse filled in its phase's colour
//! inside the box's outline, with the parts of grains that cross a periodic box's edges
//! drawn again at the opposite edges, so the box looks as the periodic packing is.

use super::draw::{failed, register_font, FONT};
use super::{encode_rgb, PlotError};
use crate::io::vtk::periodic_shifts;
use crate::packing::PackedGrain;
use crate::scene::{Domain, Phase};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::f64::consts::TAU;
use std::io::Write;

/// Pixels along the box's longer edge.
pub const PACKING_PNG_LONG_SIDE: u32 = 1200;

/// The fewest pixels along the shorter edge (a very flat box stays visible).
const MIN_SHORT_SIDE: u32 = 100;

/// Pixels around the box.
pub const PACKING_PNG_MARGIN: u32 = 30;

/// Pixels of the strip above the box's margin, for the title and the legend.
pub const PACKING_PNG_TITLE_HEIGHT: u32 = 70;

const MARGIN: u32 = PACKING_PNG_MARGIN;
const TITLE_HEIGHT: u32 = PACKING_PNG_TITLE_HEIGHT;

/// Vertices of each drawn ellipse: at 1200 pixels the largest grains of a sparse
/// packing span a few hundred pixels, where 72 vertices leave facets of under 1 % of
/// the radius (`1 − cos(π/72)`).
const VERTICES: usize = 72;

/// A grain's outline is drawn when its smaller semi-axis spans at least this many
/// pixels; below, the outlines of a dense packing would paint it black.
const OUTLINE_MIN_PIXELS: f64 = 4.0;

/// Phase colours, in phase order, repeating (matplotlib's tab10).
const PALETTE: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

/// The colour of phase `index`.
pub fn phase_colour(index: usize) -> RGBColor {
    PALETTE[index % PALETTE.len()]
}

/// The picture's size in pixels `(width, height)` for a box of sides `[Lx, Ly]`, and
/// the pixels per box unit.
pub fn packing_png_size(sides: [f64; 2]) -> (u32, u32, f64) {
    let long = sides[0].max(sides[1]);
    let scale = f64::from(PACKING_PNG_LONG_SIDE) / long;
    let pixels = |l: f64| ((l * scale).round() as u32).max(MIN_SHORT_SIDE);
    (
        pixels(sides[0]) + 2 * MARGIN,
        pixels(sides[1]) + 2 * MARGIN + TITLE_HEIGHT,
        scale,
    )
}

/// Draws the packing of `grains` (ellipses of a 2D scene in `domain`, their phase
/// indices into `phases`) and writes it as PNG to `out`: x to the right, y up, the box
/// [`PACKING_PNG_LONG_SIDE`] pixels along its longer edge, a title with its size in
/// `unit` and a legend of the phases' colours above it.
pub fn render_packing_png(
    out: &mut dyn Write,
    phases: &[Phase],
    grains: &[PackedGrain],
    domain: &Domain,
    unit: &str,
) -> Result<(), PlotError> {
    if let Some(g) = grains.iter().find(|g| g.phase >= phases.len()) {
        return Err(PlotError::GrainPhase {
            id: g.id,
            phase: g.phase,
            phases: phases.len(),
        });
    }
    let sides = [domain.size[0], domain.size[1]];
    let (width, height, scale) = packing_png_size(sides);
    let mut rgb = vec![0u8; 3 * width as usize * height as usize];
    register_font()?;
    {
        let root = BitMapBackend::with_buffer(&mut rgb, (width, height)).into_drawing_area();
        root.fill(&WHITE).map_err(failed("the background"))?;
        let (title, body) = root.split_vertically(TITLE_HEIGHT);
        let inner = body.margin(MARGIN, MARGIN, MARGIN, MARGIN);
        // The box in pixels: y grows downwards in the image.
        let (w, h) = inner.dim_in_pixel();
        let to_pixel = |x: f64, y: f64| {
            (
                (x * scale).round() as i32,
                h as i32 - (y * scale).round() as i32,
            )
        };
        for g in grains {
            let colour = phase_colour(g.phase);
            let outline = g.semi_axes[0].min(g.semi_axes[1]) * scale >= OUTLINE_MIN_PIXELS;
            let shifts = std::iter::once([0.0; 3]).chain(periodic_shifts(g, domain));
            for shift in shifts {
                let points: Vec<(i32, i32)> = ellipse_points(g, shift)
                    .into_iter()
                    .map(|(x, y)| to_pixel(x, y))
                    .collect();
                inner
                    .draw(&Polygon::new(points.clone(), colour.mix(0.85).filled()))
                    .map_err(failed("a grain"))?;
                if outline {
                    let mut closed = points;
                    closed.push(closed[0]);
                    inner
                        .draw(&PathElement::new(closed, BLACK.mix(0.6).stroke_width(1)))
                        .map_err(failed("a grain's outline"))?;
                }
            }
        }
        // Whatever reaches past the box (the grains crossing a periodic edge, drawn
        // whole at both ends) is covered by the margins and the title strip again.
        let white = WHITE.filled();
        let (w, h) = (w as i32, h as i32);
        let m = MARGIN as i32;
        for rect in [
            [(-m, -m - TITLE_HEIGHT as i32), (w + m, 0)],
            [(-m, h), (w + m, h + m)],
            [(-m, -m), (0, h + m)],
            [(w, -m), (w + m, h + m)],
        ] {
            inner
                .draw(&Rectangle::new(rect, white))
                .map_err(failed("the margin"))?;
        }
        inner
            .draw(&Rectangle::new([(0, 0), (w, h)], BLACK.stroke_width(2)))
            .map_err(failed("the box"))?;
        draw_legend(&title, phases, grains, domain, unit)?;
        root.present().map_err(failed("the picture"))?;
    }
    encode_rgb(out, (width, height), &rgb)
}

/// [`VERTICES`] points on `grain`'s ellipse moved by `shift`, in box units.
fn ellipse_points(grain: &PackedGrain, shift: [f64; 3]) -> Vec<(f64, f64)> {
    let [a1, a2, _] = grain.semi_axes;
    let e1 = crate::contact::rotation_column(grain.quaternion, 0);
    let e2 = crate::contact::rotation_column(grain.quaternion, 1);
    (0..VERTICES)
        .map(|k| {
            let (sin, cos) = (TAU * k as f64 / VERTICES as f64).sin_cos();
            let (u, v) = (a1 * cos, a2 * sin);
            (
                grain.centre[0] + shift[0] + u * e1[0] + v * e2[0],
                grain.centre[1] + shift[1] + u * e1[1] + v * e2[1],
            )
        })
        .collect()
}

/// The title (grains, box in `unit`, area fraction) and one coloured square per phase.
fn draw_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    phases: &[Phase],
    grains: &[PackedGrain],
    domain: &Domain,
    unit: &str,
) -> Result<(), PlotError> {
    let area_of = |g: &PackedGrain| domain.dimension.measure(g.semi_axes);
    let fraction = grains.iter().map(area_of).sum::<f64>() / domain.volume();
    let font = |size: u32| {
        (FONT, size)
            .into_font()
            .color(&BLACK)
            .pos(Pos::new(HPos::Left, VPos::Center))
    };
    area.draw_text(
        &format!(
            "{} grains in a {} \u{d7} {} {unit} box, area fraction {:.4}",
            grains.len(),
            domain.size[0],
            domain.size[1],
            fraction
        ),
        &font(20),
        (MARGIN as i32, 22),
    )
    .map_err(failed("the title"))?;
    let mut x = MARGIN as i32;
    for (index, phase) in phases.iter().enumerate() {
        area.draw(&Rectangle::new(
            [(x, 44), (x + 16, 60)],
            phase_colour(index).filled(),
        ))
        .map_err(failed("the legend"))?;
        let label = format!(
            "{} ({})",
            phase.name,
            grains.iter().filter(|g| g.phase == index).count()
        );
        area.draw_text(&label, &font(16), (x + 22, 52))
            .map_err(failed("the legend"))?;
        x += 40 + 9 * label.chars().count() as i32;
    }
    Ok(())
}
