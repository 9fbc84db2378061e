//! Scene files: TOML in, a validated [`Scene`] out, and grains drawn from it.
//!
//! Two layers, as the crate's style asks: `raw` mirrors the file with serde
//! (`deny_unknown_fields`, every value spanned), and `validate` turns it into a
//! [`Scene`] of typed, checked values. Nothing downstream sees a raw string or checks
//! again. Every key and its default is documented in `docs/config.md`.
//!
//! ```
//! use grainpack::io::scene::{GrainCount, Scene};
//! let text = r#"
//!     seed = 7
//!     grains = 50
//!     [box]
//!     size = [40, 40, 40]
//!     [[phase]]
//!     name = "ferrite"
//!     size = { distribution = "lognormal", sigma = 0.3, scale = 6, min = 3, max = 12 }
//! "#;
//! let scene = Scene::from_str(text, "example.toml").unwrap();
//! assert_eq!(scene.count, GrainCount::Exactly(50));
//! let grains = scene.sample_grains(&mut scene.rng()).unwrap();
//! assert_eq!(grains.len(), 50);
//! ```

mod density;
mod distribution;
mod error;
mod orientation;
mod output;
mod raw;
mod sample;
mod special;
mod validate;
mod von_mises;

#[cfg(test)]
pub(crate) use distribution::sample_laws;
pub use distribution::Distribution;
pub use error::{SampleError, SceneError, TOP_LEVEL};
pub use orientation::{rotation_column, Axis, Orientation};
pub use output::{
    proportional_cells, OutputSpec, RveFill, RveSpec, VtkSpec, DEFAULT_RVE_CELLS,
    DEFAULT_VTK_RESOLUTION, MAX_RVE_CELLS, MAX_RVE_CELLS_PER_EDGE, MAX_VTK_RESOLUTION,
    MIN_VTK_RESOLUTION,
};
pub use sample::GrainSpec;
pub use von_mises::{VonMises, MAX_KAPPA};

use std::f64::consts::PI;
use std::path::Path;

/// The largest `target_fraction` accepted, and the largest expected packing fraction
/// of a `grains` count: 0.7707, the densest known packing of congruent ellipsoids
/// (Donev et al., *Phys. Rev. Lett.* 92, 255506, 2004), denser than any sphere packing
/// (0.7405). Random packings made by growth jam well below it (spheres ≈ 0.64,
/// spheroids of aspect 1.5 ≈ 0.70–0.72), so a request above it cannot be met.
pub const MAX_TARGET_FRACTION: f64 = 0.7707;

/// The least share of a distribution its cutoffs must keep: below it the cutoffs
/// "exclude essentially all the mass", and rejection sampling would need over 1000
/// draws per value.
pub const MIN_ACCEPTED_MASS: f64 = 1e-3;

/// The most draws rejection sampling makes for one value. With acceptance at least
/// [`MIN_ACCEPTED_MASS`] = 10⁻³, all 50 000 draws fail with probability
/// `(1 − 10⁻³)^50 000 < e⁻⁵⁰`.
pub const MAX_DRAWS: usize = 50_000;

/// The most grains a scene may ask for, exactly or expected from its target fraction
/// (about 2 GB of grain state in the packing loop).
pub const MAX_GRAINS: usize = 10_000_000;

/// A validated scene: what to pack, into what, and what to write.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// Seed of the random generator ([`Scene::rng`]).
    pub seed: u64,
    /// The box.
    pub domain: Domain,
    /// How many grains to draw.
    pub count: GrainCount,
    /// The phases, in file order (a grain's phase is its index here); at least one.
    pub phases: Vec<Phase>,
    /// Parameters of the packing loop.
    pub packing: PackingParams,
    /// What to write, and where.
    pub output: OutputSpec,
}

/// The box `[0, Lx) × [0, Ly) × [0, Lz)` and its boundary.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Domain {
    /// Edge lengths `[Lx, Ly, Lz]`, positive and finite.
    pub size: [f64; 3],
    /// Periodic or walled.
    pub boundary: Boundary,
}

impl Domain {
    /// `Lx·Ly·Lz`.
    pub fn volume(&self) -> f64 {
        self.size.iter().product()
    }

    /// The shortest edge.
    pub fn min_side(&self) -> f64 {
        self.size.iter().copied().fold(f64::INFINITY, f64::min)
    }
}

/// How the faces of the box behave.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Boundary {
    /// Opposite faces are glued: grains wrap around.
    Periodic,
    /// The faces are walls: grains stay entirely inside.
    Reflecting,
}

/// How many grains a scene has.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum GrainCount {
    /// Exactly this many (`grains = N`).
    Exactly(usize),
    /// As many as it takes for their volumes to reach this fraction of the box
    /// (`target_fraction = φ`): grains are drawn until their total volume first
    /// reaches `φ·V`, so it exceeds `φ·V` by less than the last grain's volume.
    Fraction(f64),
}

/// One phase: its share of the grain volume and its grain statistics.
#[derive(Debug, Clone, PartialEq)]
pub struct Phase {
    /// Name, unique within the scene.
    pub name: String,
    /// Share of the total grain volume, in `(0, 1]`; the shares sum to 1.
    pub share: f64,
    /// Equivalent-sphere diameter `d`: the grain's volume is `π d³/6`.
    pub size: Distribution,
    /// Aspect ratio `α = a1/a2` with `a2 = a3` (see [`GrainSpec`]).
    pub aspect_ratio: Distribution,
    /// How the grains are oriented.
    pub orientation: Orientation,
}

impl Phase {
    /// Expected volume of one grain, `π E[d³]/6`.
    pub fn expected_volume(&self) -> f64 {
        PI / 6.0 * self.size.moment(3)
    }

    /// The longest any grain can be end to end: `d_max · max(α_max^{2/3}, α_min^{−1/3})`
    /// (the first axis `2a1 = d α^{2/3}` of a prolate grain, the equatorial diameter
    /// `2a2 = d α^{−1/3}` of an oblate one).
    pub fn max_length(&self) -> f64 {
        let (_, d_max) = self.size.support();
        let (a_min, a_max) = self.aspect_ratio.support();
        d_max * a_max.powf(2.0 / 3.0).max(a_min.powf(-1.0 / 3.0))
    }
}

/// Parameters of the packing loop, with defaults a user rarely changes
/// (`[packing]` in the scene file). The loop documents how it uses each.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PackingParams {
    /// Step limit: the loop stops with the reason "step limit" after this many FIRE
    /// steps in all. Default 100 000.
    pub max_steps: u64,
    /// When the target cannot be reached, the loop bisects the scale between the best
    /// overlap-free one and the smallest jammed one until they are this close
    /// (relative). In `(0, 0.1]`; default 10⁻³ (0.3 % of packing fraction).
    pub jam_resolution: f64,
    /// Whether and how grains may turn while packing. Default [`Rotation::None`]:
    /// orientations stay as drawn, as the scene's statistics ask.
    pub rotation: Rotation,
    /// The most a grain may turn away from its drawn orientation, in radians, in
    /// `(0, π]`. Default π: no limit.
    pub max_turn: f64,
    /// Whether grains that may turn are turned back toward their drawn orientations,
    /// as far as their neighbours let them, once packed at the target. Default true.
    pub restore: bool,
}

impl Default for PackingParams {
    fn default() -> Self {
        Self {
            max_steps: 100_000,
            jam_resolution: 1e-3,
            rotation: Rotation::None,
            max_turn: std::f64::consts::PI,
            restore: true,
        }
    }
}

/// How grains may turn while packing (`packing.rotation`). Turning lets a jammed
/// packing grow denser, at the price of orientations that are no longer the drawn ones:
/// the summary reports how far grains turned.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rotation {
    /// Orientations stay as drawn (`false`).
    None,
    /// Grains turn freely (`true`).
    Free,
    /// Grains of a tilt phase turn only about its tilt axis, so that their first axis
    /// stays in the plane the scene puts it in; other grains keep their orientation
    /// (`"axis"`).
    Axis,
}

impl Rotation {
    /// The value as `summary.json` names it.
    pub fn name(self) -> &'static str {
        match self {
            Self::None => "none",
            Self::Free => "free",
            Self::Axis => "axis",
        }
    }
}

/// `1 / Σₚ (shareₚ / E[vₚ])`: see [`Scene::expected_grain_volume`].
fn mean_grain_volume(phases: &[Phase]) -> f64 {
    1.0 / phases
        .iter()
        .map(|p| p.share / p.expected_volume())
        .sum::<f64>()
}

impl Scene {
    /// Reads and validates a scene file; errors name `path`.
    pub fn from_path(path: &Path) -> Result<Self, SceneError> {
        let text = std::fs::read_to_string(path).map_err(|source| SceneError::Read {
            path: path.to_owned(),
            source,
        })?;
        Self::from_str(&text, &path.display().to_string())
    }

    /// Validates a scene given as text; errors name the file `name`.
    pub fn from_str(text: &str, name: &str) -> Result<Self, SceneError> {
        validate::scene(text, name)
    }

    /// Mean volume of a grain over all phases: grains are drawn so that each phase gets
    /// its share of the volume, so this is `1 / Σₚ (shareₚ / E[vₚ])`.
    pub fn expected_grain_volume(&self) -> f64 {
        mean_grain_volume(&self.phases)
    }

    /// The expected number of grains (exact for [`GrainCount::Exactly`]).
    pub fn expected_count(&self) -> f64 {
        match self.count {
            GrainCount::Exactly(n) => n as f64,
            GrainCount::Fraction(f) => f * self.domain.volume() / self.expected_grain_volume(),
        }
    }

    /// The expected packing fraction of the grains at full size (the target itself for
    /// [`GrainCount::Fraction`], up to the last grain's overshoot).
    pub fn expected_fraction(&self) -> f64 {
        match self.count {
            GrainCount::Exactly(n) => {
                n as f64 * self.expected_grain_volume() / self.domain.volume()
            }
            GrainCount::Fraction(f) => f,
        }
    }
}
