//! A fixed workload for instruction counts of one contact method on one reference set:
//! `contact_count METHOD SET PASSES` runs `Method::evaluate_all` PASSES times over
//! `tests/data/contact_SET.csv`. Per pair, with valgrind (which does not take AVX-512,
//! hence the AVX2 build):
//!
//! ```sh
//! RUSTFLAGS="-C target-cpu=x86-64-v3" cargo build --release --example contact_count \
//!     --target-dir target/x86-64-v3
//! valgrind --tool=callgrind target/x86-64-v3/release/examples/contact_count fast typical 5
//! ```
//!
//! and the same with 0 passes, the difference divided by 5 × the pairs (BENCHMARKS.md).

use grainpack::contact::Method;
use grainpack::io::cases::CaseTable;
use std::hint::black_box;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.len() != 4 {
        eprintln!("usage: contact_count METHOD SET PASSES (SET: typical, extreme, degenerate)");
        std::process::exit(2);
    }
    let Some(method) = Method::ALL.iter().copied().find(|m| m.name() == args[1]) else {
        eprintln!("contact_count: unknown method {:?}", args[1]);
        std::process::exit(2);
    };
    let path = format!(
        "{}/tests/data/contact_{}.csv",
        env!("CARGO_MANIFEST_DIR"),
        args[2]
    );
    let Ok(passes) = args[3].parse::<usize>() else {
        eprintln!("contact_count: PASSES must be a count, not {:?}", args[3]);
        std::process::exit(2);
    };
    let file = std::fs::File::open(&path).unwrap_or_else(|e| {
        eprintln!("contact_count: {path}: {e}");
        std::process::exit(2);
    });
    let table = CaseTable::read(file).unwrap_or_else(|e| {
        eprintln!("contact_count: {path}: {e}");
        std::process::exit(2);
    });
    let pairs: Vec<_> = (0..table.rows.len())
        .filter_map(|i| table.case(i).ok().map(|c| (c.r12, c.q1, c.q2)))
        .collect();
    for _ in 0..passes {
        black_box(method.evaluate_all(black_box(&pairs)));
    }
    println!("{} pairs, {passes} passes", pairs.len());
}
