#!/usr/bin/env bash
# Regenerate every figure and every script-made table of docs/ from a build of the current commit.
#
#   scripts/figures.sh [--clean] [--quick] [--only name,name,...]
#
# --clean   remove the build directory first ($BUILD_DIR, default build) and build from scratch
# --quick   skip the long ones (validation, peers, table3, the ablation tables, feti, qp)
# --only    run only the named parts (below)
#
# The parts, what each writes and how long it takes. "measured": on the project's test machine (2 cores)
# while other jobs shared it, at the commit of the page; "page": the time the page states for its command.
#
#   brick         docs/brick-benchmark.md: the defaults table and the paper's-tolerance table
#                 (scripts/bench-brick.py at 1e-6 and 1e-4)                            1.5 min measured
#   accuracy      docs/accuracy-cost.md: monolithic from 1e-2 to 1e-8 (scripts/bench-accuracy.py) 1 min page
#   precision     docs/figures/work-precision*.png and docs/work-precision.md's table
#                 (scripts/work-precision.py: brick, two bodies, 1e-1 to 1e-10)       12.5 min measured
#   solutions     docs/figures/solution-brick.png, solution-twobodies.png, solution-indentation.png,
#                 solution-hemisphere.png (build/conefeti -output,
#                 scripts/render-solution.py)                                         0.5 min measured
#   validation    docs/validation.md and docs/figures/hertz-*.png, cattaneo-*.png: Hertz on three or four meshes per
#                 case (scripts/bench-hertz.py), two elastic bodies against Hertz and Cattaneo-Mindlin
#                 (scripts/bench-cattaneo.py, about 20 min more) and scale on real geometry
#                 (scripts/bench-geometry-scale.py) 12 min measured before the two-body cases
#   peers         docs/peers.md, docs/peers.png: PETSc's own solvers on the same problem
#                 (scripts/bench-peers.py)                                             35 min page
#   table3        docs/table3.md: the seed paper's Table 3, disks against friction polygons k = 2, 4
#                 (scripts/bench-table3.py)                                             8 min measured
#   ablations     docs/brick-ablations.md: every table (scripts/bench-brick.py --extra ...,
#                 scripts/goals-brick.py); the prose beside them was written for the numbers at the
#                 commits the page names, so read the diff                              ~10 min page
#   feti          build/figures/feti-benchmark.md (scripts/bench-feti.py, as docs/feti-benchmark.md
#                 says; copied into that page by hand: its tables are interleaved with text) 15 min page
#   qp            build/figures/qp-benchmark.md (scripts/bench-qp.sh; likewise by hand)       11 min page
#
# The pages made when dense K+ blocks were the contact default (brick-benchmark's paper-tolerance table,
# accuracy-cost, the ablations) pass -feti_kplus_explicit 1, which reproduces them bit for bit.
#
# Everything: about 1 h 50 min, plus the build (3-6 min from clean); --quick: about 15 minutes.
# Tables go into their pages between a marker `<!-- generated: NAME -->` and the end of the fenced block
# after it (scripts/docs-block.py), with a first line "# made at commit <hash> on <machine>, <date>".
# Needs python3-matplotlib (scripts/setup.sh).
set -euo pipefail
cd "$(dirname "$0")/.."

build=${BUILD_DIR:-build}
clean=0 quick=0 only=""
while [ $# -gt 0 ]; do
  case "$1" in
    --clean) clean=1 ;;
    --quick) quick=1 ;;
    --only) only="$2"; shift ;;
    *) echo "figures.sh: unknown argument $1 (see the header of scripts/figures.sh)" >&2; exit 1 ;;
  esac
  shift
done
want() {
  if [ -n "$only" ]; then [[ ",$only," == *",$1,"* ]]; return; fi
  if [ $quick -eq 1 ]; then case "$1" in validation|peers|table3|ablations|feti|qp) return 1 ;; esac; fi
  return 0
}

/usr/bin/python3 -c "import matplotlib, h5py, numpy" 2>/dev/null || {
  echo "figures.sh: python3-matplotlib, python3-h5py and python3-numpy are needed (scripts/setup.sh installs them)" >&2
  exit 1
}
[ $clean -eq 1 ] && rm -rf "$build"
BUILD_DIR=$build scripts/build.sh >/dev/null

commit=$(git rev-parse --short HEAD)
[ -n "$(git status --porcelain --untracked-files=no -- src include tutorials CMakeLists.txt)" ] && commit="$commit + local changes"
machine="$(uname -n) ($(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | sed 's/.*: //'))"
prov="commit $commit on $machine, $(date -u '+%Y-%m-%d %H:%M UTC')"
mkdir -p build/figures docs/figures
start=$SECONDS
say() { echo "figures.sh: [$(((SECONDS - start) / 60)) min] $*"; }
block() { /usr/bin/python3 scripts/docs-block.py "$1" "$2" --provenance "$prov"; }

if want brick; then
  say "brick: defaults"
  scripts/bench-brick.py --build "$build" --algorithms monolithic --rtol 1e-6 | block docs/brick-benchmark.md defaults
  say "brick: the paper's tolerance"
  scripts/bench-brick.py --build "$build" --algorithms monolithic,msa,merged --extra "-feti_kplus_explicit 1" | block docs/brick-benchmark.md paper-tolerance
fi

if want accuracy; then
  say "accuracy-cost"
  scripts/bench-accuracy.py --build "$build" --extra "-feti_kplus_explicit 1" | block docs/accuracy-cost.md tables
fi

if want precision; then
  say "work-precision (the longest part)"
  scripts/work-precision.py --build "$build" --json build/figures/work-precision.json --table build/figures/work-precision.md >/dev/null
  block docs/work-precision.md tables <build/figures/work-precision.md
fi

if want solutions; then
  say "solution pictures"
  tmp=$(mktemp -d)
  "$build/conefeti" -options_file petsc-options/brick.opts -scene_refine 8 -output "$tmp/brick" -summary_table 0 >/dev/null
  scripts/render-solution.py "$tmp/brick.h5" docs/figures/solution-brick.png \
    --title "brick, n = 5832, Coulomb F = 0.3, defaults (build/conefeti -options_file petsc-options/brick.opts -scene_refine 8)"
  "$build/conefeti" -options_file petsc-options/twobodies.opts -scene_refine 5 -output "$tmp/twobodies" -summary_table 0 >/dev/null
  scripts/render-solution.py "$tmp/twobodies.h5" docs/figures/solution-twobodies.png \
    --title "two bodies, Coulomb F = 0.3, defaults (build/conefeti -options_file petsc-options/twobodies.opts -scene_refine 5)"
  "$build/conefeti" -options_file petsc-options/indentation.opts -scene_body0_cells 20,20,20 -scene_body0_subdomains 3,3,3 -output "$tmp/indentation" -summary_table 0 >/dev/null
  scripts/render-solution.py "$tmp/indentation.h5" docs/figures/solution-indentation.png \
    --title "Hertz indentation, frictionless (build/conefeti -options_file petsc-options/indentation.opts -scene_body0_cells 20,20,20 -scene_body0_subdomains 3,3,3)"
  gmsh -3 meshes/hemisphere.geo -setnumber h 0.02 -o "$tmp/hemisphere.msh" -v 2 >/dev/null
  "$build/conefeti" -options_file petsc-options/hemisphere.opts -scene_body0_mesh "$tmp/hemisphere.msh" -output "$tmp/hemisphere" -summary_table 0 >/dev/null
  scripts/render-solution.py "$tmp/hemisphere.h5" docs/figures/solution-hemisphere.png \
    --title "elastic hemisphere on a rigid plane (Gmsh, h = 0.02 at the contact; petsc-options/hemisphere.opts)"
  rm -rf "$tmp"
fi

if want validation; then
  say "validation (docs/validation.md: Hertz on three meshes per case, scale on real geometry)"
  scripts/bench-hertz.py --build "$build" --case box --sizes 10,20,30 --write docs/validation.md --plot docs/figures/hertz-box.png
  scripts/bench-hertz.py --build "$build" --case indentation --sizes 0.04,0.02,0.01 --write docs/validation.md --plot docs/figures/hertz-indentation.png
  scripts/bench-hertz.py --build "$build" --case hemisphere --sizes 0.04,0.02,0.01,0.007 --write docs/validation.md --plot docs/figures/hertz-hemisphere.png
  scripts/bench-cattaneo.py --build "$build" --case hertz --part 2 --sizes 0.02,0.014,0.01,0.007,0.005 --write docs/validation.md --plot-dir docs/figures
  scripts/bench-cattaneo.py --build "$build" --case hertz --sizes 0.02,0.014,0.01 --write docs/validation.md --section hertz-whole
  scripts/bench-cattaneo.py --build "$build" --case mindlin --part 2 --sizes 0.02,0.014,0.01,0.007,0.005 --write docs/validation.md --plot-dir docs/figures
  scripts/bench-cattaneo.py --build "$build" --case mindlin --sizes 0.02,0.014,0.01 --write docs/validation.md --section mindlin-whole
  scripts/bench-cattaneo.py --build "$build" --case mindlin --part 2 --sizes 0.02,0.014,0.01,0.007,0.005 --targets 0 --write docs/validation.md --section mindlin-press
  scripts/bench-geometry-scale.py --build "$build" --write docs/validation.md
fi

if want peers; then
  say "peers (docs/peers.md, docs/peers.png)"
  scripts/bench-peers.py --build "$build"
fi

if want ablations; then
  page=docs/brick-ablations.md
  say "ablations (every table of $page)"
  b() { scripts/bench-brick.py --build "$build" "$@"; }
  b --algorithms monolithic,merged --extra "-feti_kplus_explicit 1 -paper_m -gap 3e-3" | block $page paper-zone
  b --algorithms monolithic,msa --extra "-feti_kplus_explicit 1 -contact_tao_smalxe_penalty_pc 0" | block $page penalty-pc-off
  b --algorithms monolithic --extra "-feti_kplus_explicit 1 -contact_tao_smalxe_rho 2 -contact_tao_smalxe_rho_first 0.5 -contact_tao_smalxe_anderson_start 2" | block $page rho-first
  b --algorithms monolithic --extra "-feti_kplus_explicit 1 -options_file petsc-options/coulomb-fewer-iterations.opts" | block $page fewer-iterations
  scripts/goals-brick.py --build "$build" --others --config default --config "fewer-iterations=-options_file petsc-options/coulomb-fewer-iterations.opts" \
    --config "rho-first=-contact_tao_smalxe_rho 2 -contact_tao_smalxe_rho_first 0.5 -contact_tao_smalxe_anderson_start 2" \
    --config "projcg=-contact_tao_smalxe_subsolver_tao_mpgp_expansion_projcg" | block $page goals
  b --algorithms monolithic --extra "-feti_kplus_explicit 1 -contact_tao_smalxe_penalty_pc 0 -contact_tao_smalxe_subsolver_tao_mpgp_arc 0" | block $page arc-off
  b --algorithms monolithic,msa,merged --extra "-feti_kplus_explicit 1 -contact_tao_smalxe_penalty_pc 0 -contact_coulomb_follow_radii 0" | block $page follow-radii-off
  { b --algorithms msa --extra "-feti_kplus_explicit 1 -contact_tao_smalxe_penalty_pc 0 -contact_msa_recycle 0"; echo
    b --algorithms msa --extra "-feti_kplus_explicit 1 -contact_tao_smalxe_penalty_pc 0 -contact_msa_start_rtol 1e-7"; } | block $page msa
  b --algorithms monolithic --extra "-feti_kplus_explicit 1 -contact_tao_smalxe_penalty_pc 0 -contact_tao_smalxe_anderson 0" | block $page anderson-off
  b --algorithms monolithic --extra "-feti_kplus_explicit 1 -contact_tao_smalxe_penalty_pc 0 -contact_tao_smalxe_rho 2" | block $page rho-2
  b --algorithms monolithic --extra "-feti_kplus_explicit 1 -contact_tao_smalxe_penalty_pc 0 -contact_tao_smalxe_rho 3" | block $page rho-3
  b --algorithms monolithic,msa,merged --extra "-feti_kplus_explicit 1 -contact_tao_smalxe_penalty_pc 0 -contact_tao_smalxe_subsolver_tao_mpgp_expansion_projcg 1 -contact_tao_smalxe_block0_tao_mprgp_expansion_projcg 1 -contact_tao_smalxe_block1_tao_mpgp_expansion_projcg 1" | block $page projcg
  b --algorithms monolithic --extra "-feti_kplus_explicit 0" | block $page kplus-implicit
  b --algorithms monolithic --hugepages 0 --extra "-feti_kplus_explicit 1" | block $page small-pages
fi

if want table3; then
  say "table3 (docs/table3.md)"
  scripts/bench-table3.py --build "$build" --markdown docs/table3.md
fi

if want feti; then
  say "feti (build/figures/feti-benchmark.md; copy into docs/feti-benchmark.md by hand)"
  scripts/bench-feti.py --build "$build" --repeat 2 --parts factor,scaling,compare >build/figures/feti-benchmark.md
fi

if want qp; then
  say "qp (build/figures/qp-benchmark.md; copy into docs/qp-benchmark.md by hand)"
  scripts/bench-qp.sh >build/figures/qp-benchmark.md
fi

say "done ($prov); git diff docs/ shows what changed"
