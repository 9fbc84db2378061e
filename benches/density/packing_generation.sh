#!/usr/bin/env bash
# Side by side with PackingGeneration (Baranau and Tallarek's C++ generator of
# force-biased and Lubachevsky–Stillinger packings, github.com/VasiliBaranov/
# packing-generation, built from its source with `make` in its _Release folder; it is
# not part of this repository).
#
#   PACKING_GENERATION=/path/PackingGeneration.exe \
#     benches/density/packing_generation.sh PACK_BINARY [SEEDS] [SCENES...]
#
# For each scene (default: mono_periodic.toml and lognormal_periodic.toml of this
# folder; the family of starts from 0.60 to 0.72 of issue 27 is start/*.toml) and
# seed, interleaved: `pack` at each effort of EFFORTS (default "1 3"),
# then PackingGeneration on the very spheres `pack` drew (their diameters), once per
# protocol of PG_MODES (default "-fba:1e-3 -fba:1e-4"; a protocol is a comma list of
# stages `option:contraction rate`, run one after the other on the same packing, as
# "-fba:1e-2,-ls:1e-2"). Both run on one core. Prints one row per run: reached
# fraction and wall time (PackingGeneration's is the sum of its stages).
#
# Without PACKING_GENERATION (or when it is not an executable) it says so and exits 0,
# so that CI, which does not build PackingGeneration, skips it.
set -euo pipefail
pg=${PACKING_GENERATION:-}
if [ -z "$pg" ] || [ ! -x "$pg" ]; then
  echo "packing_generation.sh: PACKING_GENERATION is not set to an executable: skipped" >&2
  exit 0
fi
pack=$1; shift
seeds=${1:-1,2,3}; shift || true
here=$(cd "$(dirname "$0")" && pwd)
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=("$here/mono_periodic.toml" "$here/lognormal_periodic.toml")
efforts=${EFFORTS:-1 3}
modes=${PG_MODES:--fba:1e-3 -fba:1e-4}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
now() { date +%s.%N; }
echo "| scene | seed | grains | program | protocol | reached | time (s) |"
echo "|---|---:|---:|---|---|---:|---:|"
for scene in "${scenes[@]}"; do
  name=$(basename "$scene" .toml)
  # The scene with grains.csv written, so that PackingGeneration gets the same spheres.
  sed 's/^grains_csv = false/grains_csv = true/' "$scene" > "$work/scene.toml"
  for seed in ${seeds//,/ }; do
    for effort in $efforts; do
      { cat "$work/scene.toml"; printf '\n[packing]\neffort = %s\n' "$effort"; } > "$work/effort.toml"
      rm -rf "$work/out"
      t0=$(now)
      "$pack" --quiet --threads 1 --seed "$seed" --out "$work/out" "$work/effort.toml" 2>/dev/null || true
      t1=$(now)
      python3 - "$work/out/summary.json" "$name" "$seed" "$effort" "$t0" "$t1" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
wall = float(sys.argv[6]) - float(sys.argv[5])
print(f"| {sys.argv[2]} | {sys.argv[3]} | {s['grains']} | grainpack | effort {sys.argv[4]} "
      f"({s['stop_reason']}) | {s['packing_fraction']:.4f} | {wall:.1f} |")
PY
    done
    # The drawn diameters (any common scale: PackingGeneration rescales them). It packs
    # spheres only: a scene of other grains (benches/density/start/spheroids_*) gets
    # grainpack's rows alone.
    python3 - "$work/out/grains.csv" "$work/diameters.txt" <<'PY' || continue
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
if any(len({r["a1"], r["a2"], r["a3"]}) > 1 for r in rows):
    sys.exit(1)
open(sys.argv[2], "w").write("".join(f"{2 * float(r['a1']):.17g}\n" for r in rows))
PY
    for mode in $modes; do
      dir="$work/pg"
      rm -rf "$dir" && mkdir -p "$dir" && cp "$work/diameters.txt" "$dir/"
      start=1
      total=0
      for stage in ${mode//,/ }; do
        option=${stage%%:*}
        rate=${stage#*:}
        # Box for a nominal density of 1 (the force-biased algorithm compresses toward
        # it; Lubachevsky–Stillinger ignores it).
        python3 - "$dir" "$seed" "$rate" "$start" <<'PY'
import math, sys
d, seed, rate, start = sys.argv[1:]
diameters = [float(x) for x in open(f"{d}/diameters.txt")]
side = (sum(math.pi / 6 * x**3 for x in diameters)) ** (1 / 3)
open(f"{d}/generation.conf", "w").write(
    f"Particles count: {len(diameters)}\nPacking size: {side!r} {side!r} {side!r}\n"
    f"Generation start: {start}\nSeed: {seed}\nSteps to write: 1000000000\n"
    f"Boundaries mode: 1\nContraction rate: {rate}\n")
PY
        rm -f "$dir/packing.nfo"
        t0=$(now)
        (cd "$dir" && "$pg" "$option" > "log$option.txt" 2>&1) || true
        t1=$(now)
        total=$(python3 -c "print($total + $t1 - $t0)")
        start=0
      done
      python3 - "$dir/packing.nfo" "$name" "$seed" "$(wc -l < "$work/diameters.txt")" "$mode" "$total" <<'PY'
import sys
try:
    text = open(sys.argv[1]).read()
    phi = f"{1 - float(text.split('Final Porosity:')[1].split()[0]):.4f}"
except (OSError, IndexError, ValueError):
    phi = "failed"
print(f"| {sys.argv[2]} | {sys.argv[3]} | {int(sys.argv[4])} | PackingGeneration | "
      f"{sys.argv[5].replace(',', ' then ')} | {phi} | {float(sys.argv[6]):.1f} |")
PY
    done
  done
done
