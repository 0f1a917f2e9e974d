#!/bin/sh
# Issue 17's speed bar: ssna111 (a rigid cone punched into an elasto-plastic
# axisymmetric solid, VMIS_ISOT_LINE under SIMO_MIEHE, 50 steps) end to end,
# and the time per Newton iteration at large strain against small strain on
# the same mesh: ssna111c as shipped (SIMO_MIEHE; LIAISON_UNIL contact) and
# a copy with DEFORMATION='PETIT' (written to a temp dir). Medians of N runs.
# ssna111a (the discrete DEFI_CONTACT variant) is refused before solving
# (docs/cases.md): ssna111c is the same study with the contact held by
# LIAISON_UNIL. The small-strain copy is not a code_aster case: its
# TEST_RESU print NOOK (other answers), only its timing matters.
# Optional: skipped when the case is absent (../shared is not in the repo).
# Usage: benches/large_strain/ssna111.sh [ASTER] [CASES_DIR] [N]
set -eu
aster=${1:-target/ci/aster}
cases=${2:-/work/shared/cases}
n=${3:-5}
case_dir=$cases/ssna111c
[ -f "$case_dir/ssna111c.export" ] || { echo "ssna111c not found under $cases: skipped"; exit 0; }
aster=$(cd "$(dirname "$aster")" && pwd)/$(basename "$aster")
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# The small-strain copy: every file of the case, the command file edited.
mkdir -p "$tmp/petit"
cp "$case_dir"/* "$tmp/petit/"
sed -e 's/DEFORMATION="SIMO_MIEHE"/DEFORMATION="PETIT"/' \
    "$case_dir/ssna111c.comm" > "$tmp/petit/ssna111c.comm"
grep -q 'DEFORMATION="PETIT"' "$tmp/petit/ssna111c.comm" || { echo "edit failed: the case changed"; exit 1; }

med() { sort -n | awk '{a[NR]=$1} END {if (NR) print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }

# One variant, N runs: wall time end to end, then per-iteration CPU from
# ASTER_NEWTON_TIMING (iterations and CPU summed over the case's solves)
# and its behaviour (Gauss-point integration) share.
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
  grep -E '^\[newton\]   ' "$tmp/$name.err" | head -9 || true
}

bench simo_miehe "$case_dir/ssna111c.export"
bench petit "$tmp/petit/ssna111c.export"
