//! Drawing the statistics figure with plotters, into an RGB buffer.

use super::histogram::{aligned_bins, freedman_diaconis_bins, Histogram};
use super::panel::Panel;
use super::target::Target;
use super::PlotError;
use crate::laws::Moments;
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::ops::Range;
use std::sync::OnceLock;

/// The family name the embedded font is registered under.
pub(super) const FONT: &str = "DejaVu Sans";

/// The embedded font (DejaVu Sans, licence in `assets/fonts/DejaVu-LICENSE.txt`).
static FONT_BYTES: &[u8] = include_bytes!("../../../assets/fonts/DejaVuSans.ttf");

/// The y axis reaches this multiple of the tallest bar or curve, leaving room for the
/// legend above the data.
const HEADROOM: f64 = 1.4;

/// Share of the data range added on each side of the x axis.
pub(super) const X_MARGIN: f64 = 0.04;

/// A data range narrower than this share of its magnitude (or than this, in absolute
/// terms, for magnitudes below 1) is a single value: a constant law, or grains that
/// all share one value up to rounding. 1e-9 is far above the rounding of a recomputed
/// diameter (16 ε relative) or axis angle (a few ε radians) and far below any spread
/// a scene can ask for.
const SINGLE_VALUE_REL: f64 = 1e-9;

/// Half-width of the axis around a single value, as a share of the value (in absolute
/// units for values below 1, e.g. an angle of 0°).
const SINGLE_VALUE_PAD: f64 = 0.05;

/// The packed grains' histogram.
pub(super) const PACKED: RGBColor = RGBColor(31, 119, 180);
/// The target law.
pub(super) const TARGET: RGBColor = RGBColor(214, 39, 40);
/// The voxel grains' outline.
pub(super) const VOXEL: RGBColor = RGBColor(255, 127, 14);

/// Registers the embedded font with plotters, once per process.
pub(super) fn register_font() -> Result<(), PlotError> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let ok = REGISTERED.get_or_init(|| {
        plotters::style::register_font(FONT, FontStyle::Normal, FONT_BYTES).is_ok()
    });
    if *ok {
        Ok(())
    } else {
        Err(PlotError::Font)
    }
}

/// Maps a plotters error to [`PlotError::Draw`] naming `what` was being drawn.
pub(super) fn failed<E: std::fmt::Display>(what: &str) -> impl FnOnce(E) -> PlotError + '_ {
    move |e| PlotError::Draw {
        what: what.to_string(),
        message: e.to_string(),
    }
}

/// The x interval the histograms cover: the law's range and every finite value.
fn data_range(panel: &Panel) -> (f64, f64) {
    let values = panel.packed.iter().chain(panel.voxel.iter().flatten());
    let (mut lo, mut hi) = panel.target.range();
    for &x in values.filter(|x| x.is_finite()) {
        (lo, hi) = (lo.min(x), hi.max(x));
    }
    let magnitude = lo.abs().max(hi.abs());
    if hi - lo <= SINGLE_VALUE_REL * magnitude.max(1.0) {
        let mid = 0.5 * (lo + hi);
        let pad = SINGLE_VALUE_PAD * magnitude.max(1.0);
        (mid - pad, mid + pad)
    } else {
        (lo, hi)
    }
}

/// Tick labels per axis asked of plotters.
const X_TICKS: usize = 7;
/// Tick labels on the y axis.
const Y_TICKS: usize = 6;

/// Decimals for the labels of ticks on an axis spanning `span` with at most `ticks`
/// labels. plotters spaces ticks by a step `{1, 2, 5} × 10ᵐ` giving at most `ticks`
/// of them; the smallest such step above `span/ticks` is at most that step, so its
/// decimals are enough for every label.
pub(super) fn tick_decimals(span: f64, ticks: usize) -> usize {
    let raw = span / ticks as f64;
    if !(raw > 0.0 && raw.is_finite()) {
        return 0;
    }
    let exponent = raw.log10().floor();
    let mantissa = raw / 10f64.powf(exponent);
    // A mantissa above 5 rounds up to the step 10^(m+1).
    let exponent = exponent as i32 + i32::from(mantissa > 5.0);
    (-exponent).clamp(0, 12) as usize
}

/// The legend entry of a sample: its size and mean ± standard deviation, with
/// `decimals` decimals.
fn sample_label(name: &str, values: &[f64], unit: &str, decimals: usize) -> String {
    let finite: Vec<f64> = values.iter().copied().filter(|x| x.is_finite()).collect();
    match Moments::of_sample(&finite) {
        Some(m) => format!(
            "{name}, n = {}: {:.decimals$}{unit} \u{b1} {:.decimals$}{unit}",
            finite.len(),
            m.mean,
            m.std
        ),
        None => format!("{name}, n = 0"),
    }
}

/// The packed grains' legend entry, with the KS distance to the law when known.
fn packed_label(panel: &Panel, unit: &str, decimals: usize) -> String {
    let label = sample_label("packed grains", &panel.packed, unit, decimals);
    match panel.ks_distance {
        Some(d) => format!("{label}, KS {d:.3}"),
        None => label,
    }
}

/// The legend entry of the target law, with `decimals` decimals.
fn law_label(panel: &Panel, unit: &str, decimals: usize) -> String {
    match (&panel.target, panel.law_moments) {
        (Target::Value(v), _) => format!("{}: {v:.decimals$}{unit}", panel.law),
        (Target::Curve(_), Some(m)) => format!(
            "{}: {:.decimals$}{unit} \u{b1} {:.decimals$}{unit}",
            panel.law,
            no_negative_zero(m.mean, decimals),
            m.std
        ),
        (Target::Curve(_), None) => panel.law.clone(),
    }
}

/// `x`, or 0 if it prints as zero with `decimals` decimals: a mean of 0 computed by
/// quadrature (`-1e-17`) would print as `-0.0`.
fn no_negative_zero(x: f64, decimals: usize) -> f64 {
    if x.abs() < 0.5 * 10f64.powi(-(decimals as i32)) {
        0.0
    } else {
        x
    }
}

/// The chart of a panel in `area`: its caption `what`, axis labels `labels` (x, y),
/// ranges (x, y), and the mesh with ticks of `decimals` (x, y) decimals.
pub(super) fn axes<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    what: &str,
    labels: (&str, &str),
    (x, y): (Range<f64>, Range<f64>),
    (x_decimals, y_decimals): (usize, usize),
) -> Result<ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>, PlotError> {
    let mut chart = ChartBuilder::on(area)
        .caption(what, (FONT, 20))
        .margin_top(6)
        .margin_bottom(10)
        .margin_left(12)
        .margin_right(22)
        .x_label_area_size(52)
        .y_label_area_size(72)
        .build_cartesian_2d(x, y)
        .map_err(failed(what))?;
    chart
        .configure_mesh()
        .x_desc(labels.0)
        .y_desc(labels.1)
        .label_style((FONT, 15))
        .axis_desc_style((FONT, 16))
        .x_labels(X_TICKS)
        .y_labels(Y_TICKS)
        .x_label_formatter(&|x| format!("{x:.x_decimals$}"))
        .y_label_formatter(&|y| format!("{y:.y_decimals$}"))
        .bold_line_style(BLACK.mix(0.08))
        .light_line_style(TRANSPARENT)
        .axis_style(BLACK.mix(0.6))
        .draw()
        .map_err(failed(what))?;
    Ok(chart)
}

/// Draws one panel: the packed histogram, the target law, the voxel outline, a legend.
pub(super) fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    panel: &Panel,
) -> Result<(), PlotError> {
    let what = panel.title.as_str();
    let binned = if panel.packed.is_empty() {
        panel.voxel.as_deref().unwrap_or_default()
    } else {
        &panel.packed
    };
    let (lo, hi, bins) = match (&panel.target, data_range(panel)) {
        (Target::Curve(_), data) => aligned_bins(binned, panel.target.range(), data),
        (Target::Value(_), (lo, hi)) => (lo, hi, freedman_diaconis_bins(binned, lo, hi)),
    };
    let packed = Histogram::new(&panel.packed, lo, hi, bins);
    let voxel = panel
        .voxel
        .as_ref()
        .map(|v| Histogram::new(v, lo, hi, bins));

    // Everything drawn above the axis, as (x, height) points, to size the y axis and
    // to find the emptier upper corner for the legend.
    let mut heights: Vec<(f64, f64)> = packed.outline();
    heights.extend(voxel.iter().flat_map(Histogram::outline));
    if let Target::Curve(points) = &panel.target {
        heights.extend(points.iter().filter(|p| p.1.is_finite()));
    }
    let top = heights.iter().map(|p| p.1).fold(0.0, f64::max);
    let y_max = if top > 0.0 { HEADROOM * top } else { 1.0 };
    let mid = 0.5 * (lo + hi);
    let side_max = |left: bool| {
        heights
            .iter()
            .filter(|p| (p.0 < mid) == left)
            .map(|p| p.1)
            .fold(0.0, f64::max)
    };
    let legend_at = if side_max(false) <= side_max(true) {
        SeriesLabelPosition::UpperRight
    } else {
        SeriesLabelPosition::UpperLeft
    };

    let pad = X_MARGIN * (hi - lo);
    let x_decimals = tick_decimals(hi - lo + 2.0 * pad, X_TICKS);
    let y_decimals = tick_decimals(y_max, Y_TICKS);
    // Figures in the legend get one decimal more than the ticks.
    let figures = x_decimals + 1;
    let mut chart = axes(
        area,
        what,
        (panel.x_label, panel.y_label),
        ((lo - pad)..(hi + pad), 0.0..y_max),
        (x_decimals, y_decimals),
    )?;

    let unit = if panel.x_label.contains("degrees") {
        "\u{b0}"
    } else {
        ""
    };
    let fill = PACKED.mix(0.35).filled();
    chart
        .draw_series(
            packed
                .bars()
                .into_iter()
                .map(|(a, b, d)| Rectangle::new([(a, 0.0), (b, d)], fill)),
        )
        .map_err(failed(what))?
        .label(packed_label(panel, unit, figures))
        .legend(move |(x, y)| Rectangle::new([(x, y - 6), (x + 20, y + 6)], fill));
    chart
        .draw_series(std::iter::once(PathElement::new(
            packed.outline(),
            PACKED.stroke_width(1),
        )))
        .map_err(failed(what))?;

    let line = TARGET.stroke_width(2);
    let target = match &panel.target {
        Target::Curve(points) => chart.draw_series(LineSeries::new(points.clone(), line)),
        Target::Value(v) => chart.draw_series(std::iter::once(PathElement::new(
            vec![(*v, 0.0), (*v, y_max / HEADROOM)],
            line,
        ))),
    };
    target
        .map_err(failed(what))?
        .label(law_label(panel, unit, figures))
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], line));

    if let (Some(hist), Some(values)) = (&voxel, &panel.voxel) {
        let outline = VOXEL.stroke_width(2);
        chart
            .draw_series(std::iter::once(PathElement::new(hist.outline(), outline)))
            .map_err(failed(what))?
            .label(sample_label("voxel RVE", values, unit, figures))
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], outline));
    }

    legend(&mut chart, legend_at, what)
}

/// Draws the legend of `chart` (a panel's, captioned `what`) at `at`.
pub(super) fn legend<'a, DB: DrawingBackend + 'a>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    at: SeriesLabelPosition,
    what: &str,
) -> Result<(), PlotError> {
    chart
        .configure_series_labels()
        .position(at)
        .margin(8)
        .legend_area_size(28)
        .label_font((FONT, 14))
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK.mix(0.3))
        .draw()
        .map_err(failed(what))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tick_decimals_cover_the_step_plotters_picks() {
        // Spans of 13 (steps of 2), 0.65 (0.1), 0.22 with 6 ticks (0.05), 190 (50).
        assert_eq!(tick_decimals(13.0, 7), 0);
        assert_eq!(tick_decimals(0.65, 7), 1);
        assert_eq!(tick_decimals(0.22, 6), 2);
        assert_eq!(tick_decimals(190.0, 7), 0);
        assert_eq!(tick_decimals(0.0, 7), 0);
    }
}
