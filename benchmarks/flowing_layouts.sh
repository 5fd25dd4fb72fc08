#!/usr/bin/env bash
# Usage: benchmarks/flowing_layouts.sh [RBC_IFEM] [RANKS] [KEEP]
#
# What the flowing layouts study costs (issue targets: the quick study
# <= 10 minutes on 2 ranks; the full study <= 60 minutes once the step is
# cheaper). Two parts, in one script run:
#
#  1. prm/flowing_layouts_quick.prm as it is: its wall time, and where the
#     time of its runs goes (the sections of every run's timing.csv summed).
#     With KEEP, its output directory is copied there.
#  2. the full study, prm/flowing_layouts.prm, estimated: one run of N = 1,
#     4 and 7 cells (uniform, uniform, clustered) of its mesh for 40 steps
#     and one DM solve gives the seconds per step and per DM solve; for the
#     study's 48 runs (1600 steps, 11 DM solves each; 7 layouts per N, 6
#     for N = 1, whose uniform and clustered cells coincide) they are
#     interpolated linearly in N.
# The quick study's time and the full study's probes and estimate are added
# to doc/results/benchmarks/flowing_layouts_quick.csv,
# flowing_layouts_probes.csv and flowing_layouts_estimate.csv
# (benchmarks/common.sh).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
source "$(dirname "$0")/common.sh"
keep=${3:+$(realpath -m "$3")}
benchmark_setup "$@"

start=$(date +%s.%N)
mpirun -np "$ranks" "$exe" "$here/prm/flowing_layouts_quick.prm" >quick.log 2>&1 ||
  { tail -20 quick.log; exit 1; }
quick=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { print b - a }')
n_runs=$(grep -c "^run .* of .*, in " quick.log || true)
results_table flowing_layouts_quick ranks "flowing runs" "wall [s]" "wall [min]" section "section [s]" "share of the sections"
awk -F, 'FNR > 1 { gsub(/"/, "", $1); t[$1] += $3; total += $3 }
         END { for (s in t) if (t[s] / total > 0.02) printf "%.1f\t%.1f%%\t%s\n", t[s], 100 * t[s] / total, s }' \
  output/flowing_layouts_quick/*/timing.csv | sort -rn | while IFS=$'\t' read -r seconds share section; do
  results_row "$ranks" "$n_runs" "$(printf '%.0f' "$quick")" "$(awk -v s="$quick" 'BEGIN { printf "%.1f", s / 60 }')" \
    "$section" "$seconds" "$share"
done
[ -n "$keep" ] && { rm -rf "$keep"; mkdir -p "$(dirname "$keep")"; cp -r output/flowing_layouts_quick "$keep"; }

# One run of the full study's mesh: N cells of KIND, 40 steps, DM at the end.
probe() {
  local kind=$1 n=$2
  { sed -e 's/^set Experiment .*/set Experiment = flow/' \
        -e "s|^set Output directory .*|set Output directory = probe_$n|" "$here/prm/flowing_layouts.prm"
    cat <<PRM
subsection Layout
  set Kind            = $kind
  set Number of cells = $n
end
subsection Time
  set Number of steps = 40
  set Output interval = 40
end
subsection Immersed cells
  set Enabled             = true
  set Diffusion interval  = 40
  set Progress interval   = 40
  set Checkpoint interval = 0
end
PRM
  } >probe_$n.prm
  mpirun -np "$ranks" "$exe" probe_$n.prm >probe_$n.log 2>&1 || { tail -20 probe_$n.log; exit 1; }
  local step dm
  step=$(sed -n 's/.* steps in .* s, \(.*\) s per step/\1/p' probe_$n.log)
  dm=$(awk -F, 'FNR > 1 { gsub(/"/, "", $1); if ($1 ~ /^diffusion/) t += $3 } END { print t / 2 }' probe_$n/timing.csv)
  echo "$n $step $dm"
}
{ probe uniform 1; probe uniform 4; probe clustered 7; } >probes.txt
echo
echo "full study (prm/flowing_layouts.prm), measured on its mesh over 40 steps:"
results_table flowing_layouts_probes ranks N "s per step" "s per DM solve"
while read -r n step dm; do
  results_row "$ranks" "$n" "$(printf '%.3f' "$step")" "$(printf '%.2f' "$dm")"
done <probes.txt
read -r total hours < <(awk '{ n[NR] = $1; s[NR] = $2; d[NR] = $3; m = NR }
     function at(x, v,   i) { for (i = 1; i < m; ++i) if (x <= n[i + 1]) return v[i] + (v[i + 1] - v[i]) * (x - n[i]) / (n[i + 1] - n[i]); return v[m] }
     END { for (N = 1; N <= 7; ++N) { runs = N == 1 ? 6 : 7; total += runs * (1600 * at(N, s) + 11 * at(N, d)) }
           printf "%.0f %.1f\n", total, total / 3600 }' probes.txt)
echo
results_table flowing_layouts_estimate ranks runs "estimated full study [s]" "estimated full study [h]"
results_row "$ranks" 48 "$total" "$hours"
