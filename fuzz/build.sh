#!/usr/bin/env bash
# Builds the fuzz targets with libFuzzer's coverage instrumentation on the stable
# toolchain (the flags cargo-fuzz passes, without its nightly-only sanitizer):
# inline 8-bit edge counters, a PC table and comparison tracing; debug assertions and
# overflow checks on, so that an arithmetic overflow is a crash too. Binaries land in
# fuzz/target/x86_64-unknown-linux-gnu/release/. Run from anywhere: `nice -n 19 fuzz/build.sh`.
set -euo pipefail
cd "$(dirname "$0")"
export RUSTFLAGS="-Cpasses=sancov-module \
 -Cllvm-args=-sanitizer-coverage-level=4 \
 -Cllvm-args=-sanitizer-coverage-inline-8bit-counters \
 -Cllvm-args=-sanitizer-coverage-pc-table \
 -Cllvm-args=-sanitizer-coverage-trace-compares \
 --cfg fuzzing -Cdebug-assertions -Coverflow-checks"
# --target: RUSTFLAGS then reach the targets only, not build scripts and proc macros.
# --locked: a lock that no longer matches Cargo.toml (the library gained or lost a
# dependency) stops the build instead of being re-resolved behind its back.
cargo build --locked --release --bins --target x86_64-unknown-linux-gnu "$@"
