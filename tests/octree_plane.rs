//! The broad phase in 2D: discs in the mid-plane of a `Domain::plane` slab (as the 2D
//! engine stores ellipses' bounding circles) give exactly the pairs of a 2D brute force
//! over the rectangle's own periodic images, none across the slab's `z` faces.

mod support;

use grainpack::octree::{Octree, Params, Sphere};
use grainpack::scene::{Boundary, Domain};
use rand::Rng;
use support::octree::{rng, sorted_keys, PairKey};

/// Every pair (and periodic image in x, y) of discs that meet, by brute force in 2D.
fn brute_force_2d(discs: &[Sphere], sides: [f64; 2], periodic: bool) -> Vec<PairKey> {
    let images: &[i32] = if periodic { &[-1, 0, 1] } else { &[0] };
    let mut keys = Vec::new();
    for (a, p) in discs.iter().enumerate() {
        for q in &discs[a + 1..] {
            for &kx in images {
                for &ky in images {
                    let shift = [f64::from(kx) * sides[0], f64::from(ky) * sides[1], 0.0];
                    let d = [0, 1].map(|k| q.centre[k] + shift[k] - p.centre[k]);
                    let reach = p.radius + q.radius;
                    if d[0] * d[0] + d[1] * d[1] <= reach * reach {
                        keys.push((p.id, q.id, [kx as i8, ky as i8, 0]));
                    }
                }
            }
        }
    }
    keys.sort_unstable();
    keys
}

#[test]
fn discs_in_the_plane_pair_as_in_2d() {
    for seed in 0..4 {
        let mut r = rng(300 + seed);
        let sides = [3.0, 2.0];
        for boundary in [Boundary::Periodic, Boundary::Reflecting] {
            let domain = Domain::plane(sides, boundary);
            let z = domain.plane_z();
            // Radii 0.01–0.1 (ten to one), with some discs across the x and y faces.
            let discs: Vec<Sphere> = (0..600)
                .map(|id| Sphere {
                    id,
                    centre: [
                        r.random::<f64>() * sides[0],
                        r.random::<f64>() * sides[1],
                        z,
                    ],
                    radius: 0.01 * 10f64.powf(r.random::<f64>()),
                })
                .collect();
            let tree = Octree::build(&discs, domain.box_shape().unwrap(), Params::default())
                .expect("valid scene");
            tree.check_invariants().expect("invariants hold");
            let mut pairs = Vec::new();
            tree.pairs(&mut pairs);
            let got = sorted_keys(&pairs);
            let want = brute_force_2d(&discs, sides, boundary == Boundary::Periodic);
            assert!(!want.is_empty());
            assert_eq!(got, want, "seed {seed}, {boundary:?}");
        }
    }
}
