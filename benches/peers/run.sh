#!/usr/bin/env bash
# aster against CalculiX on the same problem and mesh (issue 19's peer table).
#
#   benches/peers/run.sh [--aster BIN] [N...]        (default N: 8 16 32)
#
# For each mesh size N, benches/peers/hertz2d.py writes the 2D Hertz problem
# (a half cylinder pressed on a block, plane strain, frictionless contact)
# for both codes on one mesh; each code runs it once, timed by GNU time.
# Printed per code: unknowns, wall seconds, CPU seconds (user + system),
# peak memory (MB), the force on the loaded line F (half model), the largest
# contact pressure pmax, and its error against Hertz's p0 for the code's own
# F (p0 = sqrt(2F E* / (pi R)), 1/E* = 2 (1 - nu^2) / E).
#
# aster's pressure is the continuous formulation's LAGS_C at the slave nodes;
# CalculiX's is CSTR of its node-to-surface contact (a penalty, so pmax
# oscillates node to node). Skipped, with a message and exit 0, when `ccx`
# (Debian's calculix-ccx) is absent. Timings mean something only on a quiet
# machine: quote medians of several runs.
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
aster="$root/target/ci/aster"
sizes=()
while [ $# -gt 0 ]; do
  case "$1" in
    --aster) aster=$2; shift 2 ;;
    -h|--help) sed -n '2,20p' "$0"; exit 0 ;;
    *) sizes+=("$1"); shift ;;
  esac
done
[ ${#sizes[@]} -eq 0 ] && sizes=(8 16 32)
if ! command -v ccx > /dev/null; then
  echo "peers: ccx (CalculiX) not found: skipped (apt-get install calculix-ccx)"
  exit 0
fi
if [ ! -x "$aster" ]; then
  echo "peers: no aster binary at $aster (cargo build --profile ci -p aster-cli)" >&2
  exit 2
fi
if [ ! -x /usr/bin/time ]; then
  echo "peers: GNU time (/usr/bin/time) is needed" >&2
  exit 2
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

hertz() { # F (half model) -> p0
  awk -v f="$1" 'BEGIN { e = 2.0e5; nu = 0.3; r = 50.0; es = e / (2 * (1 - nu * nu));
    printf "%.6g", sqrt(2 * (f < 0 ? -f : f) * es / (3.141592653589793 * r)) }'
}
row() { # code n unknowns timefile F pmax
  local code=$1 n=$2 dofs=$3 t=$4 f=$5 p=$6
  local p0; p0=$(hertz "$f")
  awk -v code="$code" -v n="$n" -v dofs="$dofs" -v f="$f" -v p="$p" -v p0="$p0" '
    NR == 1 { printf "%-8s %4s %9s %8.2f %8.2f %8.0f %12.6g %12.6g %9.2f%%\n",
      code, n, dofs, $1, $2 + $3, $4 / 1024, (f < 0 ? -f : f), p, 100 * (p - p0) / p0 }' "$t"
}

printf '%-8s %4s %9s %8s %8s %8s %12s %12s %10s\n' code N unknowns wall_s cpu_s peak_MB F pmax "pmax/p0-1"
for n in "${sizes[@]}"; do
  d="$work/$n"
  mkdir -p "$d"
  dofs=$(python3 "$here/hertz2d.py" "$d" --n "$n" | awk '{ print $3 }')
  (cd "$d" && /usr/bin/time -f '%e %U %S %M' -o aster.time \
    "$aster" run -q hertz2d.comm --mesh hertz2d.mail --out out > aster.out 2> aster.err)
  if [ $? -ne 0 ]; then
    echo "aster failed at N=$n:"; tail -3 "$d/aster.err"
  else
    f=$(awk '$1 == "F" && $3 == "REAC_NODA" { print $NF }' "$d/aster.out")
    p=$(awk '$1 == "P0" && $3 == "DEPL" { v = -$NF; if (v > m) m = v } END { printf "%.6g", m }' "$d/aster.out")
    row aster "$n" "$dofs" "$d/aster.time" "$f" "$p"
  fi
  (cd "$d" && /usr/bin/time -f '%e %U %S %M' -o ccx.time ccx -i hertz2d > ccx.out 2>&1)
  if [ $? -ne 0 ] || ! grep -q "total force" "$d/hertz2d.dat"; then
    echo "ccx failed at N=$n:"; tail -3 "$d/ccx.out"
  else
    f=$(awk '/total force/ { getline; getline; f = $2 } END { print f }' "$d/hertz2d.dat")
    p=$(awk '/contact stress/ { m = 0; on = 1; next } on && NF == 4 && $2 + 0 > m { m = $2 + 0 }
             END { printf "%.6g", m }' "$d/hertz2d.dat")
    row ccx "$n" "$dofs" "$d/ccx.time" "$f" "$p"
  fi
done
