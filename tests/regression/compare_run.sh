#!/usr/bin/env bash
# Usage: compare_run.sh [-r TOLERANCE] [-n RANKS -m MPIEXEC] [-b FILE:COLUMN:LOW:HIGH]...
#                       [-a FILE:COLUMN:LOW:HIGH]... [-e FILE:PREFIX:TOLERANCE]...
#                       [-c CHECKPOINT] RBC_IFEM PRM EXPECTED_DIR NUMDIFF
#
# Runs an experiment (on RANKS MPI ranks with -n) in an empty directory and
# compares each file stored in EXPECTED_DIR (and its folders: a run's
# subfolder of that name) with the run's file of that name
# using numdiff (relative TOLERANCE, default 1e-8; absolute 1e-10 for values
# near 0). run.log stands for the program's log, less the lines naming the
# number of ranks and the memory used. For a CSV file only the columns
# named in the stored file's header are compared, so a stored file can leave
# out columns that legitimately differ (iteration counts across rank counts).
# Each -b checks that COLUMN of the last row of the run's CSV FILE (in the
# output directory) lies in [LOW, HIGH]: a band around a published value.
# Each -a checks that every row's COLUMN lies in [LOW, HIGH] (a gap that
# stays positive over the run), and prints the smallest and largest value.
# Each -e checks that on every row of FILE the columns whose names start
# with PREFIX agree within the relative TOLERANCE (cells that symmetry makes
# equal), and prints the largest relative spread.
# -c copies CHECKPOINT to the output directory's checkpoint.bin before the
# run, for a PRM that resumes from a stored state (Immersed cells/Resume).
set -u
source "$(dirname "$0")/../script_setup.sh"
tolerance=1e-8
ranks=
mpiexec=
bands=()
all_rows=()
equal=()
checkpoint=
while getopts "r:n:m:b:a:e:c:" option; do
  case $option in
    r) tolerance=$OPTARG ;;
    n) ranks=$OPTARG ;;
    m) mpiexec=$OPTARG ;;
    b) bands+=("$OPTARG") ;;
    a) all_rows+=("$OPTARG") ;;
    e) equal+=("$OPTARG") ;;
    c) checkpoint=$(realpath "$OPTARG") ;;
    *) exit 2 ;;
  esac
done
shift $((OPTIND - 1))
exe=$1
prm=$2
expected=$3
numdiff=$4

set_launcher "$ranks" "$mpiexec"
enter_scratch_directory
directory=$(sed -n 's/^set Output directory *= *//p' "$prm")
if [ -n "$checkpoint" ]; then
  mkdir -p "$directory"
  cp "$checkpoint" "$directory/checkpoint.bin"
fi
"${launcher[@]}" "$exe" "$prm" >log.txt 2>&1
status=$?
cat log.txt
[ $status -eq 0 ] || { echo "FAILED: exit status $status"; exit 1; }
grep -v -e "rank(s)" -e "peak memory" log.txt >run.log

# The columns of CSV file $2 named in the header of CSV file $1, in $1's order.
select_columns() {
  awk -F, 'NR == FNR { if (FNR == 1) wanted = $0; next }
           FNR == 1 { n = split(wanted, names, ",");
                      for (i = 1; i <= NF; ++i) column[$i] = i;
                      for (j = 1; j <= n; ++j) if (!(names[j] in column)) { print "missing column " names[j]; exit 1 } }
           { line = $(column[names[1]]);
             for (j = 2; j <= n; ++j) line = line "," $(column[names[j]]);
             print line }' "$1" "$2"
}

failed=0
while IFS= read -r name; do
  reference="$expected/$name"
  result="$directory/$name"
  [ "$name" = run.log ] && result=run.log
  if [[ $name == *.csv ]]; then
    selected="selected_${name//\//_}"
    select_columns "$reference" "$result" >"$selected"
    result=$selected
  fi
  if ! "$numdiff" -q -s ' \t\n,' -r "$tolerance" -a 1e-10 "$reference" "$result"; then
    echo "FAILED: $name differs from the stored $reference (relative tolerance $tolerance):"
    "$numdiff" -s ' \t\n,' -r "$tolerance" -a 1e-10 "$reference" "$result" | head -20
    failed=1
  fi
done < <(cd "$expected" && find . -type f | sed 's|^\./||' | sort)
[ $failed -eq 0 ] && echo "ok: matches $expected (relative tolerance $tolerance)"

for band in "${bands[@]}"; do
  IFS=: read -r file name low high <<<"$band"
  value=$(awk -F, -v name="$name" 'FNR == 1 { for (i = 1; i <= NF; ++i) if ($i == name) c = i; next }
                                    { v = $c } END { print v }' "$directory/$file")
  if awk -v v="$value" -v lo="$low" -v hi="$high" 'BEGIN { exit !(v != "" && v >= lo && v <= hi) }'; then
    echo "ok: $file $name = $value lies in [$low, $high]"
  else
    echo "FAILED: $file $name = $value, outside [$low, $high]"
    failed=1
  fi
done
for band in "${all_rows[@]}"; do
  IFS=: read -r file name low high <<<"$band"
  range=$(awk -F, -v name="$name" 'FNR == 1 { for (i = 1; i <= NF; ++i) if ($i == name) c = i; next }
                                    $c != "" { if (n++ == 0 || $c < lo) lo = $c; if (n == 1 || $c > hi) hi = $c }
                                    END { if (n) print lo, hi }' "$directory/$file")
  read -r smallest largest <<<"$range"
  if awk -v lo="$smallest" -v hi="$largest" -v a="$low" -v b="$high" \
       'BEGIN { exit !(lo != "" && lo >= a && hi <= b) }'; then
    echo "ok: $file $name over the run lies in [$smallest, $largest], within [$low, $high]"
  else
    echo "FAILED: $file $name over the run lies in [$smallest, $largest], not within [$low, $high]"
    failed=1
  fi
done
for check in "${equal[@]}"; do
  IFS=: read -r file prefix limit <<<"$check"
  spread=$(awk -F, -v prefix="$prefix" 'FNR == 1 { for (i = 1; i <= NF; ++i) if (index($i, prefix) == 1) c[++n] = i; next }
                                         { lo = hi = $(c[1]); for (j = 2; j <= n; ++j) { if ($(c[j]) < lo) lo = $(c[j]); if ($(c[j]) > hi) hi = $(c[j]) }
                                           s = (hi - lo) / (hi > -lo ? hi : -lo); if (s > worst) worst = s }
                                         END { if (n > 1) printf "%.3g", worst }' "$directory/$file")
  if awk -v s="$spread" -v t="$limit" 'BEGIN { exit !(s != "" && s <= t) }'; then
    echo "ok: $file columns $prefix* agree within $spread (relative), at most $limit"
  else
    echo "FAILED: $file columns $prefix* spread by ${spread:-nothing} (relative), more than $limit"
    failed=1
  fi
done
exit $failed
