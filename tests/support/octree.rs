//! Scene generators and set comparisons shared by the octree tests.

use grainpack::octree::{brute_force_pairs, BoxShape, Octree, Pair, Params, Sphere};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// A pair as an exactly comparable key: ids and the periodic image.
pub type PairKey = (u32, u32, [i8; 3]);

pub fn key(p: &Pair) -> PairKey {
    (p.i, p.j, p.image)
}

/// The pairs as a sorted list of keys, asserting that none repeats.
pub fn sorted_keys(pairs: &[Pair]) -> Vec<PairKey> {
    let mut keys: Vec<PairKey> = pairs.iter().map(key).collect();
    keys.sort_unstable();
    let n = keys.len();
    keys.dedup();
    assert_eq!(keys.len(), n, "a pair was reported twice");
    keys
}

/// Builds the tree, checks its invariants and that its pair set equals brute force's
/// exactly; returns how many pairs there were.
pub fn assert_matches_brute_force(spheres: &[Sphere], shape: BoxShape, params: Params) -> usize {
    let tree = Octree::build(spheres, shape, params).expect("valid scene");
    tree.check_invariants().expect("invariants hold");
    let mut got = Vec::new();
    let stats = tree.pairs(&mut got);
    assert_eq!(stats.pairs as usize, got.len());
    let mut want = Vec::new();
    brute_force_pairs(spheres, &shape, &mut want).expect("valid scene");
    let (got, want) = (sorted_keys(&got), sorted_keys(&want));
    if got != want {
        let missing: Vec<_> = want
            .iter()
            .filter(|k| got.binary_search(k).is_err())
            .collect();
        let extra: Vec<_> = got
            .iter()
            .filter(|k| want.binary_search(k).is_err())
            .collect();
        panic!(
            "pair sets differ ({} vs {}): missing {:?}, extra {:?}",
            got.len(),
            want.len(),
            &missing[..missing.len().min(5)],
            &extra[..extra.len().min(5)]
        );
    }
    for p in &got {
        assert!(p.0 < p.1 || (p.0 == p.1 && p.2 != [0; 3]), "bad pair {p:?}");
    }
    got.len()
}

pub fn rng(seed: u64) -> StdRng {
    StdRng::seed_from_u64(seed)
}

/// Radii log-uniform in `[r_min, r_min · ratio]`.
pub fn log_uniform(rng: &mut StdRng, r_min: f64, ratio: f64) -> f64 {
    r_min * ratio.powf(rng.random::<f64>())
}

/// `n` spheres with uniform centres in the box and radii from `radius`; ids are a
/// shuffled range so that tree order, input order and id order all differ.
pub fn uniform(
    rng: &mut StdRng,
    n: usize,
    lengths: [f64; 3],
    mut radius: impl FnMut(&mut StdRng) -> f64,
) -> Vec<Sphere> {
    let mut ids: Vec<u32> = (0..n as u32).map(|k| 3 * k + 1).collect();
    for k in (1..n).rev() {
        ids.swap(k, rng.random_range(0..=k));
    }
    ids.into_iter()
        .map(|id| Sphere {
            id,
            centre: lengths.map(|l| rng.random::<f64>() * l),
            radius: radius(rng),
        })
        .collect()
}

/// `n` spheres in a few tight Gaussian-ish clusters (sums of uniforms), some of which
/// straddle the faces.
pub fn clustered(rng: &mut StdRng, n: usize, lengths: [f64; 3], radius: f64) -> Vec<Sphere> {
    let clusters: Vec<[f64; 3]> = (0..4)
        .map(|_| lengths.map(|l| rng.random::<f64>() * l))
        .collect();
    (0..n as u32)
        .map(|id| {
            let c = clusters[rng.random_range(0..clusters.len())];
            let spread = 0.05 * lengths[0];
            let centre = [0, 1, 2].map(|a| {
                let g: f64 = (0..4).map(|_| rng.random::<f64>() - 0.5).sum();
                c[a] + spread * g
            });
            Sphere {
                id,
                centre,
                radius: radius * (0.5 + rng.random::<f64>()),
            }
        })
        .collect()
}

/// `n` spheres whose coordinates sit at or near the faces (on them, just inside, just
/// outside, exactly at `L`, far outside) so that every face, edge and corner is crossed.
pub fn on_faces(rng: &mut StdRng, n: usize, lengths: [f64; 3], radius: f64) -> Vec<Sphere> {
    (0..n as u32)
        .map(|id| {
            let centre = lengths.map(|l| match rng.random_range(0..8) {
                0 => 0.0,
                1 => l,
                2 => rng.random::<f64>() * radius,
                3 => l - rng.random::<f64>() * radius,
                4 => -rng.random::<f64>() * radius,
                5 => l + rng.random::<f64>() * radius,
                6 => l * (rng.random_range(-2..3) as f64) + rng.random::<f64>() * l,
                _ => rng.random::<f64>() * l,
            });
            Sphere {
                id,
                centre,
                radius: radius * (0.5 + rng.random::<f64>()),
            }
        })
        .collect()
}
