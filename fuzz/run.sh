#!/usr/bin/env bash
# One coverage-guided campaign: `fuzz/run.sh TARGET SECONDS [libFuzzer options]`, after
# `fuzz/build.sh`. New inputs go to fuzz/target/corpus/TARGET (the committed seeds in
# fuzz/corpus/TARGET are read, not written); a crash, a hang past one second or a
# memory blow-up is saved in fuzz/artifacts/TARGET/. Run it under `nice -n 19`.
set -euo pipefail
cd "$(dirname "$0")"
target=$1 seconds=$2
shift 2
mkdir -p "target/corpus/$target" "artifacts/$target"
dict=()
case $target in scene_bytes) dict=(-dict=scene.dict) ;; esac
exec "target/x86_64-unknown-linux-gnu/release/$target" \
    -timeout=1 -rss_limit_mb=2048 -max_len=4096 -max_total_time="$seconds" \
    -print_final_stats=1 -artifact_prefix="artifacts/$target/" "${dict[@]}" "$@" \
    "target/corpus/$target" "corpus/$target"
