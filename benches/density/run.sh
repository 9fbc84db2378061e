#!/usr/bin/env bash
# Density benchmark over scene classes: packs each scene of this folder with each seed
# and prints one row per run (reached fraction, packing time, stop reason).
#
#   benches/density/run.sh PACK_BINARY [SEEDS] [SCENES...]
#
# PACK_BINARY is a built `pack` (target/release/pack); SEEDS a comma list (default
# 1,2,3); SCENES default to every *.toml here. Runs on one thread (--threads 1), so
# that runs of two builds can be interleaved on a shared machine.
set -euo pipefail
pack=$1; shift
seeds=${1:-1,2,3}; shift || true
here=$(cd "$(dirname "$0")" && pwd)
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=("$here"/*.toml)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "| scene | seed | grains | requested | drawn | reached | estimate | time (s) | stop |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|---|"
for scene in "${scenes[@]}"; do
  for seed in ${seeds//,/ }; do
    "$pack" --quiet --threads 1 --seed "$seed" --out "$out" "$scene" 2>/dev/null || true
    python3 - "$out/summary.json" "$(basename "$scene" .toml)" "$seed" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
get = lambda k, f: f.format(s[k]) if s.get(k) is not None else "–"
print(f"| {sys.argv[2]} | {sys.argv[3]} | {s['grains']} | {get('target_fraction', '{:.4f}')} | "
      f"{get('full_size_fraction', '{:.4f}')} | {s['packing_fraction']:.4f} | "
      f"{get('reachable_fraction', '{:.3f}')} | {s['timings']['packing']:.2f} | {s['stop_reason']} |")
PY
    rm -f "$out/summary.json"
  done
done
