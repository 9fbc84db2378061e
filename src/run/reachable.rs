//! What the drawn grains are, told before they are packed: how many, the fraction
//! asked for and the fraction drawn, and an estimate of the densest random packing
//! they can reach.

use crate::contact::Dimension;
use crate::scene::{sphere_close_packing, GrainCount, GrainSpec, Scene};
use serde::Serialize;

/// The drawn grains, before packing.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Drawn {
    /// Grains drawn.
    pub grains: usize,
    /// The scene's `target_fraction`, or for a `grains` count its expected fraction.
    pub requested_fraction: f64,
    /// The fraction the drawn grains fill at full size.
    pub drawn_fraction: f64,
    /// The random close packing of spheres with the grains' equivalent diameters
    /// ([`sphere_close_packing`]: Farr and Groot's one-dimensional model), 0.6435 for
    /// equal spheres, more for spread sizes. Exact for spheres only: no model in the
    /// literature covers ellipsoids of any size law, orientation law and freedom to
    /// turn (spheroids of aspect 1.5 free to turn jam near 0.70–0.716, frozen or
    /// slender ones well below spheres), so [`Drawn::spheres`] says whether it applies.
    /// It is the density compression and relaxation reach; the swaps of effort's cycles
    /// (`packing.unjam`) pass it where sizes differ (lognormal spheres, σ = 0.25: 0.683
    /// against 0.664). With a gap (`packing.gap`) the grains pack as if inflated by
    /// `1 + gap`, so the estimate is the inflated grains' divided by `(1 + gap)³`.
    ///
    /// In 2D, the random close packing of discs with the ellipses' equivalent-circle
    /// diameters (0.834 for equal discs, 0.842 for
    /// O'Hern et al.'s bidisperse ones), divided by `(1 + gap)²`. Ellipses free to turn
    /// pack denser than discs (aspect 1.3–1.4: about 0.90, Delaney et al. 2005; Donev
    /// et al. 2007), so for them it is a floor, not a ceiling.
    pub reachable_fraction: f64,
    /// Whether every grain is a sphere (a disc in 2D), so that the estimate applies as
    /// it stands.
    pub spheres: bool,
    /// The scene's `packing.gap`.
    pub gap: f64,
    /// Spheres and volumes, or discs and areas.
    #[serde(skip)]
    pub dimension: Dimension,
}

impl Drawn {
    /// The drawn grains of `scene`.
    pub fn of(scene: &Scene, specs: &[GrainSpec]) -> Self {
        let volume: f64 = specs.iter().map(GrainSpec::volume).sum();
        let dimension = scene.domain.dimension;
        Self {
            grains: specs.len(),
            requested_fraction: match scene.count {
                GrainCount::Fraction(f) => f,
                GrainCount::Exactly(_) => scene.expected_fraction(),
            },
            drawn_fraction: volume / scene.domain.volume(),
            reachable_fraction: sphere_close_packing(specs, dimension).unwrap_or(f64::NAN)
                / (1.0 + scene.packing.gap).powi(dimension.exponent()),
            spheres: (specs.iter()).all(|s| s.semi_axes.iter().all(|&a| a == s.semi_axes[0])),
            gap: scene.packing.gap,
            dimension,
        }
    }

    /// Whether the grains at full size are denser than random packings of spheres of
    /// their sizes reach: the target is then unlikely to be met.
    pub fn above_reachable(&self) -> bool {
        self.drawn_fraction > self.reachable_fraction
    }
}
