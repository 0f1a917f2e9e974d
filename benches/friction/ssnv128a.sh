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

. "$(dirname "$0")/../newton_bench.sh"

bench friction "$case_dir/ssnv128a.export"
bench frictionless "$tmp/sans/ssnv128a.export"
