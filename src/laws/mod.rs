//! The probability laws of a scene, in one place: the size and aspect-ratio families
//! with their truncation ([`Distribution`]), the von Mises law of an angle
//! ([`VonMises`], [`VonMisesCdf`]), their densities, CDFs and moments, and the sample
//! statistics that compare packed grains with them ([`Moments`], [`ks_distance`]).
//!
//! The sampler (`scene`), the summary and the plots (`io`) all use these, so a law
//! means the same thing wherever it appears.

mod close_packing;
mod density;
mod distribution;
mod fisher;
mod sample;
mod special;
mod stats;
mod table;
mod von_mises;
mod von_mises_cdf;

pub use close_packing::{
    random_close_packing, random_close_packing_discs, random_close_packing_with, FREE_LENGTH,
    FREE_LENGTH_DISCS, RODS,
};
#[cfg(test)]
pub(crate) use distribution::sample_laws;
pub use distribution::Distribution;
pub(crate) use distribution::Invalid;
pub use fisher::Fisher;
pub use stats::{ks_distance, ks_distance_to_value, Moments};
pub use table::{EmpiricalLaw, TableBasis, TableError, TableInterpolation, TableLaw};
pub use von_mises::{VonMises, MAX_KAPPA};
pub use von_mises_cdf::VonMisesCdf;

/// The least share of a distribution its cutoffs must keep: below it the cutoffs
/// "exclude essentially all the mass", and rejection sampling would need over 1000
/// draws per value.
pub const MIN_ACCEPTED_MASS: f64 = 1e-3;

/// The most draws rejection sampling makes for one value. With acceptance at least
/// [`MIN_ACCEPTED_MASS`] = 10⁻³, all 50 000 draws fail with probability
/// `(1 − 10⁻³)^50 000 < e⁻⁵⁰`.
pub const MAX_DRAWS: usize = 50_000;
