#!/usr/bin/env bash
# Usage: flowing_trends.sh [-n RANKS -m MPIEXEC] RBC_IFEM PRM
#
# Runs a flowing layouts study (uniform and clustered, several numbers of
# cells) and checks the trends of the paper's Figs. 7 and 8 on the cells
# after flow, in flowing_layouts_summary.csv: for each kind the steady DM
# total grows with N and the DM per cell falls; clustered cells take up
# less than uniform ones at every N > 1; and no two membranes ever cross
# (min_gap > 0 in flowing_layouts.csv and in every cells.csv of the runs).
set -u
source "$(dirname "$0")/../script_setup.sh"
read_rank_options "$@"
shift $((OPTIND - 1))
exe=$1
prm=$2
set_launcher "$ranks" "$mpiexec"
enter_scratch_directory

"${launcher[@]}" "$exe" "$prm" >log.txt 2>&1
status=$?
grep -e "^run " log.txt
[ $status -eq 0 ] || { cat log.txt; echo "FAILED: exit status $status"; exit 1; }
directory=$(sed -n 's/^set Output directory *= *//p' "$prm")
cat "$directory/flowing_layouts_summary.csv"

awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
         { kind = $(c["layout"]); n = $(c["n_cells"]) + 0
           total[kind, n] = $(c["steady_dm_total"]); per_cell[kind, n] = $(c["steady_dm_per_cell"])
           if (!(kind in seen)) { seen[kind] = 1; kinds[++n_kinds] = kind }
           if (!(n in counted)) { counted[n] = 1; ns[++n_ns] = n } }
         END {
           failed = 0
           for (k = 1; k <= n_kinds; ++k)
             for (j = 2; j <= n_ns; ++j) {
               kind = kinds[k]; a = ns[j - 1]; b = ns[j]
               if (!(total[kind, b] > total[kind, a])) { print "FAILED: " kind ": DM total does not grow from N = " a " to " b; failed = 1 }
               else print "ok: " kind ": DM total grows from N = " a " to " b ": " total[kind, a] " -> " total[kind, b]
               if (!(per_cell[kind, b] < per_cell[kind, a])) { print "FAILED: " kind ": DM per cell does not fall from N = " a " to " b; failed = 1 }
               else print "ok: " kind ": DM per cell falls from N = " a " to " b ": " per_cell[kind, a] " -> " per_cell[kind, b]
             }
           for (j = 1; j <= n_ns; ++j) {
             n = ns[j]
             if (n < 2) continue
             if (!(total["clustered", n] < total["uniform", n])) { print "FAILED: clustered does not take up less than uniform at N = " n; failed = 1 }
             else print "ok: N = " n ": clustered " total["clustered", n] " < uniform " total["uniform", n]
           }
           exit failed }' "$directory/flowing_layouts_summary.csv"
failed=$?

# The smallest min_gap of CSV file $1, or "none".
smallest_gap() {
  awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "min_gap") c = i; next }
           $c != "" { if (n++ == 0 || $c < lo) lo = $c } END { print n ? lo : "none" }' "$1"
}
for table in "$directory"/flowing_layouts.csv "$directory"/*/cells.csv; do
  gap=$(smallest_gap "$table")
  [ "$gap" = none ] && continue
  if awk -v g="$gap" 'BEGIN { exit !(g > 0) }'; then
    echo "ok: ${table#"$directory"/}: smallest gap between cells $gap µm"
  else
    echo "FAILED: ${table#"$directory"/}: membranes crossed (smallest gap $gap µm)"
    failed=1
  fi
done
exit $failed
