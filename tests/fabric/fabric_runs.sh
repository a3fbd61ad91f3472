#!/bin/bash
# Usage: fabric_runs.sh YARN_IMPACT SOURCE_DIR CASE [WRITE_PATCH_MESH]
# Runs of Model = fabric (doc/fabric.md) on small patches of the shipped
# example's yarns (prm/fabric/km2_patch.prm), checked by check_history.py
# or compared byte for byte. CASE:
#  energy       4 x 4 yarns, 2.5 us, no failure, a history row every step:
#               the energy balance, the projectile's momentum against the
#               impulse of the contact force, the yarn contact's forces
#               balanced (check_history.py energy says against what); the
#               displacements of its snapshots symmetric under the half turn
#               about y (check_symmetry.py).
#  tent         3 warp yarns across weft yarns with free ends, struck
#               along a line by a thin rod at 600 m/s, no failure, 4 us:
#               with weft yarns 4 mm apart the velocity lost and the cone
#               front's speed against Smith's for the warp alone; with
#               weft yarns 1 mm apart more velocity lost, but less than
#               with the weft moving along with the warp everywhere
#               (check_tent.py says how closely).
#  pyramid      21 x 21 yarns, quarter model, struck at the centre by the
#               flat cylinder at 600 m/s, no failure, 2.2 us: thin tapes
#               (crimp straightening 0.12 %) and the example's yarns with a
#               crimp of 0.065 mm (1.04 %): the cone front along the
#               principal yarns against Smith's speed for the fabric's mass
#               per yarn, the diagonal front against the diamond's, the
#               velocity lost against the diamond cone's momentum and below
#               Phoenix and Porwal's membrane (check_pyramid.py says how
#               closely).
#  cone         1 warp yarn across 5 weft yarns struck by the cylinder, no
#               failure, 1.5 us: the cone front along the warp yarn against
#               the transverse front of the station profile
#               (check_history.py cone).
#  edges        4 x 4 yarns, no failure, Fabric/Clamped edges: none (2.5
#               us, a history row every step) with the checks of energy
#               (check_history.py energy, check_symmetry.py) and the total
#               momentum conserved (check_history.py momentum); all (the
#               default, the same run), whose clamps change it; all, warp
#               ends, weft ends, none (1 us) with only the ends they name
#               held, exactly (check_edges.py).
#  flat         the energy case struck by a flat-faced cylinder
#               (Projectile/Shape = flat cylinder) of the cylinder's
#               diameter and mass: the checks of energy (check_history.py
#               energy, check_symmetry.py).
#  offset       the flat case struck at (x, z) = (0.25, 0.125) mm and at its
#               half-turn image (-0.25, -0.125) mm (Projectile/Impact offset
#               x, z): the balances of energy at (0.25, 0.125); the two
#               histories the same to round-off, and unlike the centred
#               impact's (check_history.py mirror).
#  plies        2 plies of 4 x 4 yarns, their mid-planes 0.5 mm apart (a
#               gap of 0.179 mm), 3.3 us, no failure, a history row at every
#               step, snapshots at 0 and 3.3 us, on 1 and 2 ranks: the
#               checks of energy (check_history.py energy); the gap between
#               the plies' meshes at rest; the plies' energies summing to
#               the yarns', the lower ply still until the upper one can
#               have crossed the gap, then set moving before the projectile
#               could pass the upper ply, each ply's cone fronts
#               (check_plies.py plies); the two histories byte for byte
#               the same; 2 plies 0.4 mm apart, the lower one shifted by
#               (0.5, 0.5) mm in the fabric's plane (Fabric/Ply offset x,
#               z), 3.3 us, 1 rank: the same checks but the bound on when
#               the lower ply moves, which takes aligned crossings.
#  broken       4 x 4 yarns, Yarn/Failure strain 2 %, sudden failure,
#               3 us, a snapshot at the end, on 1 and 2 ranks: the
#               history's broken yarns 0 before any cell fails, above 0 by
#               the end, the count of the last snapshot's cells
#               (check_plies.py broken); the two histories byte for byte
#               the same.
#  fragments    the V50 ply (prm/fabric/km2_ply_v50.prm) with sudden
#               failure at 550 m/s, 5 us, 2 ranks: perforated, the
#               fragments of its broken yarns striking each other, the
#               energy error below 0.5 % at every row with the faces of
#               failed cells left out of the yarn contact
#               (check_history.py fragments).
#  ranks        4 x 4 yarns, 3.5 us, failure on: the Charmetant law with
#               sudden and with progressive failure, the linear law with
#               sudden failure (progressive needs Charmetant): the
#               history on 2 and 3 ranks byte for byte the one on 1 rank,
#               cells broken or damaged in each.
#  restart      the same Charmetant case stopped by SIGTERM at row 25
#               (2.5 us, the yarns in contact) and continued with
#               --restart, on 1 and 2 ranks: the history byte for byte the
#               uninterrupted run's; the same for the 3 x 3 patch struck by
#               the sphere, no failure, stopped at 1.25 us with tied yarn
#               contacts (1 rank); the 4 x 4 patch with sudden failure at
#               2 % stopped at 2 us, after its first failed cells, whose
#               faces the yarn contact leaves out (1 rank).
#  grip         4 x 4 yarns, no failure, 2.5 us, the clamps' finite grip
#               (Fabric/Clamp grip): the rigid clamps against grips of
#               1e6 N that never slip, of stiffness 3e8 and 3e9 N/m
#               (check_grip.py stiff); the 3 x 3 patch struck by the
#               sphere with a grip of 2 N, whole, half and quarter
#               (check_grip.py symmetric); a grip of 2 N a yarn end, the
#               default stiffness, a history row every step, on 1 and 2
#               ranks: the checks of energy (check_history.py energy) with
#               the grip's energy and dissipation inside the contact and
#               dissipated columns, the slip against the rigid clamps
#               (check_grip.py slipping), the two histories byte for byte
#               the same; the same grip stopped by SIGTERM at row 15
#               (1.5 us, the ends slipping) and continued with --restart:
#               the history byte for byte the uninterrupted run's.
#  single_warp  1 warp yarn across 5 weft yarns against Model = fe with
#               the same crimped yarn (check_history.py single_warp).
#  mesh_file    (needs WRITE_PATCH_MESH) the 4 x 4 patch, no failure, 3 us,
#               a history row every 0.05 us: generated; written by
#               write-patch-mesh and read back (Fabric/Mesh file) with the
#               patch's directions at the Gauss points (Fabric/Orientation
#               file); written without physical surfaces and read with the
#               directions estimated, and with each cell's mean direction:
#               the estimated directions within 0.01 degrees of the cells'
#               mean directions (write-patch-mesh --compare), the histories
#               against each other (check_mesh_file.py says how closely);
#               the estimated run on 2 ranks byte for byte the one on 1.
#  sphere       the energy case struck by a sphere (Projectile/Shape) of
#               the cylinder's diameter and mass instead: the same checks
#               (check_history.py energy, check_symmetry.py), on 1 and 2
#               ranks, the two histories byte for byte the same.
#  symmetry_planes
#               3 x 3 yarns, no failure, 1.2 us, a history row every step:
#               struck by the sphere (snapshots every 0.5 us) and by the
#               cylinder along z, the whole patch and its half and quarter
#               models (Symmetry); the half and the whole struck by the
#               sphere 0.25 mm off z = 0; the quarter sphere also on 2
#               ranks. The
#               whole patch's mirror symmetry before and after its first
#               yarn contact; each reduced history against the whole's at
#               every row, the projectile's velocity lost within 1e-6 of
#               the whole's (check_symmetry_planes.py says how closely);
#               the 2-rank history byte for byte the 1-rank one.
exe=$1
src=$2
case=$3
writer=${4:-}
here=$(cd "$(dirname "$0")" && pwd)
. "$(dirname "$(readlink -f "$0")")/../lib.sh"
test_begin

# patch DIR WARP WEFT END_TIME HISTORY_INTERVAL [TEXT]: the example's
# yarns, WARP x WEFT of them, no snapshots.
patch() {
  printf 'include %s/prm/fabric/km2_patch.prm\n' "$src"
  printf 'subsection Fabric\n  set Warp yarns = %s\n  set Weft yarns = %s\nend\n' "$2" "$3"
  printf 'subsection Time\n  set End time = %s\nend\n' "$4"
  printf 'subsection Output\n  set Directory = %s\n  set Snapshot interval = 0\n' "$1"
  printf '  set History interval = %s\n  set Verbosity = quiet\nend\n' "$5"
  printf '%b' "${6:-}"
}

# histories_agree A B OK FAILED: the history CSVs A and B byte for byte
# (same_history), with OK printed as a passed check, or FAILED counted.
histories_agree() {
  if same_history "$1" "$2"; then
    echo "ok     $3"
  else
    fail "$4"
  fi
}

# run RANKS ARGS...: sets rc.
run() {
  local n=$1
  shift
  if [ "$n" -eq 1 ]; then
    "$exe" "$@" > stdout 2> stderr
  else
    mpirun -np "$n" "$exe" "$@" > stdout 2> stderr
  fi
  rc=$?
}

# run_pair WHAT A B: on 1 rank, A.prm and B.prm, each stdout kept as
# A.stdout and B.stdout (the set-up lines the checkers read); a run that
# fails is counted, named "WHAT, A".
run_pair() {
  local c
  for c in "$2" "$3"; do
    run 1 "$c.prm"
    [ "$rc" -eq 0 ] || fail "$1, $c: exit $rc: $(head -c 300 stderr)"
    cp stdout "$c.stdout"
  done
}

# restarted REF CUT ROW WHAT: on 1 rank, REF.prm run to its end and
# CUT.prm (the same case) stopped by SIGTERM at history row ROW and
# continued with --restart; the two histories byte for byte, the checks
# named "restart WHAT".
restarted() {
  run 1 "$1.prm"
  [ "$rc" -eq 0 ] || fail "restart $4, reference: exit $rc: $(head -c 300 stderr)"
  YARN_IMPACT_SIGNAL_AT_ROW=$3 run 1 "$2.prm"
  [ "$rc" -eq 6 ] || fail "restart $4, stop: expected exit 6, got $rc: $(head -c 300 stderr)"
  run 1 --restart "$2.prm"
  [ "$rc" -eq 0 ] || fail "restart $4: exit $rc: $(head -c 300 stderr)"
  histories_agree "$1/history_fabric.csv" "$2/history_fabric.csv" \
    "restart $4: the history is the uninterrupted run's, byte for byte" \
    "restart $4: the history differs from the uninterrupted run's"
}

no_failure='subsection Yarn\n  set Failure = false\nend\n'
linear='subsection FE\n  set Constitutive law = Linear transversely isotropic\nend\nsubsection Yarn\n  set Failure model = sudden\nend\n'
sudden='subsection Yarn\n  set Failure model = sudden\nend\n'
progressive='subsection Yarn\n  set Failure model = progressive\nend\n'

case $case in
  energy)
    patch energy 4 4 2.5e-6 1e-9 "$no_failure" > energy.prm
    sed -i 's/set Snapshot interval = 0$/set Snapshot interval = 0.5e-6/' energy.prm
    run 1 energy.prm
    [ "$rc" -eq 0 ] || fail "energy: exit $rc: $(head -c 300 stderr)"
    /usr/bin/python3 "$here/check_history.py" energy energy || failures=$((failures + 1))
    /usr/bin/python3 "$here/check_symmetry.py" energy || failures=$((failures + 1))
    ;;
  tent)
    # A strip of 3 warp yarns (their ends clamped) across weft yarns with
    # free ends, a quarter of it modelled, struck along z by a rod of
    # 0.6 mm and 9.91 mg at 600 m/s; the cone front where the deflection
    # passes 0.2 mm, above the crimp's straightening. Weft yarns 4 mm apart
    # (17, 16 cells a spacing) and 1 mm apart (71, 4 cells a spacing):
    # 68 and 71 mm long, so that the longitudinal wave stays short of the
    # clamps for the 4 us of the run.
    strip='subsection Yarn\n  set Failure = false\nend\nsubsection Fabric\n  set Clamped edges = warp ends\n  set Crimp amplitude = 0.065e-3\n  set Cone deflection threshold = 0.2e-3\nend\nsubsection Projectile\n  set Diameter = 0.6e-3\n  set Initial velocity = 600\nend\nsubsection Output\n  set Verbosity = normal\nend\nset Symmetry = quarter\n'
    wide='subsection Fabric\n  set Yarn spacing = 4e-3\n  set Cells per spacing = 16\nend\n'
    narrow='subsection Fabric\n  set Cells per spacing = 4\nend\n'
    patch wide 3 17 4e-6 0.1e-6 "$strip$wide" > wide.prm
    patch narrow 3 71 4e-6 0.1e-6 "$strip$narrow" > narrow.prm
    run_pair tent wide narrow
    /usr/bin/python3 "$here/check_tent.py" wide wide.stdout narrow narrow.stdout ||
      failures=$((failures + 1))
    ;;
  pyramid)
    # The cone front where the deflection passes 0.3 mm, above the crimp's
    # straightening; a history row every 0.05 us. Tapes: thickness
    # semi-axis 0.02 mm, crimp 0.022 mm (the meshed section reaches
    # 0.0211 mm); crimped: the example's section, crimp 0.065 mm.
    point='subsection Yarn\n  set Failure = false\nend\nsubsection Fabric\n  set Cells per spacing = 4\n  set Cone deflection threshold = 0.3e-3\nend\nsubsection Projectile\n  set Shape = flat cylinder\n  set Initial velocity = 600\nend\nsubsection Output\n  set Verbosity = normal\nend\nset Symmetry = quarter\n'
    tape='subsection Yarn\n  set Thickness semi-axis = 0.02e-3\nend\nsubsection Fabric\n  set Crimp amplitude = 0.022e-3\nend\n'
    crimped='subsection Fabric\n  set Crimp amplitude = 0.065e-3\nend\n'
    patch tape 21 21 2.2e-6 0.05e-6 "$point$tape" > tape.prm
    patch crimped 21 21 2.2e-6 0.05e-6 "$point$crimped" > crimped.prm
    run_pair pyramid tape crimped
    /usr/bin/python3 "$here/check_pyramid.py" tape tape.stdout crimped crimped.stdout ||
      failures=$((failures + 1))
    ;;
  cone)
    patch cone 1 5 1.5e-6 0.05e-6 "$no_failure" > cone.prm
    run 1 cone.prm
    [ "$rc" -eq 0 ] || fail "cone: exit $rc: $(head -c 300 stderr)"
    /usr/bin/python3 "$here/check_history.py" cone cone || failures=$((failures + 1))
    ;;
  edges)
    free='subsection Fabric\n  set Clamped edges = none\nend\n'
    patch free 4 4 2.5e-6 1e-9 "$no_failure$free" > free.prm
    patch all 4 4 2.5e-6 1e-9 "$no_failure" > all.prm
    for c in free all; do
      sed -i 's/set Snapshot interval = 0$/set Snapshot interval = 0.5e-6/' $c.prm
      run 1 $c.prm
      [ "$rc" -eq 0 ] || fail "$c: exit $rc: $(head -c 300 stderr)"
    done
    /usr/bin/python3 "$here/check_history.py" energy free || failures=$((failures + 1))
    /usr/bin/python3 "$here/check_symmetry.py" free || failures=$((failures + 1))
    /usr/bin/python3 "$here/check_history.py" momentum free conserved || failures=$((failures + 1))
    /usr/bin/python3 "$here/check_history.py" momentum all clamped || failures=$((failures + 1))
    /usr/bin/python3 "$here/check_edges.py" free none || failures=$((failures + 1))
    /usr/bin/python3 "$here/check_edges.py" all all || failures=$((failures + 1))
    for c in warp weft; do
      ends="subsection Fabric\n  set Clamped edges = $c ends\nend\n"
      patch $c 4 4 1e-6 0.1e-6 "$no_failure$ends" > $c.prm
      sed -i 's/set Snapshot interval = 0$/set Snapshot interval = 1e-6/' $c.prm
      run 1 $c.prm
      [ "$rc" -eq 0 ] || fail "$c ends: exit $rc: $(head -c 300 stderr)"
      /usr/bin/python3 "$here/check_edges.py" $c $c || failures=$((failures + 1))
    done
    ;;
  flat)
    shape='subsection Projectile\n  set Shape = flat cylinder\nend\n'
    patch flat 4 4 2.5e-6 1e-9 "$no_failure$shape" > flat.prm
    sed -i 's/set Snapshot interval = 0$/set Snapshot interval = 0.5e-6/' flat.prm
    run 1 flat.prm
    [ "$rc" -eq 0 ] || fail "flat: exit $rc: $(head -c 300 stderr)"
    /usr/bin/python3 "$here/check_history.py" energy flat || failures=$((failures + 1))
    /usr/bin/python3 "$here/check_symmetry.py" flat || failures=$((failures + 1))
    ;;
  offset)
    for c in centre:0:0 plus:0.25e-3:0.125e-3 minus:-0.25e-3:-0.125e-3; do
      IFS=: read -r name x z <<< "$c"
      shape="subsection Projectile\n  set Shape = flat cylinder\n  set Impact offset x = $x\n  set Impact offset z = $z\nend\n"
      patch $name 4 4 2.5e-6 1e-9 "$no_failure$shape" > $name.prm
      run 1 $name.prm
      [ "$rc" -eq 0 ] || fail "$name: exit $rc: $(head -c 300 stderr)"
    done
    /usr/bin/python3 "$here/check_history.py" energy plus || failures=$((failures + 1))
    /usr/bin/python3 "$here/check_history.py" mirror plus minus centre || failures=$((failures + 1))
    ;;
  plies)
    two='subsection Fabric\n  set Plies = 2\n  set Ply spacing = 0.5e-3\nend\n'
    for n in 1 2; do
      patch "plies_$n" 4 4 3.3e-6 1e-9 "$no_failure$two" > "plies_$n.prm"
      sed -i 's/set Snapshot interval = 0$/set Snapshot interval = 3.3e-6/' "plies_$n.prm"
      run $n "plies_$n.prm"
      [ "$rc" -eq 0 ] || fail "plies on $n ranks: exit $rc: $(head -c 300 stderr)"
    done
    /usr/bin/python3 "$here/check_history.py" energy plies_1 || failures=$((failures + 1))
    /usr/bin/python3 "$here/check_plies.py" plies plies_1 0.5e-3 0.1e-3 0.0575e-3 || failures=$((failures + 1))
    histories_agree plies_1/history_fabric.csv plies_2/history_fabric.csv \
      "plies: the history on 2 ranks is the one on 1 rank, byte for byte" \
      "plies: the history on 2 ranks differs from the one on 1 rank"
    shift='subsection Fabric\n  set Plies = 2\n  set Ply spacing = 0.4e-3\n  set Ply offset x = 0.5e-3\n  set Ply offset z = 0.5e-3\nend\n'
    patch shifted 4 4 3.3e-6 1e-9 "$no_failure$shift" > shifted.prm
    sed -i 's/set Snapshot interval = 0$/set Snapshot interval = 3.3e-6/' shifted.prm
    run 1 shifted.prm
    [ "$rc" -eq 0 ] || fail "shifted plies: exit $rc: $(head -c 300 stderr)"
    grep -q "each shifted by (0.5, 0.5) mm" stdout || fail "shifted plies: the set-up report does not give the shift"
    /usr/bin/python3 "$here/check_history.py" energy shifted || failures=$((failures + 1))
    /usr/bin/python3 "$here/check_plies.py" plies shifted 0.4e-3 0.1e-3 0.0575e-3 shifted || failures=$((failures + 1))
    ;;
  fragments)
    # The V50 ply with sudden failure, perforated at 550 m/s (5 us, 2 ranks).
    { printf 'include %s/prm/fabric/km2_ply_v50.prm\n' "$src"
      printf 'subsection Yarn\n  set Failure model = sudden\nend\n'
      printf 'subsection Projectile\n  set Initial velocity = 550\nend\n'
      printf 'subsection Output\n  set Directory = fragments\n'
      printf '  set Verbosity = quiet\nend\n'; } > fragments.prm
    run 2 fragments.prm
    [ "$rc" -eq 0 ] || fail "fragments: exit $rc: $(head -c 300 stderr)"
    /usr/bin/python3 "$here/check_history.py" fragments fragments || failures=$((failures + 1))
    ;;
  broken)
    weak='subsection Yarn\n  set Failure model = sudden\n  set Failure strain = 0.02\nend\n'
    for n in 1 2; do
      patch "broken_$n" 4 4 3e-6 0.1e-6 "$weak" > "broken_$n.prm"
      sed -i 's/set Snapshot interval = 0$/set Snapshot interval = 3e-6/' "broken_$n.prm"
      run $n "broken_$n.prm"
      [ "$rc" -eq 0 ] || fail "broken on $n ranks: exit $rc: $(head -c 300 stderr)"
    done
    /usr/bin/python3 "$here/check_plies.py" broken broken_1 4 4 1e-3 8 || failures=$((failures + 1))
    histories_agree broken_1/history_fabric.csv broken_2/history_fabric.csv \
      "broken: the history on 2 ranks is the one on 1 rank, byte for byte" \
      "broken: the history on 2 ranks differs from the one on 1 rank"
    ;;
  ranks)
    for law in charmetant progressive linear; do
      extra=$sudden
      [ $law = linear ] && extra=$linear
      [ $law = progressive ] && extra=$progressive
      for n in 1 2 3; do
        patch "${law}_$n" 4 4 3.5e-6 0.1e-6 "$extra" > "${law}_$n.prm"
        run $n "${law}_$n.prm"
        [ "$rc" -eq 0 ] || fail "$law on $n ranks: exit $rc: $(head -c 300 stderr)"
      done
      awk -F, 'NR > 1 && ($15 > 0 || $23 > 0) {found = 1} END {exit !found}' \
        "${law}_1/history_fabric.csv" ||
        fail "$law: no failed cell by 3.5 us (the case no longer tests failure across ranks)"
      for n in 2 3; do
        histories_agree "${law}_1/history_fabric.csv" "${law}_$n/history_fabric.csv" \
          "$law: the history on $n ranks is the one on 1 rank, byte for byte" \
          "$law: the history on $n ranks differs from the one on 1 rank"
      done
    done
    ;;
  restart)
    for n in 1 2; do
      patch "ref_$n" 4 4 3.5e-6 0.1e-6 > "ref_$n.prm"
      run $n "ref_$n.prm"
      [ "$rc" -eq 0 ] || fail "reference on $n ranks: exit $rc: $(head -c 300 stderr)"
      patch "cut_$n" 4 4 3.5e-6 0.1e-6 > "cut_$n.prm"
      YARN_IMPACT_SIGNAL_AT_ROW=25 run $n "cut_$n.prm"
      if [ "$rc" -ne 6 ] || ! grep -q "the fabric run was stopped by SIGTERM" stderr; then
        fail "stop on $n ranks: expected exit 6 and the stop line, got $rc: $(head -c 300 stderr)"
      fi
      ls "cut_$n" | grep -q '^checkpoint_fabric' || fail "stop on $n ranks: no checkpoint"
      run $n --restart "cut_$n.prm"
      [ "$rc" -eq 0 ] || fail "restart on $n ranks: exit $rc: $(head -c 300 stderr)"
      histories_agree "ref_$n/history_fabric.csv" "cut_$n/history_fabric.csv" \
        "restart on $n ranks: the history is the uninterrupted run's, byte for byte" \
        "restart on $n ranks: the history differs from the uninterrupted run's"
    done
    # The 3 x 3 patch struck by the sphere is mirror-symmetric: at row 25
    # (1.25 us) the yarn contact holds tied contacts (doc/fabric.md section
    # 10), whose faces and histories the checkpoint carries.
    extra="${no_failure}subsection Projectile\n  set Shape = sphere\nend\n"
    patch tie_ref 3 3 1.6e-6 0.05e-6 "$extra" > tie_ref.prm
    patch tie_cut 3 3 1.6e-6 0.05e-6 "$extra" > tie_cut.prm
    restarted tie_ref tie_cut 25 "with tied contacts"
    # Cells failed before the stop (sudden failure at 2 %, from 1.5 us):
    # the restart tells the yarn contact again which faces it leaves out,
    # handing no spring's energy for them.
    weak='subsection Yarn\n  set Failure model = sudden\n  set Failure strain = 0.02\nend\n'
    patch failed_ref 4 4 3e-6 0.1e-6 "$weak" > failed_ref.prm
    patch failed_cut 4 4 3e-6 0.1e-6 "$weak" > failed_cut.prm
    restarted failed_ref failed_cut 20 "with failed cells out of the yarn contact"
    awk -F, 'NR > 1 && NR <= 21 && $15 > 0 {found = 1} END {exit !found}' \
      failed_ref/history_fabric.csv ||
      fail "restart: no failed cell before the stop (the case no longer tests the faces left out)"
    ;;
  grip)
    grip() {
      printf 'subsection Fabric\n  subsection Clamp grip\n'
      printf '    set Pull-out force = %s\n    set Stiffness = %s\n' "$1" "$2"
      printf '  end\nend\n'
    }
    patch rigid 4 4 2.5e-6 0.05e-6 "$no_failure" > rigid.prm
    patch soft 4 4 2.5e-6 0.05e-6 "$no_failure$(grip 1e6 3e8)" > soft.prm
    patch hard 4 4 2.5e-6 0.05e-6 "$no_failure$(grip 1e6 3e9)" > hard.prm
    for c in rigid soft hard; do
      run 1 $c.prm
      [ "$rc" -eq 0 ] || fail "$c: exit $rc: $(head -c 300 stderr)"
    done
    /usr/bin/python3 "$here/check_grip.py" stiff rigid soft hard || failures=$((failures + 1))
    sphere='subsection Projectile\n  set Shape = sphere\nend\n'
    for s in none half quarter; do
      patch "sym_$s" 3 3 2.5e-6 0.1e-6 "set Symmetry = $s\n$no_failure$sphere$(grip 2 0)" > "sym_$s.prm"
      run 1 "sym_$s.prm"
      [ "$rc" -eq 0 ] || fail "grip, symmetry $s: exit $rc: $(head -c 300 stderr)"
    done
    /usr/bin/python3 "$here/check_grip.py" symmetric sym_none sym_half sym_quarter || failures=$((failures + 1))
    for n in 1 2; do
      patch "slip_$n" 4 4 2.5e-6 1e-9 "$no_failure$(grip 2 0)" > "slip_$n.prm"
      run $n "slip_$n.prm"
      [ "$rc" -eq 0 ] || fail "slipping grip on $n ranks: exit $rc: $(head -c 300 stderr)"
    done
    /usr/bin/python3 "$here/check_history.py" energy slip_1 || failures=$((failures + 1))
    /usr/bin/python3 "$here/check_grip.py" slipping slip_1 rigid || failures=$((failures + 1))
    histories_agree slip_1/history_fabric.csv slip_2/history_fabric.csv \
      "slipping grip: the history on 2 ranks is the one on 1, byte for byte" \
      "slipping grip: the history on 2 ranks differs from the one on 1"
    patch grip_ref 4 4 2.5e-6 0.1e-6 "$no_failure$(grip 2 0)" > grip_ref.prm
    patch grip_cut 4 4 2.5e-6 0.1e-6 "$no_failure$(grip 2 0)" > grip_cut.prm
    restarted grip_ref grip_cut 15 "with a slipping grip"
    ;;
  single_warp)
    patch fabric 1 5 0.5e-6 0.01e-6 "$no_failure" > fabric.prm
    run 1 fabric.prm
    [ "$rc" -eq 0 ] || fail "fabric: exit $rc: $(head -c 300 stderr)"
    patch fe 1 5 0.5e-6 0.01e-6 "$no_failure" > fe.prm
    printf 'set Model = fe\nsubsection Yarn\n  set Length = 5e-3\nend\n' >> fe.prm
    printf 'subsection FE\n  set Cells along the axis = 40\n  subsection Crimp\n' >> fe.prm
    printf '    set Amplitude = 0.1e-3\n    set Wavelength = 2e-3\n  end\nend\n' >> fe.prm
    # The fabric's step is shorter (its yarn contact's springs): this
    # safety factor gives the FE run the fabric's first step, 9.2357 ns,
    # to 2e-5, so that the two runs differ by their yarns, not their steps.
    printf 'subsection Time\n  set Safety factor = 0.69821\nend\n' >> fe.prm
    run 1 fe.prm
    [ "$rc" -eq 0 ] || fail "fe: exit $rc: $(head -c 300 stderr)"
    /usr/bin/python3 "$here/check_history.py" single_warp fabric fe || failures=$((failures + 1))
    ;;
  mesh_file)
    "$writer" 4 4 8 patch || fail "write-patch-mesh 4 4 8 patch"
    "$writer" 4 4 8 bare --no-surfaces --per-cell || fail "write-patch-mesh bare"
    mesh='  set Mesh file = patch.msh\n  set Orientation file = patch.orientation\n'
    bare='  set Mesh file = bare.msh\n'
    cells='  set Mesh file = bare.msh\n  set Orientation file = bare.orientation\n'
    for run_case in generated read estimated per_cell; do
      case $run_case in
        generated) extra='' ;;
        read) extra=$mesh ;;
        estimated) extra=$bare ;;
        per_cell) extra=$cells ;;
      esac
      patch "$run_case" 4 4 3e-6 0.05e-6 "$no_failure" > "$run_case.prm"
      sed -i "s/^  set Weft yarns = 4$/&\n$extra/" "$run_case.prm"
      run 1 "$run_case.prm"
      [ "$rc" -eq 0 ] || fail "mesh_file $run_case: exit $rc: $(head -c 300 stderr)"
    done
    angle=$("$writer" --compare bare.msh bare.orientation)
    echo "       $angle"
    if /usr/bin/python3 -c "import sys; sys.exit(0 if float(sys.argv[1]) < 0.01 else 1)" \
         "$(echo "$angle" | sed 's/.*directions \([0-9.e+-]*\) degrees/\1/')"; then
      echo "ok     estimated directions within 0.01 degrees of the cells' mean directions"
    else
      fail "estimated directions: $angle"
    fi
    /usr/bin/python3 "$here/check_mesh_file.py" generated read estimated per_cell || failures=$((failures + 1))
    sed 's/Directory = estimated$/Directory = estimated_2/' estimated.prm > estimated_2.prm
    run 2 estimated_2.prm
    [ "$rc" -eq 0 ] || fail "mesh_file estimated on 2 ranks: exit $rc: $(head -c 300 stderr)"
    histories_agree estimated/history_fabric.csv estimated_2/history_fabric.csv \
      "mesh_file: the estimated run on 2 ranks is the one on 1 rank, byte for byte" \
      "mesh_file: the estimated run on 2 ranks differs from the one on 1 rank"
    ;;
  sphere)
    shape='subsection Projectile\n  set Shape = sphere\nend\n'
    for n in 1 2; do
      patch "sphere_$n" 4 4 2.5e-6 1e-9 "$no_failure$shape" > "sphere_$n.prm"
      sed -i 's/set Snapshot interval = 0$/set Snapshot interval = 0.5e-6/' "sphere_$n.prm"
      run $n "sphere_$n.prm"
      [ "$rc" -eq 0 ] || fail "sphere on $n ranks: exit $rc: $(head -c 300 stderr)"
    done
    /usr/bin/python3 "$here/check_history.py" energy sphere_1 || failures=$((failures + 1))
    /usr/bin/python3 "$here/check_symmetry.py" sphere_1 || failures=$((failures + 1))
    histories_agree sphere_1/history_fabric.csv sphere_2/history_fabric.csv \
      "sphere: the history on 2 ranks is the one on 1 rank, byte for byte" \
      "sphere: the history on 2 ranks differs from the one on 1 rank"
    ;;
  symmetry_planes)
    check="$here/check_symmetry_planes.py"
    for shape in sphere cylinder; do
      for sym in none half quarter; do
        patch "${shape}_$sym" 3 3 1.2e-6 1e-9 \
          "${no_failure}set Symmetry = $sym\nsubsection Projectile\n  set Shape = $shape\nend\n" \
          > "${shape}_$sym.prm"
      done
    done
    # Off the plane z = 0, on the plane x = 0: the half model still holds.
    for sym in none half; do
      patch "offset_$sym" 3 3 1.2e-6 1e-9 \
        "${no_failure}set Symmetry = $sym\nsubsection Projectile\n  set Shape = sphere\n  set Impact offset z = 0.25e-3\nend\n" \
        > "offset_$sym.prm"
    done
    sed -i 's/set Snapshot interval = 0$/set Snapshot interval = 0.5e-6/' sphere_none.prm
    cp sphere_quarter.prm sphere_quarter_2.prm
    sed -i 's/Directory = sphere_quarter$/Directory = sphere_quarter_2/' sphere_quarter_2.prm
    for r in sphere_none sphere_half sphere_quarter cylinder_none cylinder_half \
      cylinder_quarter offset_none offset_half; do
      run 1 $r.prm
      [ "$rc" -eq 0 ] || fail "$r: exit $rc: $(head -c 300 stderr)"
    done
    run 2 sphere_quarter_2.prm
    [ "$rc" -eq 0 ] || fail "sphere_quarter on 2 ranks: exit $rc: $(head -c 300 stderr)"
    /usr/bin/python3 "$check" mirror sphere_none || failures=$((failures + 1))
    for sym in half quarter; do
      /usr/bin/python3 "$check" compare sphere_none sphere_$sym 1e-6 || failures=$((failures + 1))
      /usr/bin/python3 "$check" compare cylinder_none cylinder_$sym 1e-6 || failures=$((failures + 1))
    done
    /usr/bin/python3 "$check" compare offset_none offset_half 1e-6 || failures=$((failures + 1))
    histories_agree sphere_quarter/history_fabric.csv sphere_quarter_2/history_fabric.csv \
      "symmetry_planes: the quarter model's history on 2 ranks is the one on 1 rank, byte for byte" \
      "symmetry_planes: the quarter model's history on 2 ranks differs from the one on 1 rank"
    ;;
  *)
    echo "unknown case $case"
    exit 2
    ;;
esac
test_end
