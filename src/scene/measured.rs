//! Measured grain tables: a phase whose grains come from a list (EBSD, CT, or a
//! `grains.csv` written by `pack`), either exactly those grains or drawn from them with
//! replacement.

use crate::contact::{equivalent_diameter, Dimension};
use std::sync::Arc;

/// One measured grain.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeasuredGrain {
    /// Equivalent-sphere diameter (equivalent-circle in 2D).
    pub diameter: f64,
    /// Semi-axes `[a1, a2, a3]`, if the table gives them (else the phase's shape law).
    pub semi_axes: Option<[f64; 3]>,
    /// Unit quaternion `[w, x, y, z]`, if the table gives it (else the phase's
    /// orientation law).
    pub quaternion: Option<[f64; 4]>,
    /// Crystal orientation in the sample frame (scalar-first unit quaternion, as
    /// `grains.csv` writes it in `o0..o3`), if the table gives it (else the phase's
    /// texture).
    pub crystal: Option<[f64; 4]>,
}

impl MeasuredGrain {
    /// A grain given by its semi-axes.
    pub fn with_semi_axes(semi_axes: [f64; 3], quaternion: Option<[f64; 4]>) -> Self {
        Self {
            diameter: equivalent_diameter(semi_axes),
            semi_axes: Some(semi_axes),
            quaternion,
            crystal: None,
        }
    }

    /// The longest the grain can be end to end: `2 max(a)`, or for a grain given by its
    /// diameter `None` (its shape law decides).
    pub fn length(&self) -> Option<f64> {
        self.semi_axes.map(|a| 2.0 * a[0].max(a[1]).max(a[2]))
    }
}

/// How a phase uses its measured grains.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MeasuredMode {
    /// Exactly the table's grains, once each, in table order.
    Exact,
    /// Grains drawn from the table uniformly with replacement, with the scene's seed.
    Draw,
}

/// A phase's measured grains.
#[derive(Debug, Clone, PartialEq)]
pub struct Measured {
    /// The grains, in table order; at least one.
    pub grains: Arc<[MeasuredGrain]>,
    /// Exactly these, or drawn from them.
    pub mode: MeasuredMode,
    /// Ellipsoids, or ellipses (a 2D scene's table: `a1`, `a2`, `angle`).
    pub dimension: Dimension,
}

impl Measured {
    /// Whether the table gives semi-axes (then every row does).
    pub fn has_semi_axes(&self) -> bool {
        self.grains[0].semi_axes.is_some()
    }

    /// Whether the table gives orientations (then every row does).
    pub fn has_orientations(&self) -> bool {
        self.grains[0].quaternion.is_some()
    }

    /// Whether the table gives crystal orientations (then every row does).
    pub fn has_crystals(&self) -> bool {
        self.grains[0].crystal.is_some()
    }

    /// Total volume of the grains, `Σ π d³/6`; in 2D their area `Σ π d²/4`.
    pub fn volume(&self) -> f64 {
        match self.dimension {
            Dimension::Three => self
                .grains
                .iter()
                .map(|g| std::f64::consts::PI / 6.0 * g.diameter.powi(3))
                .sum(),
            Dimension::Two => (self.grains.iter())
                .map(|g| self.dimension.measure_of_diameter(g.diameter))
                .sum(),
        }
    }
}
