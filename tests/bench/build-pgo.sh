#!/usr/bin/env bash
# make bench builds its own tree with profile-guided optimisation on top of
# the LTO build: an instrumented daemon is trained on the simulator scenarios
# that the benchmarks do NOT measure (AGM cycle, faults tour, BMS disconnect,
# thermal derate, load dump), then everything is rebuilt with that profile.
# The headline scenario (scenarios/lfp-charge.toml) is left out of the
# training on purpose, so the figure is not tuned to its own input.
# The tree is compiled for this machine's CPU (XR_HOST_CPU, -march=native
# with FMA contraction off, so every result is the baseline build's): the
# figure is what the simulator does on the machine that runs make bench.
# Usage: build-pgo.sh BUILD_DIR JOBS
set -euo pipefail
build=${1:-build-bench}
jobs=${2:-2}
root=$(cd "$(dirname "$0")/../.." && pwd)
profile=$(cd "$root" && mkdir -p "$build" && cd "$build" && pwd)/pgo-profile
stamp=$profile/trained-at-commit

configure() {
  cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DXR_PGO="$1" -DXR_PGO_DIR="$profile" -DXR_HOST_CPU=ON >/dev/null
}

# A profile is only valid for the sources it was recorded on.
head=$(git -C "$root" rev-parse HEAD 2>/dev/null || echo unknown)
if [ "$(git -C "$root" status --porcelain -- daemon drivers 2>/dev/null | wc -l)" != 0 ]; then head="$head-dirty"; fi
if [ ! -f "$stamp" ] || [ "$(cat "$stamp")" != "$head" ] || [ "$head" = "${head%-dirty}-dirty" ]; then
  echo "pgo: training an instrumented build (profile in $profile)"
  rm -rf "$profile"
  mkdir -p "$profile"
  configure generate
  cmake --build "$build" -j "$jobs" --target xregulatord
  for s in agm-cycle faults-tour bms-disconnect thermal-derate load-dump; do
    "$build/daemon/app/xregulatord" --sim --speed max --scenario "$root/scenarios/$s.toml" \
      --http 127.0.0.1:0 >/dev/null 2>&1 || { echo "pgo: training run $s failed"; exit 1; }
  done
  echo "$head" >"$stamp"
fi
configure use
cmake --build "$build" -j "$jobs" --target xr_benchmarks
