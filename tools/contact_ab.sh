#!/usr/bin/env bash
# Two builds of `pack` on the contact reference sets: same output bits, then times.
#
#     tools/contact_ab.sh BASE NEW [PAIRS] [METHODS] [SETS]
#
# BASE and NEW are `pack` binaries (e.g. a copy of target/release/pack built before a
# change, and the one after). First, for accurate, fast, batch and batch-fast on every
# reference set (tests/data/contact_{typical,extreme,degenerate,plane_typical,
# plane_extreme}.csv), `pack contact SET --method M -o out.csv` with both, and `cmp`:
# any difference is printed and makes the exit status 1. Then `pack contact SET --method M
# --time` for each method of METHODS on each set of SETS (defaults: all four methods;
# typical extreme), the two binaries alternately, PAIRS times each (default 5), so both
# see the same machine load; prints the medians of the printed ns_per_call_median.
set -uo pipefail
base=$1 new=$2 pairs=${3:-5}
methods=${4:-"accurate fast batch batch-fast"}
sets=${5:-"typical extreme"}
data="$(cd "$(dirname "$0")/.." && pwd)/tests/data"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
status=0
for m in accurate fast batch batch-fast; do
    for s in typical extreme degenerate plane_typical plane_extreme; do
        "$base" contact "$data/contact_$s.csv" --method $m -o "$work/base.csv" 2>/dev/null
        rb=$?
        "$new" contact "$data/contact_$s.csv" --method $m -o "$work/new.csv" 2>/dev/null
        rn=$?
        if [ $rb != $rn ] || ! cmp -s "$work/base.csv" "$work/new.csv"; then
            echo "DIFFER: $m $s (exit $rb / $rn)"
            status=1
        fi
    done
done
[ $status = 0 ] && echo "outputs identical: 4 methods x 5 sets"
time_of() {
    "$1" contact "$data/contact_$3.csv" --method "$2" --time -o /dev/null 2>&1 >/dev/null |
        sed -n 's/.*"ns_per_call_median":\([0-9.]*\).*/\1/p'
}
median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2}'; }
for m in $methods; do
    for s in $sets; do
        tb="" tn=""
        for _ in $(seq "$pairs"); do
            tb="$tb $(time_of "$base" $m $s)"
            tn="$tn $(time_of "$new" $m $s)"
        done
        mb=$(echo $tb | tr ' ' '\n' | median)
        mn=$(echo $tn | tr ' ' '\n' | median)
        printf '%-10s %-14s base %7.1f  new %7.1f  new/base %.3f\n' $m $s "$mb" "$mn" \
            "$(echo "$mn / $mb" | bc -l)"
    done
done
exit $status
