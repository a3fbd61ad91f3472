#!/bin/bash
# The runs whose numbers the docs quote, each recorded in the registry
# doc/results/CASE.json (doc/results/README.md) by scripts/registry.py:
# the command, the commit, the machine, the date, the wall time and the
# quantities read from the run's outputs. scripts/fill_docs.py then writes
# those numbers into the pages.
#
#   bash scripts/reproduce.sh --quick [CASE...]   small cases, minutes
#   bash scripts/reproduce.sh --full [CASE...]    the long cases, hours
#   bash scripts/reproduce.sh --quick --full      both
#   bash scripts/reproduce.sh --list              every case and its level
#   ... --dry-run                                 print what would run
#   ... --build DIR                               the build (default build)
#
# Runs go to results/reproduce/ (one folder or log per case, started
# afresh); a case that fails writes no registry entry and the script exits
# non-zero at the end. Run from a clean tree: the entry records whether it
# was dirty, and fill_docs.py shows such an entry's numbers as stale.
set -uo pipefail
# All of it in one function, read whole before it runs: an edit of this
# file during a run does not change the run.
main() {
cd "$(dirname "$0")/.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

quick=0 full=0 dry=0 list=0 build=build only=()
while [ $# -gt 0 ]; do
  case $1 in
    --quick) quick=1 ;;
    --full) full=1 ;;
    --dry-run) dry=1 ;;
    --list) list=1 ;;
    --build) build=$2; shift ;;
    -h|--help) sed -n '2,19p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    -*) echo "reproduce.sh: unknown option $1" >&2; exit 2 ;;
    *) only+=("$1") ;;
  esac
  shift
done
if [ $quick = 0 ] && [ $full = 0 ] && [ $list = 0 ]; then
  echo "reproduce.sh: give --quick, --full or both (--help)" >&2
  exit 2
fi
out=results/reproduce
exe=$build/yarn-impact
np=$(nproc)
py=/usr/bin/python3
figs=doc/figures
CODE="source include prm"

names=() levels=() commands=() depends=() extracts=()
# add NAME LEVEL "DEPENDS" "EXTRACT..." COMMAND: a case. COMMAND is run by
# bash from the repository root, its output in $out/NAME.log. EXTRACT is
# KIND:ARG... (scripts/registry.py), several separated by spaces.
add() {
  names+=("$1"); levels+=("$2"); depends+=("$3"); extracts+=("$4")
  commands+=("$5")
}
# A parameter file: include BASE (relative to $out, where it is written)
# with the output in $out/NAME and the extra lines.
prm() { # NAME BASE [LINES]
  local dir=$out/$1
  echo "printf 'include ../../$2\nsubsection Output\n  set Directory = $dir\n  set Overwrite = true\n  set Snapshot interval = 0\nend\n${3:-}' > $out/$1.prm"
}
one_run() { # NAME BASE [LINES]: the FE or DEM run of a prm on one rank
  echo "$(prm "$@") && $exe $out/$1.prm"
}
mpi_run() { # NAME BASE [LINES]: on every core
  echo "$(prm "$@") && mpirun -np $np $exe $out/$1.prm"
}

# ---- quick: seconds to a minute each ----------------------------------
# doc/identification.md section 8: the failure law from the stored DEM and
# FE histories.
add fibre_failure_identification quick \
  "scripts/identify_fibre_failure.py $figs/dem_tension_to_failure_summary.txt $figs/dem_tension_to_failure.csv $figs/history_dem_km2_120ms.csv $figs/history_fe_no_failure_120ms.csv" \
  "fibre_failure:$out/fibre_failure_identification.log" \
  "$py scripts/identify_fibre_failure.py $figs/dem_tension_to_failure_summary.txt $figs/dem_tension_to_failure.csv $figs/history_dem_km2_120ms.csv $figs/history_fe_no_failure_120ms.csv"
# doc/identification.md section 3: test identification/synthetic_recovery.
add synthetic_recovery quick "$CODE scripts/identify_charmetant.py tests/identification" \
  "recovery:$out/synthetic_recovery.log" \
  "bash tests/identification/synthetic_recovery.sh $build/tests/identification/charmetant_curves \$PWD/scripts"
# doc/identification.md section 2.1: test dem/elementary_segment_length.
add segment_length quick "$CODE tests/dem/elementary_segment_length.sh tests/dem/elementary_distortion.prm" \
  "segment_length:$out/segment_length.log" \
  "bash tests/dem/elementary_segment_length.sh \$(readlink -f $exe) \$PWD/tests/dem"
# doc/identification.md section 4.1: the DEM tension test to failure.
add dem_tension quick "$CODE" "elementary:$out/dem_tension.log" \
  "$(one_run dem_tension prm/elementary/tension.prm)"
# doc/validation.md section 1: the model consistency of a Model = both run
# (printed at any end time).
add model_consistency quick "$CODE" "consistency:$out/model_consistency.log" \
  "$(one_run model_consistency prm/km2_120ms_compare.prm 'subsection Time\n  set End time = 0.01e-6\nend\n')"
# doc/validation.md sections 1 and 2: runs C, D, B and E (FE, half yarn).
for run in fe_hyper fe_linear fe_hyperdens fe_hyper_section; do
  add $run quick "$CODE" "history:$out/$run" \
    "$(one_run $run prm/study/$run.prm)"
done
# doc/validation.md section 6: the failure study's cases on the paper's
# mesh, against the stored DEM histories (scripts/failure_study.sh).
for c in sudden_mu0 sudden progressive_mu0 progressive progressive_nospread \
         progressive_spread05 progressive_fibres tail sudden_200 progressive_200 tail_200 \
         sudden_300 progressive_300 tail_300; do
  v=120; case $c in *_200) v=200 ;; *_300) v=300 ;; esac
  add failure_$c quick "$CODE scripts/failure_study.sh $figs/history_dem_km2_${v}ms.csv" \
    "failure:$out/failure_study/$c:$figs/history_dem_km2_${v}ms.csv" \
    "bash scripts/failure_study.sh $build $out/failure_study $c"
done
# doc/identification.md sections 5.3 and 5.4: the FE case with Table 1
# and with k_td = 65, 20 and 6.5 MPa against the stored DEM history, and
# the compaction behind the kink (the FE runs of
# scripts/run_identification.sh that do not need the fit).
ktd_runs=""
sweep=""
for ktd in 65e6 20e6 6.5e6; do
  ktd_runs="$ktd_runs && $(prm fe_ktd_$ktd prm/km2_120ms_fe.prm "subsection FE\n  subsection Charmetant\n    set k_td = $ktd\n  end\nend\n") && ($exe $out/fe_ktd_$ktd.prm > $out/fe_ktd_$ktd.log 2>&1 || tail -1 $out/fe_ktd_$ktd.log)"
  sweep="$sweep k_td_$ktd=$out/fe_ktd_$ktd/history_fe.csv"
done
add identification_ktd quick \
  "$CODE scripts/compare_identified.py scripts/fe_kink_compaction.py $figs/history_dem_km2_120ms.csv" \
  "compare:$out/identification_ktd.log kink:$out/identification_ktd.log table1=history:$out/fe_table1 k_td_65e6=history:$out/fe_ktd_65e6 k_td_20e6=history:$out/fe_ktd_20e6 k_td_6_5e6=history:$out/fe_ktd_6.5e6" \
  "$(prm fe_table1 prm/km2_120ms_fe.prm 'subsection Output\n  set Snapshot interval = 1e-6\nend\n') && $exe $out/fe_table1.prm > $out/fe_table1.log$ktd_runs && $py scripts/compare_identified.py $figs/history_dem_km2_120ms.csv $out/identification_table1.png 'Table 1=$out/fe_table1/history_fe.csv' && $py scripts/compare_identified.py $figs/history_dem_km2_120ms.csv $out/identification_ktd.png$sweep && echo '-- fe_table1' && $py scripts/fe_kink_compaction.py $out/fe_table1/fe_0010.0.vtu $out/fe_table1/fe_0000.0.vtu | tail -1"

# doc/fe-model.md section 7, README: the paper's FE case alone
# (prm/km2_120ms_fe.prm, full yarn, one rank), with failure off and with
# half the safety factor.
add fe_paper_case quick "$CODE" \
  "run:$out/fe_paper_case:$out/fe_paper_case_run.log nofailure=run:$out/fe_paper_case_nofailure sf04=run:$out/fe_paper_case_sf04" \
  "$(prm fe_paper_case prm/km2_120ms_fe.prm) && $exe $out/fe_paper_case.prm > $out/fe_paper_case_run.log && $(prm fe_paper_case_nofailure prm/km2_120ms_fe.prm 'subsection Yarn\n  set Failure = false\nend\n') && $exe $out/fe_paper_case_nofailure.prm && $(prm fe_paper_case_sf04 prm/km2_120ms_fe.prm 'subsection Time\n  set Safety factor = 0.4\nend\n') && $exe $out/fe_paper_case_sf04.prm"
# doc/fe-model.md section 2: the progressive law without onset spread
# (prm/km2_120ms_fe_progressive.prm, one rank) with the cell kernel the
# CPU runs and with the portable one.
nospread='subsection Yarn\n  set Damage onset spread = 0\nend\n'
add fe_kernels quick "$CODE" \
  "native=run:$out/fe_kernels_native:$out/fe_kernels_native.log portable=run:$out/fe_kernels_portable:$out/fe_kernels_portable.log" \
  "$(prm fe_kernels_native prm/km2_120ms_fe_progressive.prm "$nospread") && $exe $out/fe_kernels_native.prm > $out/fe_kernels_native.log && $(prm fe_kernels_portable prm/km2_120ms_fe_progressive.prm "$nospread") && YARN_IMPACT_PORTABLE_KERNEL=1 $exe $out/fe_kernels_portable.prm > $out/fe_kernels_portable.log"
# doc/fe-model.md section 6: the FE tests' runs (tests/fe/*.prm, one
# rank), the early deceleration of smith_free on finer meshes and
# smith_prescribed with the paper's 2.2 mm nose.
fever=""
fex=""
for t in bar_wave_speed energy_conservation smith_free smith_prescribed; do
  fever="$fever && $(one_run fe_verification_$t tests/fe/$t.prm)"
  fex="$fex $t=run:$out/fe_verification_$t"
done
for v in "c100:subsection FE\n  set Cells along the axis = 100\nend\n" \
         "c400r1:subsection FE\n  set Section refinements = 1\nend\n" \
         "c800r1:subsection FE\n  set Cells along the axis = 800\n  set Section refinements = 1\nend\n"; do
  # the window is measured, not checked: the coarse mesh is outside the
  # test's tolerance
  v="$v""subsection Verification\n  set Checks =\nend\n"
  fever="$fever && $(one_run fe_verification_free_${v%%:*} tests/fe/smith_free.prm "${v#*:}")"
  fex="$fex free_${v%%:*}=run:$out/fe_verification_free_${v%%:*}"
done
fever="$fever && $(one_run fe_verification_prescribed_nose22 tests/fe/smith_prescribed.prm 'subsection Projectile\n  set Diameter = 2.2e-3\nend\nsubsection Verification\n  set Checks =\nend\n')"
fex="$fex prescribed_nose22=run:$out/fe_verification_prescribed_nose22"
add fe_verification quick "$CODE tests/fe" "${fex# }" "true$fever"
# doc/dem.md section 9: the DEM tests' runs (tests/dem/*.prm, one rank).
demver=""
demx=""
for t in single_fibre_wave_speed smith_plateau_strain smith_deceleration \
         energy_balance cut_recoil; do
  demver="$demver && $(one_run dem_verification_$t tests/dem/$t.prm)"
  demx="$demx $t=run:$out/dem_verification_$t"
done
add dem_verification quick "$CODE tests/dem" "${demx# }" "true$demver"

# ---- full: the long cases (minutes to hours each on 2 cores) -----------
# The README's default case: the paper's study in one run (FE and DEM).
add default full "$CODE" \
  "fe=history:results/default/history_fe.csv dem=history:results/default/history_dem.csv consistency:$out/default.log" \
  "bash scripts/run_default.sh"
# The DEM references of doc/validation.md section 6 and doc/identification.md
# section 5 (stored as doc/figures/history_dem_km2_*.csv).
add dem_km2_120ms full "$CODE" "history:$out/dem_km2_120ms" \
  "$(mpi_run dem_km2_120ms prm/km2_120ms_dem.prm)"
for v in 200 300; do
  add dem_km2_${v}ms full "$CODE" "history:$out/dem_km2_${v}ms" \
    "$(mpi_run dem_km2_${v}ms prm/study/dem_${v}ms.prm)"
done
# doc/validation.md section 4: FE resolution, DEM contact stiffness and
# friction (scripts/run_study.sh runs the same).
add fe_resolution full "$CODE scripts/fe_resolution_study.sh" \
  "summary:$out/fe_resolution/values.txt" \
  "bash scripts/fe_resolution_study.sh $build $out/fe_resolution"
for run in dem_kn_low dem_no_friction; do
  add $run full "$CODE" "history:$out/$run" "$(mpi_run $run prm/study/$run.prm)"
done
# doc/validation.md section 6: the failure study's refined meshes.
for c in progressive_axial2x progressive_section2x progressive_section4x \
         sudden_section2x sudden_section4x tail_axial2x tail_section2x; do
  add failure_$c full "$CODE scripts/failure_study.sh $figs/history_dem_km2_120ms.csv" \
    "failure:$out/failure_study/$c:$figs/history_dem_km2_120ms.csv" \
    "bash scripts/failure_study.sh $build $out/failure_study $c"
done
# doc/identification.md: the elementary tests, the fit, the FE case with
# the identified constants.
add identification full "$CODE scripts/run_identification.sh scripts/identify_charmetant.py scripts/compare_identified.py" \
  "fit:results/identification/fit.txt tension=elementary:results/identification/tension.log compare:results/identification/impact.txt compare:results/identification/impact_ktd.txt kink:results/identification/kink.txt" \
  "bash scripts/run_identification.sh"
# doc/ballistics.md: the velocity sweep.
add ballistic_sweep full "$CODE scripts/ballistic_sweep.py" \
  "summary:$out/ballistic_sweep.log sweep:$out/ballistic_sweep" \
  "$py scripts/ballistic_sweep.py --build $build --out $out/ballistic_sweep --np $np --models charmetant,linear,dem,hybrid --dem-velocities 450,600,1000 --hybrid-velocities 450,600,1000"
# doc/performance.md, doc/performance-dem.md: the benchmarks.
# The FE force loop on 1 rank and on every core, and the paper's FE case end
# to end (doc/performance.md section 1); the DEM step on the whole yarn from
# the impact on every core (doc/performance.md section 2).
add bench_fe_throughput full "$CODE bench" "summary:$out/bench_fe_throughput.log" \
  "$build/bench_fe_throughput 300 prm/km2_120ms_fe.prm && mpirun -np $np $build/bench_fe_throughput 300 -"
add bench_dem_throughput full "$CODE bench" "summary:$out/bench_dem_throughput.log" \
  "mpirun -np $np $build/bench_dem_throughput 0.0254 3000 4e-6 0 32"
add bench_hybrid_cost full "$CODE bench" "summary:$out/bench_hybrid_cost.log" \
  "bash bench/hybrid_cost.sh $np"

# ---- run ----------------------------------------------------------------
if [ $list = 1 ]; then
  for i in "${!names[@]}"; do echo "${levels[$i]} ${names[$i]}"; done
  exit 0
fi
for want in "${only[@]}"; do
  printf '%s\n' "${names[@]}" | grep -qx -- "$want" \
    || { echo "reproduce.sh: no case $want (--list)" >&2; exit 2; }
done
[ $dry = 1 ] || mkdir -p "$out"
failed=() ran=0 start_all=$(date +%s)
for i in "${!names[@]}"; do
  name=${names[$i]} level=${levels[$i]}
  { [ $level = quick ] && [ $quick = 1 ]; } || { [ $level = full ] && [ $full = 1 ]; } || continue
  if [ ${#only[@]} -gt 0 ] && ! printf '%s\n' "${only[@]}" | grep -qx -- "$name"; then
    continue
  fi
  if [ $dry = 1 ]; then
    echo "[$level] $name: ${commands[$i]}"
    echo "    -> doc/results/$name.json (${extracts[$i]})"
    continue
  fi
  rm -rf "${out:?}/$name" "$out/$name.prm"
  t0=$(date +%s.%N)
  bash -c "${commands[$i]}" > "$out/$name.log" 2>&1
  rc=$?
  wall=$(echo "$(date +%s.%N) - $t0" | bc)
  if [ $rc -ne 0 ]; then
    echo "$name: FAILED (exit $rc; $out/$name.log)"
    failed+=("$name")
    continue
  fi
  # shellcheck disable=SC2086
  if ! $py scripts/registry.py record --case "$name" --level "$level" \
      --command "${commands[$i]}" --wall "$wall" --depends ${depends[$i]} \
      --extract ${extracts[$i]}; then
    failed+=("$name")
  fi
  ran=$((ran + 1))
done
[ $dry = 1 ] && exit 0
echo "reproduce.sh: $ran case(s) in $(( $(date +%s) - start_all )) s"
if [ ${#failed[@]} -gt 0 ]; then
  echo "reproduce.sh: failed: ${failed[*]}" >&2
  exit 1
fi
echo "now: /usr/bin/python3 scripts/fill_docs.py   (writes the numbers into the docs)"
}
main "$@"
exit $?
