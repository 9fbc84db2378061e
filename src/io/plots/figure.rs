//! The layout of the statistics figure: a title, then per phase a line of its three
//! panels and lines of its extra panels below.

use super::cdf::draw_cdf_panel;
use super::draw::{draw_panel, failed, register_font, FONT};
use super::extra::Extra;
use super::panel::Row;
use super::{PlotError, COLUMNS, PANEL_WIDTH, TITLE_HEIGHT};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// Height of a line's heading, in pixels.
const HEADING_HEIGHT: u32 = 40;

/// Lines of panels of the figure: per phase its three, then [`COLUMNS`] extra panels
/// per line (`extras[p]`, phase p's).
pub(super) fn line_count(extras: &[Vec<Extra>]) -> usize {
    extras
        .iter()
        .map(|e| 1 + e.len().div_ceil(COLUMNS as usize))
        .sum()
}

/// Draws the whole figure into `rgb` (`3 · width · height` bytes).
pub(super) fn figure(
    rgb: &mut [u8],
    size: (u32, u32),
    rows: &[Row],
    extras: &[Vec<Extra>],
    grains: usize,
) -> Result<(), PlotError> {
    register_font()?;
    let root = BitMapBackend::with_buffer(rgb, size).into_drawing_area();
    root.fill(&WHITE).map_err(failed("the background"))?;
    let (title, body) = root.split_vertically(TITLE_HEIGHT);
    let centred = |size: u32| {
        (FONT, size)
            .into_font()
            .color(&BLACK)
            .pos(Pos::new(HPos::Center, VPos::Center))
    };
    title
        .draw_text(
            &format!(
                "Grain statistics: {grains} packed grains against the scene\u{2019}s laws \
                 (legends: mean \u{b1} standard deviation)"
            ),
            &centred(24),
            ((size.0 / 2) as i32, (TITLE_HEIGHT / 2) as i32),
        )
        .map_err(failed("the title"))?;
    let lines = line_count(extras);
    let mut areas = body.split_evenly((lines, 1)).into_iter();
    for (row, extra) in rows.iter().zip(extras) {
        let in_row = |e: PlotError| match e {
            PlotError::Draw { what, message } => PlotError::Draw {
                what: format!("{what} of {}", row.title),
                message,
            },
            other => other,
        };
        let Some(area) = areas.next() else { break };
        for (panel, area) in row.panels.iter().zip(line(&area, &row.title)?) {
            draw_panel(&area, panel).map_err(in_row)?;
        }
        for chunk in extra.chunks(COLUMNS as usize) {
            let Some(area) = areas.next() else { break };
            let heading = format!("{} (continued)", row.title.split(':').next().unwrap_or(""));
            for (panel, area) in chunk.iter().zip(line(&area, &heading)?) {
                match panel {
                    Extra::Density(p) => draw_panel(&area, p),
                    Extra::Cdf(p) => draw_cdf_panel(&area, p),
                }
                .map_err(in_row)?;
            }
        }
    }
    root.present().map_err(failed("the figure"))
}

/// Draws a line's heading (a rule and `title`) and returns the areas of its
/// [`COLUMNS`] panels.
fn line<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    title: &str,
) -> Result<Vec<DrawingArea<DB, Shift>>, PlotError> {
    let (heading, panels) = area.split_vertically(HEADING_HEIGHT);
    heading
        .draw(&PathElement::new(
            vec![(16, 0), ((COLUMNS * PANEL_WIDTH) as i32 - 16, 0)],
            BLACK.mix(0.25).stroke_width(1),
        ))
        .map_err(failed(title))?;
    heading
        .draw_text(
            title,
            &(FONT, 20)
                .into_font()
                .color(&BLACK)
                .pos(Pos::new(HPos::Left, VPos::Center)),
            (24, (HEADING_HEIGHT / 2) as i32),
        )
        .map_err(failed(title))?;
    Ok(panels.split_evenly((1, COLUMNS as usize)))
}
