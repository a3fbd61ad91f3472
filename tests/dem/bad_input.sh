#!/bin/bash
# Bad DEM input must stop yarn-impact with a one-line error that names the
# parameter, and exit code 1, before anything is written: the run leaves no
# output directory (no parameters.prm; with Model = both, no FE output), and
# `--check` refuses the same input with the same line.
# Usage: bad_input.sh path/to/yarn-impact
exe="$1"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
failures=0

# run_case NAME TEXT ARGS...: exit 1, one line naming TEXT, no $dir/run.
run_case()
{
  local name="$1" text="$2"
  shift 2
  rm -rf "$dir/run"
  local out
  out=$("$exe" "$@" 2>&1)
  local rc=$?
  if [ $rc -ne 1 ] || ! grep -qF -- "$text" <<< "$out" ||
     [ "$(wc -l <<< "$out")" -ne 1 ] ||
     [ "$(grep -c 'error' <<< "$out")" -ne 1 ]; then
    echo "FAILED $name (exit $rc): $out"
    failures=$((failures + 1))
  elif [ -e "$dir/run" ]; then
    echo "FAILED $name: the output directory was written: $(ls "$dir/run")"
    failures=$((failures + 1))
  else
    echo "PASSED $name: $out"
  fi
}

# expect NAME EXPECTED-TEXT PRM-LINES...
expect()
{
  local name="$1" text="$2"
  shift 2
  {
    echo "set Model = dem"
    printf '%s\n' "$@"
    echo "subsection Output"
    echo "  set Directory = $dir/run"
    echo "  set Verbosity = test"
    echo "end"
  } > "$dir/$name.prm"
  run_case "$name" "$text" "$dir/$name.prm"
  run_case "--check $name" "$text" --check "$dir/$name.prm"
}

printf '0 0\n1e-5 oops\n' > "$dir/malformed.txt"
printf '0 0\n5e-6 0\n' > "$dir/overlap.txt"
printf '0 0\n' > "$dir/short.txt"
printf '0 6e-6\n0 -1.2e-5\n' > "$dir/asymmetric.txt"
printf '0 0\n1 0\n' > "$dir/far_outside.txt"

expect malformed_file "line 2: expected two numbers" \
  "subsection Yarn" "set Number of fibres = 2" "end" \
  "subsection DEM" "set Fibre layout = file" \
  "set Fibre file = $dir/malformed.txt" "end"
expect overlapping_fibres "overlap" \
  "subsection Yarn" "set Number of fibres = 2" "end" \
  "subsection DEM" "set Fibre layout = file" \
  "set Fibre file = $dir/overlap.txt" "end"
expect wrong_count "holds 1 fibre centres" \
  "subsection Yarn" "set Number of fibres = 2" "end" \
  "subsection DEM" "set Fibre layout = file" \
  "set Fibre file = $dir/short.txt" "end"
expect far_outside "the fibre on line 2 lies" \
  "subsection Yarn" "set Number of fibres = 2" "end" \
  "subsection DEM" "set Fibre layout = file" \
  "set Fibre file = $dir/far_outside.txt" "end"
expect missing_file "cannot be opened" \
  "subsection DEM" "set Fibre layout = file" \
  "set Fibre file = $dir/none.txt" "end"
expect no_file_name "DEM/Fibre file" \
  "subsection DEM" "set Fibre layout = file" "end"
expect too_many_fibres "Yarn/Number of fibres" \
  "subsection Yarn" "set Number of fibres = 1000" "end"
expect spacing_too_large "DEM/Sphere spacing" \
  "subsection DEM" "set Sphere spacing = 13e-6" "end"
expect negative_spacing "DEM/Sphere spacing" \
  "subsection DEM" "set Sphere spacing = -1e-6" "end"
expect zero_diameter "Yarn/Fibre diameter" \
  "subsection Yarn" "set Fibre diameter = 0" "end"
expect negative_skin "DEM/Skin" \
  "subsection DEM" "set Skin = -1e-6" "end"
expect bad_damping "DEM/Damping ratio" \
  "subsection DEM" "set Damping ratio = 1.5" "end"
expect negative_friction "DEM/Friction coefficient" \
  "subsection DEM" "set Friction coefficient = -0.1" "end"
expect bad_slab_share "DEM/Impact slab share" \
  "subsection DEM" "set Impact slab share = 0" "end"
expect bad_joint_rebuild "DEM/Joint rebuild fraction" \
  "subsection DEM" "set Joint rebuild fraction = 1.5" "end"
expect bad_partial_search "DEM/Partial search fraction" \
  "subsection DEM" "set Partial search fraction = -0.1" "end"
expect packing_does_not_fit "Parameter 'Yarn/Number of fibres' = 4000: only" \
  "subsection Yarn" "set Number of fibres = 4000" "end"
expect quarter_asymmetric_file "Parameter 'Symmetry' = quarter needs fibre" \
  "set Symmetry = quarter" \
  "subsection Yarn" "set Number of fibres = 2" "end" \
  "subsection DEM" "set Fibre layout = file" \
  "set Fibre file = $dir/asymmetric.txt" "end"
# Model = both: the DEM input is refused before the FE part runs.
expect both_spacing_too_large "Parameter 'DEM/Sphere spacing'" \
  "set Model = both" \
  "subsection DEM" "set Sphere spacing = 13e-6" "end"
expect both_missing_file "cannot be opened" \
  "set Model = both" \
  "subsection DEM" "set Fibre layout = file" \
  "set Fibre file = $dir/none.txt" "end"
# The elementary tests use the same packing (without symmetry).
expect elementary_spacing_too_large "Parameter 'DEM/Sphere spacing'" \
  "subsection DEM" "set Sphere spacing = 13e-6" "end" \
  "subsection Elementary test" "set Loading = tension" "end"
expect elementary_too_many_fibres "Parameter 'Yarn/Number of fibres'" \
  "subsection Yarn" "set Number of fibres = 4000" "end" \
  "subsection Elementary test" "set Loading = tension" "end"
# A verification window past the end time measured nothing, after the run.
expect window_after_end "Parameter 'Verification/Window end' = 3e-06 s is" \
  "subsection Time" "set End time = 2e-6" "end" \
  "subsection Verification" "set Checks = deceleration" "end"
expect both_window_after_end "Parameter 'Verification/Window end'" \
  "set Model = both" \
  "subsection Time" "set End time = 2e-6" "end" \
  "subsection Verification" "set Checks = transverse speed" "end"

exit $failures
