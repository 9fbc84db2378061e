#!/usr/bin/env bash
# pw85 (the C++ reference library of the Perram–Wertheim contact function) against
# `pack contact`, on the same machine in the same run.
#
#     tools/pw85/run.sh PW85_DIR PACK [ROUNDS] [SETS]
#
# PW85_DIR is a checkout of https://github.com/sbrisard/pw85 (v2, header-only: its
# include/pw85/pw85.hpp), PACK a release build of `pack`, or several separated by spaces
# in one argument (e.g. "/tmp/pack-base target/release/pack": each round times pw85 and
# every build, so all see the same load). Needs g++ and Boost's headers
# (Debian: apt-get install libboost-dev). Compiles tools/pw85/pw85_time.cpp with -O3
# -march=native (as .cargo/config.toml builds grainpack for the native CPU), then for
# each set of SETS (default: typical extreme) runs pw85 and `pack contact SET --method M
# --time` for accurate, fast, batch and batch-fast alternately, ROUNDS times (default 5),
# and prints the medians of ns_per_call_median and pw85's time over each of ours.
set -euo pipefail
if [ $# -lt 2 ]; then
    sed -n '2,15p' "$0" >&2
    exit 2
fi
pw85=$1 packs=$2 rounds=${3:-5}
sets=${4:-"typical extreme"}
[ -f "$pw85/include/pw85/pw85.hpp" ] || { echo "run.sh: no include/pw85/pw85.hpp in $pw85" >&2; exit 2; }
for pack in $packs; do
    [ -x "$pack" ] || { echo "run.sh: $pack is not an executable" >&2; exit 2; }
done
here=$(cd "$(dirname "$0")" && pwd)
data="$here/../../tests/data"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
g++ -O3 -march=native -DNDEBUG -std=c++17 -I "$pw85/include" "$here/pw85_time.cpp" -o "$work/pw85_time" ||
    { echo "run.sh: compiling failed (Boost's headers: apt-get install libboost-dev)" >&2; exit 1; }
ns() { sed -n 's/.*"ns_per_call_median":\([0-9.]*\).*/\1/p'; }
median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2}'; }
methods="accurate fast batch batch-fast"
for s in $sets; do
    set_csv="$data/contact_$s.csv"
    "$work/pw85_time" "$set_csv" | sed -n 's/.*"max_rel_error":\([^}]*\)}.*/pw85 '"$s"': largest relative error of mu^2 \1/p'
    declare -A times=()
    for _ in $(seq "$rounds"); do
        times[pw85]+=" $("$work/pw85_time" "$set_csv" | ns)"
        for pack in $packs; do
            for m in $methods; do
                times[$pack $m]+=" $("$pack" contact "$set_csv" --method $m --time -o /dev/null 2>&1 >/dev/null | ns)"
            done
        done
    done
    p=$(echo ${times[pw85]} | tr ' ' '\n' | median)
    printf '%-10s %-9s %8.1f ns\n' pw85 "$s" "$p"
    for pack in $packs; do
        [ "$packs" = "$pack" ] || echo "$pack:"
        for m in $methods; do
            t=$(echo ${times[$pack $m]} | tr ' ' '\n' | median)
            printf '%-10s %-9s %8.1f ns  pw85 / this %.2f\n' "$m" "$s" "$t" "$(echo "$p / $t" | bc -l)"
        done
    done
    unset times
done
