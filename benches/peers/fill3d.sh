#!/usr/bin/env bash
# The fill of the 3D Cholesky factor under each ordering (issue 19).
#
#   benches/peers/fill3d.sh [N...]        (default N: 4 8)
#
# For each size N, benches/peers/hertz3d.py writes the 3D contact mesh
# (HEXA8, ~216 N^3 unknowns); the `fill3d` example (crates/fem) assembles its
# stiffness matrix and prints nnz(L) and flops under faer's AMD and aster's
# nested dissection, and under METIS's nested dissection when pymetis is
# installed (benches/peers/metis_order.py; skipped otherwise).
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
sizes=("$@")
[ ${#sizes[@]} -eq 0 ] && sizes=(4 8)
(cd "$root" && cargo build -q --profile ci -p aster-fem --example fill3d) || exit 2
bin="$root/target/ci/examples/fill3d"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for n in "${sizes[@]}"; do
  d="$work/$n"
  echo "== N = $n: $(python3 "$here/hertz3d.py" "$d" --n "$n")"
  "$bin" "$d/hertz3d.mail" --graph "$d/graph" > "$d/fill.out" || { cat "$d/fill.out"; continue; }
  if python3 "$here/metis_order.py" "$d/graph" "$d/metis.order"; then
    "$bin" "$d/hertz3d.mail" --graph "$d/graph" --metis "$d/metis.order" --skip-amd
  else
    cat "$d/fill.out"
  fi
done
