#!/usr/bin/env bash
# Install conefeti into a fresh prefix and build the brick tutorial against that prefix only, the two
# ways README.md gives: find_package(conefeti) in a CMake project (tests/install/app) and
# mpicxx $(pkg-config --cflags --libs conefeti). Each program must run a small brick to convergence.
# Also checked: the installed headers hold no private/ directory and no tutorial includes one.
set -euo pipefail

while [ $# -gt 0 ]; do
  case $1 in
    --build) build=$2 ;;
    --source) source=$2 ;;
    --work) work=$2 ;;
    --cmake) cmake=$2 ;;
    --cxx) cxx=$2 ;;
    --mpicxx) mpicxx=$2 ;;
    --mpiexec) mpiexec=$2 ;;
    *) echo "install-and-build.sh: unknown argument $1" >&2; exit 1 ;;
  esac
  shift 2
done
fail() { echo "FAIL: $*" >&2; exit 1; }
here=$(cd "$(dirname "$0")" && pwd)
tutorial=$source/tutorials/contact/brick.cxx

if grep -rln 'conefeti/private/' "$source/tutorials"; then
  fail "the tutorials above include a private header, which an installed conefeti does not have"
fi

rm -rf "$work"
mkdir -p "$work"
prefix=$work/prefix
"$cmake" --install "$build" --prefix "$prefix" >"$work/install.log" || { cat "$work/install.log"; fail "cmake --install"; }
[ -f "$prefix/include/conefeti.h" ] || fail "no include/conefeti.h under $prefix"
[ ! -e "$prefix/include/conefeti/private" ] || fail "the private headers were installed"
pc=$(find "$prefix" -name conefeti.pc)
config=$(find "$prefix" -name conefetiConfig.cmake)
[ -n "$pc" ] || fail "no conefeti.pc under $prefix"
[ -n "$config" ] || fail "no conefetiConfig.cmake under $prefix"
libdir=$(dirname "$(dirname "$pc")")

# run <program>: a 2-rank brick converges (exit 0, "converged" in the pipeline line)
run() {
  local out
  out=$("$mpiexec" -n 2 "$1" -k 2 2>&1) || { echo "$out"; fail "$1 exited with $?"; }
  grep -q '^pipeline coulomb; converged' <<<"$out" || { echo "$out"; fail "$1 did not report a converged brick"; }
  echo "ok: $1 ($(grep '^pipeline' <<<"$out"))"
}

# 1. CMake: find_package(conefeti) with CMAKE_PREFIX_PATH=<prefix>
"$cmake" -S "$here/app" -B "$work/cmake-build" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_CXX_COMPILER="$cxx" \
  -DBRICK_SOURCE="$tutorial" -DCMAKE_BUILD_TYPE=Release >"$work/cmake-configure.log" 2>&1 ||
  { cat "$work/cmake-configure.log"; fail "configuring a project that calls find_package(conefeti)"; }
grep -q "conefeti_DIR:PATH=$prefix/" "$work/cmake-build/CMakeCache.txt" || fail "find_package(conefeti) did not take the one in $prefix"
"$cmake" --build "$work/cmake-build" >"$work/cmake-build.log" 2>&1 ||
  { cat "$work/cmake-build.log"; fail "building the brick with conefeti::conefeti"; }
run "$work/cmake-build/brick"

# 2. pkg-config, the library found at run time through LD_LIBRARY_PATH
flags=$(PKG_CONFIG_PATH="$libdir/pkgconfig" pkg-config --cflags --libs conefeti) || fail "pkg-config --cflags --libs conefeti"
case $flags in *"$source/include"*) fail "pkg-config points into the source tree: $flags" ;; esac
# shellcheck disable=SC2086 # the flags are words
"$mpicxx" -std=c++17 -o "$work/brick-pkgconfig" "$tutorial" $flags >"$work/pkgconfig-build.log" 2>&1 ||
  { cat "$work/pkgconfig-build.log"; fail "mpicxx $tutorial \$(pkg-config --cflags --libs conefeti)"; }
LD_LIBRARY_PATH=$libdir${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH} run "$work/brick-pkgconfig"

# 3. the installed program finds the installed library by itself
"$prefix/bin/conefeti" -help >/dev/null 2>&1 || fail "the installed $prefix/bin/conefeti does not start"
echo "ok: $prefix/bin/conefeti -help"
