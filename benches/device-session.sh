#!/usr/bin/env bash
# One GPU session, end to end, in a single command: build (or take prebuilt binaries), list
# the adapters, run the GPU tests with JKRBEM_REQUIRE_GPU=1, time the kernels (with the
# per-kernel profile where the binary has it), the cuFFT / VkFFT / copy floors, a 2048×1024
# R1/R2 = 5 pull-off (adhesive force and full curve), the same scene on both backends for
# parity, and `--accuracy 1%` runs. Every step has a time limit; a step that runs out is
# reported as such (with the progress it made) and the session goes on.
#
#     OUT=report-dir benches/device-session.sh                 # every step
#     OUT=report-dir benches/device-session.sh bench floors    # some steps, in this order
#
# Steps: devices tests bench floors measure curve parity accuracy (default: all, in that order).
# Writes $OUT/report.md (the summary), $OUT/*.csv and $OUT/log.txt.
#
# Environment:
#   JKRBEM_BIN_DIR   folder with a prebuilt `jkrbem` and test binaries under tests/ (used when
#                    cargo is missing, as on a machine that cannot reach crates.io)
#   PYVKFFT_SRC      a pyvkfft source tree to build with nvcc for the VkFFT floor (optional)
#   GRIDS            bench grids (default 256,512,1024,2048)
#   BENCH_LIMIT_S, BENCH_REPEATS, BENCH_PULLOFF_MAX, MEASURE_LIMIT_S, CURVE_LIMIT_S, PARITY_GRID, PARITY_LIMIT_S, ACCURACY_LIMIT_S, TESTS_LIMIT_S
set -uo pipefail
cd "$(dirname "$0")/.."
ROOT=$(pwd)
OUT=${OUT:-jkrbem-out/device}
mkdir -p "$OUT"
OUT=$(cd "$OUT" && pwd)
LOG=$OUT/log.txt
REPORT=$OUT/report.md
GRIDS=${GRIDS:-256,512,1024,2048}
MEASURE_LIMIT_S=${MEASURE_LIMIT_S:-280}
CURVE_LIMIT_S=${CURVE_LIMIT_S:-280}
PARITY_GRID=${PARITY_GRID:-512}
PARITY_LIMIT_S=${PARITY_LIMIT_S:-240}
ACCURACY_LIMIT_S=${ACCURACY_LIMIT_S:-200}
TESTS_LIMIT_S=${TESTS_LIMIT_S:-240}
STEPS=("$@")
[ ${#STEPS[@]} -eq 0 ] && STEPS=(devices tests bench floors measure curve parity accuracy)
T0=$(date +%s)

say() { echo "$*" | tee -a "$REPORT"; }
log() { echo "[$(($(date +%s) - T0)) s] $*" | tee -a "$LOG" >&2; }
# Run a command under a time limit (SIGINT, then SIGKILL 10 s later), output to the log.
limited() {
  local limit=$1
  shift
  timeout -s INT -k 10 "$limit" "$@" >>"$LOG" 2>&1
}

# ---- the binaries ----------------------------------------------------------------------
if command -v cargo >/dev/null 2>&1 && [ -z "${JKRBEM_BIN_DIR:-}" ]; then
  log "building with $(cargo --version)"
  cargo build --release >>"$LOG" 2>&1 || { log "build failed"; exit 1; }
  BIN=$ROOT/target/release/jkrbem
  TEST_BINS=()
  cargo test --release --no-run --message-format=json 2>>"$LOG" |
    python3 -c 'import json,sys
for l in sys.stdin:
    m = json.loads(l)
    if m.get("reason") == "compiler-artifact" and m.get("executable") and m["target"]["kind"] == ["test"]:
        print(m["target"]["name"], m["executable"])' >"$OUT/.tests"
  while read -r name exe; do TEST_BINS+=("$name=$exe"); done <"$OUT/.tests"
  rm -f "$OUT/.tests"
else
  DIR=${JKRBEM_BIN_DIR:?no cargo here: set JKRBEM_BIN_DIR to prebuilt binaries}
  DIR=$(cd "$DIR" && pwd)
  BIN=$DIR/jkrbem
  TEST_BINS=()
  for t in "$DIR"/tests/*; do TEST_BINS+=("$(basename "$t")=$t"); done
  # Test binaries find the CLI at the path it was built at; point that path here.
  if [ -f "$DIR/built-at" ]; then
    built=$(cat "$DIR/built-at")
    if [ "$built" != "$BIN" ] && [ ! -e "$built" ]; then
      mkdir -p "$(dirname "$built")" && ln -sf "$BIN" "$built"
    fi
  fi
fi
log "jkrbem: $BIN"

: >"$REPORT"
say "# jkrbem device session"
say ""
say "- date: $(date -u '+%Y-%m-%d %H:%M UTC')"
say "- commit: $(git rev-parse --short HEAD 2>/dev/null || echo unknown)$(git diff --quiet 2>/dev/null || echo ' (with uncommitted changes)')"
say "- host: $(nproc) CPU threads, $(awk '/MemTotal/ {printf "%.0f GiB", $2/1048576}' /proc/meminfo)"
if command -v nvidia-smi >/dev/null 2>&1; then
  say "- GPU: $(nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm,clocks.max.mem --format=csv,noheader)"
fi
say "- steps: ${STEPS[*]}"
say ""

# pyvkfft builds with nvcc in the background while the GPU tests run.
VKFFT_SITE=$OUT/.pyvkfft
if [ -n "${PYVKFFT_SRC:-}" ] && [[ " ${STEPS[*]} " == *" floors "* ]]; then
  (VKFFT_BACKEND=cuda timeout 400 python3 -m pip install -q --no-index --no-deps \
    --no-build-isolation --target "$VKFFT_SITE" "$PYVKFFT_SRC" >"$OUT/pyvkfft-build.txt" 2>&1 &&
    echo ok >>"$OUT/pyvkfft-build.txt") &
  VKFFT_BUILD=$!
fi
VKFFT_WAITED=

# Sample a growing states CSV every 10 s: elapsed s, states, CG iterations, last d̄ and c̄.
watch_states() {
  local csv=$1 trace=$2
  echo "elapsed_s,states,cg_iterations,d_bar,c_bar,f_bar" >"$trace"
  local t=0
  while sleep 10; do
    t=$((t + 10))
    [ -f "$csv" ] || continue
    python3 - "$csv" "$t" >>"$trace" 2>/dev/null <<'EOF'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
if rows:
    it = sum(int(r["cg_iterations"]) for r in rows)
    r = rows[-1]
    print(f'{sys.argv[2]},{len(rows)},{it},{r["d_bar"]},{r["c_bar"]},{r["f_bar"]}')
EOF
  done
}

# One pull-off under a limit; prints a table row for the report.
pulloff() {
  local label=$1 limit=$2
  shift 2
  local stem=$OUT/$label
  log "pull-off $label: $*"
  watch_states "$stem.incomplete.csv" "$stem.trace.csv" &
  local watcher=$!
  local start=$(date +%s.%N)
  limited "$limit" "$BIN" simulate "$@" --out "$stem.csv" --summary "$stem.json"
  local rc=$?
  local wall=$(python3 -c "import time; print(f'{time.time() - $start:.1f}')")
  kill $watcher 2>/dev/null
  wait $watcher 2>/dev/null
  python3 - "$label" "$rc" "$wall" "$stem" "$*" <<'EOF' | tee -a "$REPORT"
import csv, json, os, sys
label, rc, wall, stem, args = sys.argv[1:]
path = stem + ".csv" if os.path.exists(stem + ".csv") else stem + ".incomplete.csv"
rows = list(csv.DictReader(open(path))) if os.path.exists(path) else []
it = sum(int(r["cg_iterations"]) for r in rows)
fmin = min((float(r["f_bar"]) for r in rows), default=float("nan"))
status = "complete" if rc == "0" else ("time limit" if rc in ("124", "130", "137") else f"exit {rc}")
last = rows[-1] if rows else {}
print(f"| {label} | `{args}` | {status} | {wall} | {len(rows)} | {it} | "
      f"{float(wall) / it * 1e3 if it else float('nan'):.3f} | {abs(fmin):.6f} | "
      f"{last.get('d_bar', '—')} | {last.get('c_bar', '—')} |")
EOF
}

pulloff_header() {
  say "| run | flags | status | wall (s) | states | CG iterations | wall / iteration (ms) | \\|min F̄\\| so far | last d̄ | last c̄ |"
  say "| --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
}

for step in "${STEPS[@]}"; do
  log "step $step"
  case $step in
  devices)
    say "## Adapters (\`jkrbem devices\`)"
    say ""
    say '```'
    "$BIN" devices 2>&1 | tee -a "$REPORT" >>"$LOG"
    say '```'
    say ""
    ;;
  tests)
    say "## GPU tests (JKRBEM_REQUIRE_GPU=1, limit ${TESTS_LIMIT_S} s each)"
    say ""
    say "| test binary | result | wall (s) |"
    say "| --- | --- | ---: |"
    # The binaries run side by side (each with 4 test threads) to keep the step short.
    names=()
    pids=()
    for entry in "${TEST_BINS[@]}"; do
      name=${entry%%=*}
      exe=${entry#*=}
      case $name in gpu_* | cli_gpu | failure_cg | bench) ;; *) continue ;; esac
      names+=("$name")
      (start=$(date +%s)
        JKRBEM_REQUIRE_GPU=1 timeout -k 10 "$TESTS_LIMIT_S" "$exe" --test-threads 4 >"$OUT/test-$name.txt" 2>&1
        echo "exit $? after $(($(date +%s) - start)) s" >>"$OUT/test-$name.txt") &
      pids+=($!)
    done
    wait "${pids[@]}"
    for name in "${names[@]}"; do
      summary=$(grep -E "^test result" "$OUT/test-$name.txt" | tail -1)
      ended=$(tail -n 1 "$OUT/test-$name.txt")
      [[ $ended == "exit 124"* ]] && summary="time limit"
      say "| $name | ${summary:-$ended} | ${ended##* after } |"
    done
    cat "$OUT"/test-*.txt >>"$LOG"
    rm -f "$OUT"/test-*.txt
    say ""
    ;;
  bench)
    say "## Kernels and CG iterations (\`jkrbem bench\`)"
    say ""
    profile=()
    "$BIN" bench --help 2>/dev/null | grep -q -- "--profile" && profile=(--profile)
    say '```'
    timeout -s INT -k 10 "${BENCH_LIMIT_S:-300}" "$BIN" bench --backends cpu,gpu --grids "$GRIDS" \
      --pulloff-max-grid "${BENCH_PULLOFF_MAX:-256}" --repeats "${BENCH_REPEATS:-3}" --cg-iterations 10 "${profile[@]}" --out "$OUT/bench" >"$OUT/bench.txt" 2>&1 || echo "(bench exited with $?)" >>"$OUT/bench.txt"
    grep -v "^bench: " "$OUT/bench.txt" >>"$REPORT"
    cat "$OUT/bench.txt" >>"$LOG"
    say '```'
    cp "$OUT/bench/bench.csv" "$OUT/bench.csv" 2>/dev/null
    cp "$OUT/bench/profile.csv" "$OUT/profile.csv" 2>/dev/null
    rm -rf "$OUT/bench"
    say ""
    ;;
  floors)
    say "## Floors: cuFFT, VkFFT and copy bandwidth (same device)"
    say ""
    if [ -n "${VKFFT_BUILD:-}" ]; then
      wait "$VKFFT_BUILD"
      if grep -q '^ok$' "$OUT/pyvkfft-build.txt"; then
        export PYTHONPATH=$VKFFT_SITE${PYTHONPATH:+:$PYTHONPATH}
      else
        say "(pyvkfft did not build: $(tail -n 3 "$OUT/pyvkfft-build.txt" | tr '\n' ' '))"
      fi
    fi
    say '```'
    timeout -k 10 300 python3 benches/cufft_floor.py --grids "$GRIDS" --out "$OUT/floors.csv" >"$OUT/floors.txt" 2>&1 ||
      echo "(cufft_floor.py exited with $?)" >>"$OUT/floors.txt"
    cat "$OUT/floors.txt" | tee -a "$LOG" >>"$REPORT"
    say '```'
    say ""
    ;;
  measure)
    say "## 2048×1024 R1/R2 = 5, adhesive force (limit ${MEASURE_LIMIT_S} s)"
    say ""
    pulloff_header
    pulloff gpu-2048-measure "$MEASURE_LIMIT_S" --ratio 5 --grid 2048 --backend gpu --measure adhesive-force
    say ""
    ;;
  curve)
    say "## 2048×1024 R1/R2 = 5, full curve (limit ${CURVE_LIMIT_S} s)"
    say ""
    pulloff_header
    pulloff gpu-2048-curve "$CURVE_LIMIT_S" --ratio 5 --grid 2048 --backend gpu
    say ""
    ;;
  parity)
    say "## Parity: R1/R2 = 5 at ${PARITY_GRID} on both backends, run side by side (limit ${PARITY_LIMIT_S} s each)"
    say ""
    pulloff_header
    pulloff "cpu-${PARITY_GRID}-measure" "$PARITY_LIMIT_S" --ratio 5 --grid "$PARITY_GRID" --backend cpu --measure adhesive-force >"$OUT/.cpu-row" &
    cpu_job=$!
    pulloff "gpu-${PARITY_GRID}-measure" "$PARITY_LIMIT_S" --ratio 5 --grid "$PARITY_GRID" --backend gpu --measure adhesive-force
    wait $cpu_job
    rm -f "$OUT/.cpu-row"
    python3 - "$OUT/gpu-${PARITY_GRID}-measure.json" "$OUT/cpu-${PARITY_GRID}-measure.json" <<'EOF2' | tee -a "$REPORT"
import json, sys
try:
    g, c = (json.load(open(p))["f_ad_bar"] for p in sys.argv[1:])
    print(f"\n|min F̄| GPU {g:.7f}, CPU {c:.7f}: relative difference {abs(g - c) / c:.2e}")
except Exception as e:
    print(f"\n(no parity figure: {e})")
EOF2
    say ""
    ;;
  accuracy)
    say "## \`--accuracy 1%\` on the GPU (limit ${ACCURACY_LIMIT_S} s each)"
    say ""
    for r in 1 5 25; do
      log "accuracy R1/R2 = $r"
      start=$(date +%s)
      limited "$ACCURACY_LIMIT_S" "$BIN" simulate --ratio "$r" --accuracy 1% --backend gpu \
        --out "$OUT/accuracy-r$r.csv" --summary "$OUT/accuracy-r$r.json"
      rc=$?
      say "- R1/R2 = $r: exit $rc after $(($(date +%s) - start)) s: $(grep -E '\|min F̄\||f_ad' "$LOG" | tail -n 1)"
    done
    say ""
    ;;
  *)
    log "unknown step $step"
    ;;
  esac
done
say "Session wall time: $(($(date +%s) - T0)) s."
rm -rf "$VKFFT_SITE"
# At most a few files come back from a device call: keep the report and the log, pack the rest.
(cd "$OUT" && find . -maxdepth 1 -type f ! -name report.md ! -name log.txt ! -name results.tar.gz -printf '%P\n' |
  tar czf results.tar.gz -T - --remove-files 2>/dev/null)
