#!/usr/bin/env bash
# Times two versions of fastnorm's headers in one process along the bench trajectory
# (ab_headers.cpp; docs/performance.md §1, "Comparing two versions").
#
#   examples/bench/ab/ab.sh [--steps N] [--rounds R] [--solver NAME] A [B]
#   examples/bench/ab/ab.sh --same A        # A against itself: the instrument's spread
#
# A and B: a git revision of this repository (its include/ tree) or a directory holding
# fastnorm/; B defaults to the working tree's include/. Builds with g++ -O3 in
# ${AB_BUILD:-build/ab} (about a minute on 2 cores) and prints one line per round and the
# median ratios B/A (below 1: B faster). Needs libeigen3-dev (scripts/test installs it).
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)
steps=2000 rounds=3 solver=elliptic same=0
while [ $# -gt 0 ]; do
  case "$1" in
    --steps) steps=$2; shift 2 ;;
    --rounds) rounds=$2; shift 2 ;;
    --solver) solver=$2; shift 2 ;;
    --same) same=1; shift ;;
    -h | --help) sed -n '2,12p' "$0"; exit 0 ;;
    -*) echo "ab.sh: unknown option $1" >&2; exit 2 ;;
    *) break ;;
  esac
done
[ $# -ge 1 ] || { echo "ab.sh: name version A (a git revision or a directory holding fastnorm/)" >&2; exit 2; }
version_a=$1
version_b=${2:-$root/include}
[ "$same" = 1 ] && version_b=$version_a

build=${AB_BUILD:-$root/build/ab}
mkdir -p "$build"
build=$(cd "$build" && pwd)

# A header tree: a directory as it is, or a revision's include/ extracted into the build.
headers() {
  local version=$1 slot=$2
  if [ -d "$version/fastnorm" ]; then
    (cd "$version" && pwd)
  else
    rm -rf "${build:?}/$slot"
    mkdir -p "$build/$slot"
    git -C "$root" archive "$version" include | tar -x -C "$build/$slot"
    echo "$build/$slot/include"
  fi
}
headers_a=$(headers "$version_a" a)
headers_b=$(headers "$version_b" b)

flags=(-std=c++17 -O3 -DNDEBUG -DEIGEN_DONT_PARALLELIZE -I"$root/examples" -isystem /usr/include/eigen3)
compile_variant() {
  local variant=$1 include=$2
  g++ "${flags[@]}" -I"$include" -Dfastnorm=fastnorm_$variant -Dfastnorm_bench=fastnorm_bench_$variant \
    -Dfastnorm_example=fastnorm_example_$variant -DAB_VARIANT=$variant \
    -c "$root/examples/bench/ab/model_variant.cpp" -o "$build/model_$variant.o"
}
compile_variant a "$headers_a" &
compile_variant b "$headers_b" &
g++ "${flags[@]}" -c "$root/examples/bench/ab/ab_headers.cpp" -o "$build/ab_headers.o"
wait %1 && wait %2
g++ "$build/ab_headers.o" "$build/model_a.o" "$build/model_b.o" -o "$build/ab_headers"

echo "ab: A = $version_a ($headers_a), B = $version_b ($headers_b)"
"$build/ab_headers" "$steps" "$solver" "$rounds" "$build/poses_$steps.bin"
