//! What a panel of the statistics figure holds: a phase's measured values and the
//! target law they were drawn from; a row is a phase's panels.

use super::target::Target;
use crate::laws::Moments;

/// One panel: a quantity of one phase.
#[derive(Debug, Clone)]
pub(super) struct Panel {
    /// Caption.
    pub title: String,
    /// x axis label, with the unit.
    pub x_label: &'static str,
    /// y axis label, with the unit.
    pub y_label: &'static str,
    /// Legend entry of the target law, without its figures.
    pub law: String,
    /// Mean and standard deviation of a target density, in the units of the x axis.
    pub law_moments: Option<Moments>,
    /// The target law.
    pub target: Target,
    /// The packed grains' values.
    pub packed: Vec<f64>,
    /// The voxel grains' values, when voxel samples were given.
    pub voxel: Option<Vec<f64>>,
    /// KS distance of the packed values to the law, as `summary.json` reports it.
    pub ks_distance: Option<f64>,
}

/// One row of the figure: a phase.
#[derive(Debug, Clone)]
pub(super) struct Row {
    /// The row's heading.
    pub title: String,
    /// Equivalent diameter, aspect ratio, angle.
    pub panels: [Panel; 3],
}
