#!/usr/bin/env bash
# Runs every fuzzer built in BUILD for RUNS inputs each with a fixed seed (the same run every time,
# so a CI failure reproduces; long searches go by hand with -runs=10000000 or -max_total_time),
# from a copy of its seed corpus (the corpus in the repository only grows by hand), and fails on
# the first finding: a crash, a sanitizer report, a leak or a timeout. The crashing input is left
# in the work folder and its path printed.
#   bash test/fuzz/run_fuzzers.sh build-fuzz 20000 [name ...]
# Every seed is first run once whole; then the fuzzing takes the flags of <name>.options
# ([libfuzzer] section, OSS-Fuzz's format: `max_len = 8192` becomes -max_len=8192), which may
# cap the input length below the largest seed, whose mutants would otherwise all be that long.
# The timeout is wall-clock time per input (10 s); a long run that shares its machine with other
# work can raise it with RANGEFIT_FUZZ_TIMEOUT=<seconds>, so waiting for a core is not a finding.
set -euo pipefail
build=${1:?usage: run_fuzzers.sh BUILD RUNS [name ...]}
runs=${2:?usage: run_fuzzers.sh BUILD RUNS [name ...]}
timeout=${RANGEFIT_FUZZ_TIMEOUT:-10}
shift 2
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d /tmp/rangefit-fuzz.XXXXXX)
names=("$@")
if [ ${#names[@]} -eq 0 ]; then
  for exe in "$build"/test/fuzz/*_fuzz; do names+=("$(basename "$exe" _fuzz)"); done
fi
for name in "${names[@]}"; do
  exe="$build/test/fuzz/${name}_fuzz"
  mkdir -p "$work/$name"
  [ -d "$here/corpus/$name" ] && cp -r "$here/corpus/$name/." "$work/$name/"
  flags=()
  if [ -f "$here/$name.options" ]; then
    while read -r key value; do flags+=("-$key=$value"); done < <(
      sed -n 's/^[[:space:]]*\([a-z_]*\)[[:space:]]*=[[:space:]]*\([^[:space:]]*\).*/\1 \2/p' \
        "$here/$name.options")
  fi
  export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
  seeds=("$work/$name"/*)
  if [ -e "${seeds[0]}" ] && ! "$exe" -timeout="$timeout" -rss_limit_mb=2048 \
      -artifact_prefix="$work/$name-" "${seeds[@]}" > "$work/$name-seeds.log" 2>&1; then
    tail -n 40 "$work/$name-seeds.log"
    echo "fuzz: $name failed on a seed; see $work/$name-seeds.log"
    exit 1
  fi
  if ! "$exe" -seed=1 -runs="$runs" -timeout="$timeout" -rss_limit_mb=2048 -print_final_stats=1 \
      "${flags[@]}" -artifact_prefix="$work/$name-" "$work/$name" > "$work/$name.log" 2>&1; then
    tail -n 40 "$work/$name.log"
    echo "fuzz: $name found a problem; input: $(ls "$work/$name"-* 2>/dev/null | head -1)"
    exit 1
  fi
  echo "fuzz: $name $(grep -o 'number_of_executed_units: [0-9]*' "$work/$name.log" | cut -d' ' -f2) runs, no finding"
done
rm -rf "$work"
