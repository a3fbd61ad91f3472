#!/bin/bash
# Bad DEM input must stop yarn-impact with a one-line error that names the
# parameter, and a non-zero exit code.  Usage: bad_input.sh path/to/yarn-impact
exe="$1"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
failures=0

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
  local out
  # A set-up refused after the output directory was prepared leaves its
  # parameters.prm there; each case starts from an empty folder.
  rm -rf "$dir/run"
  out=$("$exe" "$dir/$name.prm" 2>&1)
  local rc=$?
  if [ $rc -eq 0 ] || ! grep -q -- "$text" <<< "$out" ||
     [ "$(grep -c 'error' <<< "$out")" -ne 1 ]; then
    echo "FAILED $name (exit $rc): $out"
    failures=$((failures + 1))
  else
    echo "PASSED $name: $out"
  fi
}

printf '0 0\n1e-5 oops\n' > "$dir/malformed.txt"
printf '0 0\n5e-6 0\n' > "$dir/overlap.txt"
printf '0 0\n' > "$dir/short.txt"

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

exit $failures
