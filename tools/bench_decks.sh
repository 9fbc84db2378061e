#!/usr/bin/env bash
# Time and peak memory of writing rve.inp for the kanapy scene (configs/kanapy_elongated.toml)
# at N³ cells: the same run with the voxel RVE only, then with the deck, interleaved.
#
#     tools/bench_decks.sh [N ...]        (default: 64 128 256; needs GNU time, /usr/bin/time)
#
# Prints, per run, the outputs' seconds from summary.json (timings.outputs) and the peak
# RSS; the deck's cost is the difference between the two runs of a size.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for n in "${@:-64 128 256}"; do
    for n1 in $n; do
        for deck in false true; do
            scene="$work/k${n1}_$deck.toml"
            sed '/^\[output\]/,$d' configs/kanapy_elongated.toml >"$scene"
            cat >>"$scene" <<TOML

[phase.elastic]
E = 210e9
nu = 0.3

[output]
dir = "$work/out"
grains_csv = false
vtk = false
centers = false
statistics_png = false
rve = true
rve_resolution = $n1
sections_png = false
abaqus = $deck
TOML
            rm -rf "$work/out"
            rss=$( { /usr/bin/time -f "%M" target/release/pack "$scene" --quiet; } 2>&1 | tail -1)
            outputs=$(python3 -c "import json; print(json.load(open('$work/out/summary.json'))['timings']['outputs'])")
            size=$(du -b "$work/out/rve.inp" 2>/dev/null | cut -f1 || echo 0)
            echo "cells ${n1}^3 abaqus=$deck: outputs ${outputs} s, peak RSS ${rss} kB, rve.inp ${size:-0} bytes"
        done
    done
done
