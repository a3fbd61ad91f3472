#!/bin/bash
# The multiscale bridge in one command (doc/identification.md): the DEM
# elementary tests (tension, compaction free and confined, distortion at
# three confining pressures), the fit of the Charmetant constants, the FE
# case of the paper with the identified constants, and its comparison with
# the DEM. Results in results/identification/. About 7 minutes on 2 cores.
#
#   bash scripts/run_identification.sh [DEM comparison.csv]
#
# The DEM side of the comparison is a DEM history or the comparison.csv of a
# Model = both run (results/default/comparison.csv after
# scripts/run_default.sh); without one, the recorded DEM history
# doc/figures/history_dem_km2_120ms.csv (prm/km2_120ms_dem.prm, see
# doc/identification.md section 6) is used.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
out=results/identification
mkdir -p "$out"
# The tests run on one rank each in two lanes, which keeps both cores busy
# (a 2-rank split of one test gives the same curves but is only 1.4 times
# faster); the distortion test runs one process per confining pressure.
run_case() {
  local case=$1 prm=$2 dir=$out/$1
  rm -rf "$dir"
  sed "s#set Directory = .*#set Directory = $dir#" "$prm" > "$out/$case.prm"
  local start=$(date +%s)
  build/yarn-impact "$out/$case.prm" > "$out/$case.log" 2>&1 || true
  echo "   ($case: $(( $(date +%s) - start )) s)" >> "$out/$case.log"
}
for pc in 2e6 10e6 50e6; do
  sed "s/set Confining pressures .*=.*/set Confining pressures    = $pc/" \
    prm/elementary/distortion.prm > "$out/distortion_$pc.in.prm"
done
echo "== DEM elementary tests (logs in $out/*.log)"
{ run_case distortion_50e6 "$out/distortion_50e6.in.prm"
  run_case distortion_10e6 "$out/distortion_10e6.in.prm"; } &
for case in tension compaction compaction_confined; do
  run_case $case prm/elementary/$case.prm
done
run_case distortion_2e6 "$out/distortion_2e6.in.prm"
wait
for case in tension compaction compaction_confined distortion_2e6 \
            distortion_10e6 distortion_50e6; do
  grep -v '^\[' "$out/$case.log"
done
csvs="$out/tension/elementary_tension.csv $out/compaction/elementary_compaction.csv $out/compaction_confined/elementary_compaction.csv"
for pc in 2e6 10e6 50e6; do
  csvs="$csvs $out/distortion_$pc/elementary_distortion.csv"
done
echo "== Fit"
/usr/bin/python3 scripts/identify_charmetant.py --each \
  --prm "$out/km2_120ms_fe_identified.prm" \
  --directory "$out/fe_identified" --plot "$out/fit.png" $csvs \
  | tee "$out/fit.txt"
echo "== FE impact with the identified constants"
rm -rf "$out/fe_identified" "$out/fe_table1"
build/yarn-impact "$out/km2_120ms_fe_identified.prm" | sed -n "/^Summary/,\$p" || echo "   (the FE run stopped early; its history up to the stop is compared)"
sed "s#set Directory .*=.*#set Directory = $out/fe_table1#" \
  prm/km2_120ms_fe.prm > "$out/km2_120ms_fe_table1.prm"
build/yarn-impact "$out/km2_120ms_fe_table1.prm" > /dev/null
dem=${1:-results/default/comparison.csv}
[ -f "$dem" ] || dem=doc/figures/history_dem_km2_120ms.csv
echo "== Against the DEM ($dem)"
/usr/bin/python3 scripts/compare_identified.py "$dem" "$out/impact.png" \
  "Table 1=$out/fe_table1/history_fe.csv" \
  "identified=$out/fe_identified/history_fe.csv" | tee "$out/impact.txt"
echo "== How soft must the section be? Table 1 with k_td = 65, 20 and 6.5 MPa"
sweep=""
for ktd in 65e6 20e6 6.5e6; do
  dir=$out/fe_table1_ktd_$ktd
  rm -rf "$dir"
  { sed "s#set Directory .*=.*#set Directory = $dir#" prm/km2_120ms_fe.prm
    printf "subsection FE\n  subsection Charmetant\n    set k_td = %s\n  end\nend\n" $ktd
  } > "$out/km2_120ms_fe_table1_ktd_$ktd.prm"
  build/yarn-impact "$out/km2_120ms_fe_table1_ktd_$ktd.prm" > "$dir.log" 2>&1 \
    || echo "   (k_td = $ktd: $(tail -1 "$dir.log"))"
  sweep="$sweep k_td_${ktd}=$dir/history_fe.csv"
done
/usr/bin/python3 scripts/compare_identified.py "$dem" "$out/impact_ktd.png" \
  $sweep | tee "$out/impact_ktd.txt"
echo "== The compaction the law sees behind the transverse kink (10 us)"
for run in fe_table1 fe_identified; do
  echo "-- $run"
  /usr/bin/python3 scripts/fe_kink_compaction.py "$out/$run/fe_0010.0.vtu" \
    "$out/$run/fe_0000.0.vtu" | tail -1
done | tee "$out/kink.txt"
