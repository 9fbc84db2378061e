//! The scene as a model: the box, the phases and their grain laws, the packing
//! parameters and what to write, as typed, validated values; and drawing grains
//! from it ([`Scene::sample_grains`]).
//!
//! A scene is read from a TOML file by [`crate::io::scene`], which validates every
//! value; nothing here parses text. The packing loop and the exports take what they
//! need from it.
//!
//! ```
//! use grainpack::scene::{GrainCount, Scene};
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

mod close_packing;
mod crystal;
mod domain;
mod elastic;
mod fisher;
mod grain;
mod measured;
mod measured_draw;
mod orientation;
mod output;
mod params;
mod shape;
mod units;

use crate::contact::Dimension;
use crate::laws::Distribution;
pub use close_packing::{affine_slenderness, sphere_close_packing};
pub use crystal::{
    euler_to_quaternion, fibre_angle, quaternion_to_euler, random_angle_cdf, rotate,
    rotation_angle, PhaseTexture, Texture,
};
pub use domain::{Boundary, Domain};
pub use elastic::Elastic;
pub use fisher::{perpendicular, FisherOrientation, Spin};
pub use grain::{aspect_ratio, GrainSpec, SampleError, CRYSTAL_STREAM};
pub use measured::{Measured, MeasuredGrain, MeasuredMode};
pub use orientation::{tilt_angle, tilt_angle_of, Axis, Orientation};
pub use output::{
    proportional_cells, rve_cells, MeshSpec, OutputSpec, RveFill, RveSpec, VtkSpec,
    DEFAULT_MESH_SIZE, DEFAULT_RVE_CELLS, DEFAULT_VTK_RESOLUTION, MAX_RVE_CELLS,
    MAX_RVE_CELLS_PER_EDGE, MAX_VTK_RESOLUTION, MESH_SIZE_RANGE, MIN_MESH_GAP, MIN_VTK_RESOLUTION,
};
pub use params::{PackingParams, Rotation, Unjam};
pub use shape::{triaxial_semi_axes, ThirdRatio, Triaxial};
use std::f64::consts::PI;
pub use units::{
    LengthUnit, StressUnit, Units, PLAUSIBLE_BOX_M, PLAUSIBLE_CRYSTAL_STIFFNESS_PA,
    PLAUSIBLE_MODULUS_PA,
};

/// The largest `target_fraction` accepted, and the largest expected packing fraction
/// of a `grains` count: 0.7707, the densest known packing of congruent ellipsoids
/// (Donev et al., *Phys. Rev. Lett.* 92, 255506, 2004), denser than any sphere packing
/// (0.7405). Random packings made by growth jam well below it (spheres ≈ 0.64,
/// spheroids of aspect 1.5 ≈ 0.70–0.72), so a request above it cannot be met.
///
/// A 2D scene's limit is [`Dimension::densest_fraction`] of ellipses, `π/√12`.
pub const MAX_TARGET_FRACTION: f64 = 0.7707;

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
    /// The matrix material of `rve_fill = "matrix"` (`[matrix]`).
    pub matrix: Matrix,
    /// DAMASK's homogenization of every material (`[homogenization]`); `None` for the
    /// default, [`Homogenization::single_crystal`].
    pub homogenization: Option<Homogenization>,
    /// The units of the scene's lengths and stresses (`[units]`).
    pub units: Units,
    /// Values the scene may have but probably does not mean (a modulus or a box side
    /// far outside what the stated units make plausible), each a message naming the
    /// file, line, key and value; the run goes on, `pack` prints them and
    /// `summary.json` lists them.
    pub warnings: Vec<String>,
}

/// The one `homogenization` entry of `material.yaml` that every material uses: each
/// material is one grain, so one constituent.
#[derive(Debug, Clone, PartialEq)]
pub struct Homogenization {
    /// The entry's name, which every material refers to.
    pub name: String,
    /// The entry as written in the scene (without `name`), `N_constituents = 1` added
    /// if absent.
    pub entry: toml::Table,
}

impl Homogenization {
    /// The default: `SX`, one constituent, `mechanical: {type: pass}`.
    pub fn single_crystal() -> Self {
        let mut entry = toml::Table::new();
        entry.insert("N_constituents".into(), toml::Value::Integer(1));
        let mut mechanical = toml::Table::new();
        mechanical.insert("type".into(), toml::Value::String("pass".into()));
        entry.insert("mechanical".into(), toml::Value::Table(mechanical));
        Self {
            name: "SX".into(),
            entry,
        }
    }
}

/// The matrix material of a voxel RVE with `rve_fill = "matrix"` (`[matrix]`): the
/// material after the grains in `material.yaml` and `rve.inp`.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Matrix {
    /// Isotropic elastic constants (`[matrix.elastic]`), in the scene's units.
    pub elastic: Option<Elastic>,
    /// The matrix's DAMASK `phase` entry (`[matrix.damask]`), passed through.
    pub damask: Option<toml::Table>,
}

/// How many grains a scene has.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum GrainCount {
    /// Exactly this many (`grains = N`).
    Exactly(usize),
    /// As many as it takes for their volumes to reach this fraction of the box
    /// (`target_fraction = φ`): grains are drawn until their total volume first
    /// reaches `φ·V`, and the last one is kept only if that lands nearer `φ·V`, so the
    /// total is within half a grain's volume of `φ·V`.
    Fraction(f64),
}

/// One phase: its share of the grain volume and its grain statistics.
#[derive(Debug, Clone, PartialEq)]
pub struct Phase {
    /// Name, unique within the scene.
    pub name: String,
    /// Share of the total grain volume, in `(0, 1]`; the shares sum to 1.
    pub share: f64,
    /// Equivalent-sphere diameter `d`: the grain's volume is `π d³/6`; in 2D the
    /// equivalent-circle diameter, the ellipse's area being `π d²/4`.
    pub size: Distribution,
    /// Aspect ratio `α = a1/a2` with `a2 = a3` (see [`GrainSpec`]); of the ellipse's
    /// semi-axes in 2D ([`GrainSpec::ellipse`]).
    pub aspect_ratio: Distribution,
    /// How the grains are oriented.
    pub orientation: Orientation,
    /// The law of the grains' crystal orientations (`[phase.texture]`).
    pub texture: PhaseTexture,
    /// Isotropic elastic constants (`[phase.elastic]`, in the scene's units), for the
    /// Abaqus deck and DAMASK's Hooke phase; `None` if not given.
    pub elastic: Option<Elastic>,
    /// The phase's DAMASK `phase` entry (`[phase.damask]`), passed through to
    /// `material.yaml` as written; `None` for the documented placeholder.
    pub damask: Option<toml::Table>,
    /// For triaxial grains, the laws of `b/a` and `c/a` (or `c/b`) that replace
    /// [`Phase::aspect_ratio`]; `None` for spheroids.
    pub triaxial: Option<Triaxial>,
    /// Grains from a measured table (`[phase.measured]`); `None` for drawn phases.
    /// [`Phase::size`] is then the table's empirical law of diameters.
    pub measured: Option<Measured>,
    /// Ellipsoids, or ellipses (the scene's box has two lengths): the grains drawn are
    /// [`GrainSpec::ellipse`]s, their measure an area.
    pub dimension: Dimension,
}

impl Phase {
    /// Expected volume of one grain, `π E[d³]/6`; in 2D its expected area `π E[d²]/4`.
    pub fn expected_volume(&self) -> f64 {
        match self.dimension {
            Dimension::Three => PI / 6.0 * self.size.moment(3),
            Dimension::Two => PI / 4.0 * self.size.moment(2),
        }
    }

    /// The longest any grain can be end to end: `d_max · max(α_max^{2/3}, α_min^{−1/3})`
    /// (the first axis `2a1 = d α^{2/3}` of a prolate grain, the equatorial diameter
    /// `2a2 = d α^{−1/3}` of an oblate one).
    ///
    /// Triaxial grains: the first axis `2a = d (βγ)^{−1/3}` at the largest `d` and the
    /// smallest `βγ` ([`Triaxial::min_product`]).
    ///
    /// Ellipses: `d_max · max(α_max^{1/2}, α_min^{−1/2})` (`2a1 = d α^{1/2}`,
    /// `2a2 = d α^{−1/2}`).
    pub fn max_length(&self) -> f64 {
        let (_, d_max) = self.size.support();
        if let Some(m) = self.measured.as_ref().filter(|m| m.has_semi_axes()) {
            return m
                .grains
                .iter()
                .filter_map(|g| g.length())
                .fold(0.0, f64::max);
        }
        if let Some(t) = &self.triaxial {
            return d_max / t.min_product().cbrt();
        }
        let (a_min, a_max) = self.aspect_ratio.support();
        if self.dimension == Dimension::Two {
            return d_max * a_max.sqrt().max(1.0 / a_min.sqrt());
        }
        d_max * a_max.powf(2.0 / 3.0).max(a_min.powf(-1.0 / 3.0))
    }
}

impl Phase {
    /// A lower bound on the shortest semi-axis any grain can have: `d_min/2` times
    /// `min(α_min^{2/3}, α_max^{−1/3})` for spheroids, `min(α_min^{1/2}, α_max^{−1/2})`
    /// for ellipses, `γ_min^{2/3}` for triaxial grains (`c = (d/2) γ^{2/3} β^{−1/3}`,
    /// `β ≤ 1`); a table's semi-axes, if it gives them.
    pub fn min_semi_axis(&self) -> f64 {
        if let Some(m) = self.measured.as_ref().filter(|m| m.has_semi_axes()) {
            // An ellipse's third semi-axis, √(a1 a2), is never the shortest.
            return (m.grains.iter())
                .filter_map(|g| g.semi_axes)
                .map(|a| a[0].min(a[1]).min(a[2]))
                .fold(f64::INFINITY, f64::min);
        }
        let half = 0.5 * self.size.support().0;
        if let Some(t) = &self.triaxial {
            let gamma = match &t.third {
                ThirdRatio::OverA(law) => law.support().0,
                ThirdRatio::OverB(law) => t.b_over_a.support().0 * law.support().0,
            };
            return half * gamma.powf(2.0 / 3.0);
        }
        let (a_min, a_max) = self.aspect_ratio.support();
        match self.dimension {
            Dimension::Two => half * a_min.sqrt().min(1.0 / a_max.sqrt()),
            Dimension::Three => half * a_min.powf(2.0 / 3.0).min(a_max.powf(-1.0 / 3.0)),
        }
    }
}

/// `1 / Σₚ (shareₚ / E[vₚ])`: see [`Scene::expected_grain_volume`].
pub(crate) fn mean_grain_volume(phases: &[Phase]) -> f64 {
    1.0 / phases
        .iter()
        .map(|p| p.share / p.expected_volume())
        .sum::<f64>()
}

impl Scene {
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
