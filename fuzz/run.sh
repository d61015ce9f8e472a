#!/usr/bin/env bash
# Builds the fuzz targets and runs libFuzzer for a bounded time, on one core.
#
#   fuzz/run.sh SECONDS [TARGET]     TARGET: expr | model | scene | all (default all: SECONDS split
#                                    evenly, the targets one after another)
#
# Build directory: build-fuzz/ (override with ROTGEN_FUZZ_BUILD), clang++ (ROTGEN_FUZZ_CXX).
# Working corpora grow in BUILD/corpus/TARGET (seeded from models/*.yaml, models/scenes/*.yaml,
# fuzz/seeds/TARGET and fuzz/regressions/TARGET); crashes, timeouts and out-of-memory inputs are
# written to BUILD/artifacts/TARGET/; the libFuzzer log to BUILD/logs/TARGET.log.
# Before fuzzing, every kept regression input in fuzz/regressions/TARGET is replayed.
# Exit status: 0 when nothing was found, 1 otherwise (the artifact paths are printed).
set -euo pipefail

usage() { echo "usage: fuzz/run.sh SECONDS [expr|model|scene|all]" >&2; exit 2; }
[[ $# -ge 1 && $# -le 2 && $1 =~ ^[0-9]+$ && $1 -gt 0 ]] || usage
seconds=$1
target=${2:-all}
case $target in expr|model|scene) targets=("$target") ;; all) targets=(expr model scene) ;; *) usage ;; esac

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${ROTGEN_FUZZ_BUILD:-$root/build-fuzz}
cxx=${ROTGEN_FUZZ_CXX:-clang++}
timeout=${ROTGEN_FUZZ_TIMEOUT:-10}      # seconds per input before libFuzzer calls it a hang
rss=${ROTGEN_FUZZ_RSS_MB:-2048}         # memory limit per process

if [[ ! -f $build/CMakeCache.txt ]]; then
  cmake -S "$root/fuzz" -B "$build" -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
fi
cmake --build "$build" -j"${ROTGEN_FUZZ_BUILD_JOBS:-2}" --target "${targets[@]/#/rotgen_fuzz_}"

per=$(( seconds / ${#targets[@]} ))
(( per > 0 )) || per=1
status=0
export ASAN_OPTIONS=${ASAN_OPTIONS:-abort_on_error=1:detect_leaks=0:quarantine_size_mb=64}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
for t in "${targets[@]}"; do
  bin=$build/rotgen_fuzz_$t
  corpus=$build/corpus/$t
  artifacts=$build/artifacts/$t
  mkdir -p "$corpus" "$artifacts" "$build/logs" "$root/fuzz/regressions/$t"
  case $t in
    model) cp "$root"/models/*.yaml "$corpus/" ;;
    scene) cp "$root"/models/scenes/*.yaml "$corpus/" ;;
  esac

  # Replay the kept regressions first: each must now give a result or a user error.
  shopt -s nullglob
  regressions=("$root/fuzz/regressions/$t"/*)
  shopt -u nullglob
  if (( ${#regressions[@]} > 0 )); then
    echo "run.sh: replaying ${#regressions[@]} regression input(s) for $t" >&2
    "$bin" -timeout="$timeout" -rss_limit_mb="$rss" "${regressions[@]}" >"$build/logs/$t.replay.log" 2>&1 \
      || { echo "run.sh: a regression input of $t fails again; see $build/logs/$t.replay.log" >&2; status=1; continue; }
  fi

  echo "run.sh: fuzzing $t for $per s (one process, one core)" >&2
  before=$(ls "$artifacts" | wc -l)
  set +e
  "$bin" "$corpus" "$root/fuzz/seeds/$t" "$root/fuzz/regressions/$t" \
    -dict="$root/fuzz/rotgen.dict" -max_total_time="$per" -timeout="$timeout" -rss_limit_mb="$rss" \
    -malloc_limit_mb="$rss" -max_len="${ROTGEN_FUZZ_MAX_LEN:-8192}" -artifact_prefix="$artifacts/" \
    -print_final_stats=1 -reload=0 2>&1 | tee "$build/logs/$t.log" | grep -E '^(#[0-9]+[[:space:]]+(INITED|DONE|pulse)|==[0-9]+==|rotgen-fuzz|SUMMARY|stat::)' >&2
  rc=${PIPESTATUS[0]}
  set -e
  after=$(ls "$artifacts" | wc -l)
  if (( rc != 0 || after > before )); then
    echo "run.sh: $t found something (exit $rc); new artifacts:" >&2
    ls -t "$artifacts" | head -n $(( after - before + 1 )) | sed "s|^|  $artifacts/|" >&2
    status=1
  fi
done
exit $status
