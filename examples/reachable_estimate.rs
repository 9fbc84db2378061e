//! What the reachable estimate costs: `laws::random_close_packing` (Farr and Groot's
//! model, behind `reachable_fraction` and the first relaxation's choice; a run computes
//! it twice) on 10³ to 10⁶ diameters, spread ones and equal ones, with its value:
//!
//! ```sh
//! cargo run --release --example reachable_estimate
//! ```
//!
//! BENCHMARKS.md, "Issue 26: against b030b67 again".

use grainpack::laws::random_close_packing;
use std::time::Instant;

fn main() {
    println!("spheres,diameters,fraction,ms");
    for n in [1_000usize, 10_000, 100_000, 1_000_000] {
        // Spread: e^u for u evenly over [−½, ½), in a scrambled order.
        let spread: Vec<f64> = (0..n)
            .map(|i| (((i * 7919) % n) as f64 / n as f64 - 0.5).exp())
            .collect();
        for (name, d) in [("spread", spread), ("equal", vec![1.0; n])] {
            let start = Instant::now();
            let phi = random_close_packing(&d).expect("positive diameters");
            let ms = start.elapsed().as_secs_f64() * 1e3;
            println!("{n},{name},{phi:.17},{ms:.1}");
        }
    }
}
