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

. "$(dirname "$0")/../newton_bench.sh"
SPLIT=1

bench simo_miehe "$case_dir/ssna111c.export"
bench petit "$tmp/petit/ssna111c.export"
