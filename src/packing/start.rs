//! Where the grains start: random centres (in the slab's mid-plane for ellipses) and
//! the order along a space-filling curve the loop keeps them in.

use crate::contact::Dimension;
use crate::scene::Domain;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// The random stream used for initial positions (the scene's sampling uses stream 0).
const POSITION_STREAM: u64 = 1;

/// `n` centres uniform in the box, from `seed`'s position stream. Ellipses lie in the
/// slab's mid-plane, which no force leaves (module `contact::Dimension`: every normal
/// and torque of two of them is in-plane).
pub(super) fn random_centres(n: usize, domain: &Domain, seed: u64) -> Vec<[f64; 3]> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(POSITION_STREAM);
    match domain.dimension {
        Dimension::Three => (0..n)
            .map(|_| [0, 1, 2].map(|k| rng.random::<f64>() * domain.size[k]))
            .collect(),
        Dimension::Two => (0..n)
            .map(|_| {
                let [x, y] = [0, 1].map(|k| rng.random::<f64>() * domain.size[k]);
                [x, y, domain.plane_z()]
            })
            .collect(),
    }
}

/// The grains' indices sorted by the Morton code of their centres (10 bits a
/// coordinate), ties by index.
pub(super) fn spatial_order(centres: &[[f64; 3]], size: [f64; 3]) -> Vec<usize> {
    const BITS: u32 = 10;
    let cells = f64::from(1u32 << BITS);
    let spread = |x: u64| {
        // Bit b of x moves to bit 3b.
        (0..BITS).fold(0u64, |acc, b| acc | ((x >> b) & 1) << (3 * b))
    };
    let mut keyed: Vec<(u64, usize)> = centres
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let q = [0, 1, 2].map(|k| ((c[k] / size[k] * cells) as u64).min((1 << BITS) - 1));
            (spread(q[0]) | spread(q[1]) << 1 | spread(q[2]) << 2, i)
        })
        .collect();
    keyed.sort_unstable();
    keyed.into_iter().map(|(_, i)| i).collect()
}
