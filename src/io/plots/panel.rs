//! What a panel of the statistics figure holds: a phase's measured values and the
//! target law they were drawn from; a row is a phase's panels.

use super::target::{distribution_target, law_moments, law_name, Target};
use crate::laws::{Distribution, Moments};

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

impl Panel {
    /// A panel of values drawn from `law`, against its density (`labels`: x, then y).
    pub fn of_law(
        title: &str,
        labels: (&'static str, &'static str),
        law: &Distribution,
        packed: Vec<f64>,
        voxel: Option<Vec<f64>>,
    ) -> Self {
        Self {
            title: title.into(),
            x_label: labels.0,
            y_label: labels.1,
            law: law_name(law),
            law_moments: law_moments(law),
            target: distribution_target(law),
            packed,
            voxel,
            ks_distance: None,
        }
    }
}
