#!/bin/sh
# ssnv128a (discrete penalised Coulomb friction, 2D) end to end, and the
# time per Newton iteration with friction against the same case
# frictionless (a copy with FROTTEMENT='SANS' and the zone's friction
# keywords removed, written to a temp dir). Medians of N runs.
# Optional: skipped when the case is absent (../shared is not in the repo).
# Usage: benches/friction/ssnv128a.sh [ASTER] [CASES_DIR] [N]
set -eu
aster=${1:-target/ci/aster}
cases=${2:-/work/shared/cases}
n=${3:-7}
case_dir=$cases/ssnv128a
[ -f "$case_dir/ssnv128a.export" ] || { echo "ssnv128a not found under $cases: skipped"; exit 0; }
aster=$(cd "$(dirname "$aster")" && pwd)/$(basename "$aster")
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# The frictionless copy: every file of the case, the command file edited.
mkdir -p "$tmp/sans"
cp "$case_dir"/* "$tmp/sans/"
sed -e 's/FROTTEMENT="COULOMB"/FROTTEMENT="SANS"/' \
    -e '/^ *COULOMB=/d' -e '/^ *ALGO_FROT=/d' -e '/^ *E_T=/d' -e '/^ *COEF_MATR_FROT=/d' \
    "$case_dir/ssnv128a.comm" > "$tmp/sans/ssnv128a.comm"
grep -q 'FROTTEMENT="SANS"' "$tmp/sans/ssnv128a.comm" || { echo "edit failed: the case changed"; exit 1; }

med() { sort -n | awk '{a[NR]=$1} END {if (NR) print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }

# One variant, N runs: wall time end to end, then per-iteration CPU from
# ASTER_NEWTON_TIMING (iterations and CPU summed over the case's solves).
bench() {
  name=$1 export=$2
  : > "$tmp/$name.wall"; : > "$tmp/$name.iter"; : > "$tmp/$name.cpu"
  i=0
  while [ "$i" -lt "$n" ]; do
    s=$(date +%s%N)
    ASTER_NEWTON_TIMING=1 "$aster" run -q --out "$tmp/o-$name" "$export" > "$tmp/$name.out" 2> "$tmp/$name.err" || true
    e=$(date +%s%N)
    echo $(( (e - s) / 1000 )) >> "$tmp/$name.wall"
    # "[newton] non-linear solve: 98 iterations, 0.293 s wall, 0.243 s CPU; …"
    awk '/non-linear solve:/ {it += $4; cpu += $9} END {print it, cpu}' "$tmp/$name.err" > "$tmp/$name.sum"
    read it cpu < "$tmp/$name.sum"
    echo "$it" >> "$tmp/$name.iter"
    echo "$cpu $it" | awk '{ if ($2 > 0) printf "%.4f\n", 1000 * $1 / $2 }' >> "$tmp/$name.cpu"
    i=$((i + 1))
  done
  tally=$(grep 'TEST_RESU:' "$tmp/$name.out" | tail -1)
  printf '%-12s end to end: wall median %.3f s (%d runs); Newton iterations %s; CPU per iteration median %s ms; %s\n' \
    "$name" "$(med < "$tmp/$name.wall" | awk '{print $1 / 1e6}')" "$n" \
    "$(med < "$tmp/$name.iter")" "$(med < "$tmp/$name.cpu")" "$tally"
}

bench friction "$case_dir/ssnv128a.export"
bench frictionless "$tmp/sans/ssnv128a.export"
