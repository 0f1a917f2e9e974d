#!/bin/sh
# Stability sweep of the stick/slip scenes (a stand-in for an `aster study`
# friction scene, which does not exist yet): comm/two_plates_friction_discrete.comm
# (DISCRETE, PENALISATION/PENALISATION, E_N = 1e9) over E_T x mu x steps,
# and comm/two_plates_friction.comm (CONTINUE, STANDARD/STANDARD) over
# COEF_FROT x mu x steps (mu <= 0.3: beyond, the 0.1 shift does not slide
# the whole interface -- at mu = 0.4 both formulations converge to the same
# partial slip, DX/DY = -0.3656, and the reference -mu no longer holds).
# Each run is classified from its ANALYTIQUE checks
# (the tangential force -mu N to 1e-8, stick statuses, no slip while
# sticking): ok (all OK), wrong-force (converged, the force off mu N by more
# than 1e-8), wrong-stick (the force right, a stick check NOOK: slip while
# it should stick, or a status), refused (a located refusal before solving) or fail (the run stopped: Newton did not converge even cut). Prints a CSV.
# Usage: benches/friction/stick_slip_sweep.sh [ASTER] > sweep.csv
set -eu
aster=${1:-target/ci/aster}
root=$(cd "$(dirname "$0")/../.." && pwd)
aster=$(cd "$(dirname "$aster")" && pwd)/$(basename "$aster")
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "formulation,coef,mu,steps,outcome,ratio,ratio_rel_error,newton_iterations,wall_s,reason"
one() {
  form=$1 comm=$2 coef=$3 mu=$4 steps=$5
  case $form in
    discrete) edit="s/E_T=1.0e9,/E_T=$coef,/" ;;
    continuous) edit="s/COEF_FROT=100.0,/COEF_FROT=$coef,/" ;;
  esac
  sed -e "$edit" -e "s/COULOMB=0.3,/COULOMB=$mu,/" \
      -e "s/VALE_REFE=-0.3,/VALE_REFE=-$mu,/" -e "s/VALE_CALC=-0.3,/VALE_CALC=-$mu,/" \
      -e "s/_F(JUSQU_A=2.0, NOMBRE=4)/_F(JUSQU_A=2.0, NOMBRE=$steps)/" \
      "$root/comm/$comm" > "$tmp/case.comm"
  s=$(date +%s%N)
  ASTER_NEWTON_TIMING=1 "$aster" run -q --mesh "$root/comm/two_plates.mail" --out "$tmp/o" \
    "$tmp/case.comm" > "$tmp/out" 2> "$tmp/err" || true
  e=$(date +%s%N)
  its=$(awk '/non-linear solve:/ {it += $4} END {print it + 0}' "$tmp/err")
  # The first analytic check is the ratio: "OK|NOOK ANALYTIQUE XXXX ref calc …".
  ratio=$(awk '/ANALYTIQUE/ {print $5; exit}' "$tmp/out")
  ratio_nook=$(awk '/ANALYTIQUE/ {print ($1 == "NOOK"); exit}' "$tmp/out")
  nook=$(grep -c '^NOOK  ANALYTIQUE' "$tmp/out" || true)
  reason=$(grep -m1 'error:' "$tmp/err" | sed 's/.*error: //; s/,/;/g' | cut -c1-160 || true)
  if echo "$reason" | grep -q "^not supported"; then outcome=refused
  elif [ -n "$reason" ]; then outcome=fail; elif [ "${ratio_nook:-0}" = 1 ]; then outcome=wrong-force
  elif [ "$nook" -gt 0 ]; then outcome=wrong-stick; else outcome=ok; fi
  rel=$(echo "$ratio $mu" | awk '{ if ($1 != "") printf "%.2e", ($1 + $2 < 0 ? -($1 + $2) : $1 + $2) / $2 }')
  printf '%s,%s,%s,%s,%s,%s,%s,%s,%.3f,%s\n' "$form" "$coef" "$mu" "$steps" "$outcome" "$ratio" "$rel" \
    "$its" "$(echo "$s $e" | awk '{print ($2 - $1) / 1e9}')" "$reason"
}
for mu in 0.05 0.1 0.2 0.3; do
  for steps in 1 4 16; do
    for et in 1.0e5 1.0e6 1.0e7 1.0e8 1.0e9 1.0e10 1.0e11 1.0e12; do
      one discrete two_plates_friction_discrete.comm "$et" "$mu" "$steps"
    done
    for cf in 1.0e-2 1.0 100.0 1.0e4 1.0e6 1.0e8; do
      one continuous two_plates_friction.comm "$cf" "$mu" "$steps"
    done
  done
done
