#!/bin/sh
# Alternates two `aster` binaries on one case, N runs each, and prints the
# median CPU time (task-clock, all threads) and wall time of each: on a
# shared machine, alternating keeps both under the same load.
# Usage: benches/start/compare.sh OLD_ASTER NEW_ASTER CASE.export [N]
set -eu
old=$1 new=$2 case=$3 n=${4:-30}
command -v perf >/dev/null || { echo "perf is not installed: skipped"; exit 0; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
i=0
while [ "$i" -lt "$n" ]; do
  for which in old new; do
    eval bin=\$$which
    perf stat -x, -e task-clock -o "$out/stat" "$bin" run -q --out "$out/o" "$case" >/dev/null 2>&1 || true
    s=$(date +%s%N); "$bin" run -q --out "$out/o" "$case" >/dev/null 2>&1 || true; e=$(date +%s%N)
    grep task-clock "$out/stat" | cut -d, -f1 >> "$out/$which.cpu"
    echo $(( (e - s) / 1000 )) >> "$out/$which.wall"
  done
  i=$((i + 1))
done
med() { sort -n "$1" | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }
for which in old new; do
  printf '%s: CPU median %.2f ms, wall median %.2f ms (%d runs)\n' "$which" "$(med "$out/$which.cpu")" "$(echo "$(med "$out/$which.wall") / 1000" | bc -l)" "$n"
done
