# Shared by the case benchmarks (sourced, not run): `med` (median of the
# numbers on stdin) and `bench NAME EXPORT` (N runs of one case: wall time
# end to end, then the Newton iterations and the CPU per iteration summed
# over the case's solves from ASTER_NEWTON_TIMING, and the split of the
# last run). The caller sets `aster`, `n` and `tmp`.

med() { sort -n | awk '{a[NR]=$1} END {if (NR) print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }

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
  if [ -n "${SPLIT:-}" ]; then
    grep -E '^\[newton\]   ' "$tmp/$name.err" | head -9 || true
  fi
}
