#!/usr/bin/env bash
# One GPU session in a single command, under one time limit: the Vulkan preflight, then the
# steps asked for, each capped by what is left of SESSION_LIMIT_S (a step that no longer fits is
# skipped, and the report says so). Package first (benches/device-package.sh); the plan, the two
# device commands and what each step measures are in docs/gpu.md ("The device session").
#
#     OUT=report-dir JKRBEM_BIN_DIR=device-pack SESSION_LIMIT_S=525 benches/device-session.sh devices measure bench floors parity
#
# Steps (in the order given; default: devices measure bench floors parity):
#   devices   the adapters wgpu sees (`jkrbem devices`)
#   measure   R1/R2 = MEASURE_RATIO at MEASURE_GRID, --measure adhesive-force, on the GPU
#   bench     `jkrbem bench --profile` at GRIDS (sphere, CPU and GPU), and at MEASURE_GRID for
#             MEASURE_RATIO (the iteration time of the measure run's grid)
#   floors    cuFFT's padded convolution and R2C + C2R pair, VkFFT's where pyvkfft imports, and
#             the copy bandwidth (benches/cufft_floor.py; needs CuPy)
#   parity    R1/R2 = 5 at PARITY_GRID, adhesive force, on the GPU (f32) and the CPU (f64)
#   tests     the `gpu` test binary with JKRBEM_REQUIRE_GPU=1 (TESTS_ARGS, e.g. --include-ignored;
#             TESTS_FILTER, a name filter)
#   accuracy  `--accuracy ACCURACY_TARGET` on the GPU for R1/R2 in ACCURACY_RATIOS, each against
#             the reference table (data/reference/adhesive-force.csv)
#   curve     R1/R2 = MEASURE_RATIO at CURVE_GRID, the whole curve, on the GPU
#   profile   a whole pull-off's profile: `jkrbem bench --profile` with the pull-off of
#             R1/R2 = MEASURE_RATIO at MEASURE_GRID (--measure adhesive-force), timed, then run
#             again with timestamps: the host's time blocked on readbacks and submitting, and
#             each kernel's GPU time over the whole pull-off
#   sphere    the sphere's whole curve at SPHERE_GRID², on the GPU
#   rough     a rough sphere's adhesive force at ROUGH_GRID² on the GPU (R = 1, rms slope 0.1,
#             Hurst 0.8, the short cut-off 8 elements; the map made there by `jkrbem roughness`)
#
# Writes $OUT/report.md (the headline and the targets first, then each step's table), and
# $OUT/log.txt; every other file is packed into $OUT/results.tar.gz at the end (a device call
# brings back only a few files). A finished run's figures come from its summary JSON, a run cut
# at its limit's from its partial states file (benches/device_report.py).
#
# Environment (limits in seconds; each is also capped by what is left of the session):
#   JKRBEM_BIN_DIR   a package from benches/device-package.sh (needed where cargo is missing)
#   SESSION_LIMIT_S  the whole session (default 525); RESERVE_S kept for the report (default 15)
#   GL_DIR           the loader packages the preflight unpacks where libvulkan is missing (.gl)
#   MEASURE_RATIO (5), MEASURE_GRID (2048), MEASURE_LIMIT_S (240)
#   GRIDS (256,512,1024,2048), BENCH_REPEATS (3), BENCH_LIMIT_S (120), FLOORS_LIMIT_S (90)
#   PARITY_GRID (512), PARITY_LIMIT_S (150)
#   TESTS_LIMIT_S (240), TESTS_ARGS, TESTS_FILTER
#   ACCURACY_RATIOS (1,5,25), ACCURACY_TARGET (1%), ACCURACY_LIMIT_S (60 each)
#   CURVE_GRID (2048), CURVE_LIMIT_S (180)
#   PROFILE_LIMIT_S (300); SPHERE_GRID (2048), SPHERE_LIMIT_S (180)
#   ROUGH_GRID (2048), ROUGH_LIMIT_S (180), ROUGH_FLAGS (the scene's flags besides the map's)
#   PYVKFFT_SRC      a pyvkfft source tree to build with nvcc for the VkFFT floor (optional)
set -uo pipefail
cd "$(dirname "$0")/.."
ROOT=$(pwd)
T0=$(date +%s)
OUT=${OUT:-jkrbem-out/device}
mkdir -p "$OUT"
OUT=$(cd "$OUT" && pwd)
LOG=$OUT/log.txt
REPORT=$OUT/report.md
BODY=$OUT/.body.md
SESSION_LIMIT_S=${SESSION_LIMIT_S:-525}
RESERVE_S=${RESERVE_S:-15}
GL_DIR=${GL_DIR:-.gl}
MEASURE_RATIO=${MEASURE_RATIO:-5}
MEASURE_GRID=${MEASURE_GRID:-2048}
MEASURE_LIMIT_S=${MEASURE_LIMIT_S:-240}
GRIDS=${GRIDS:-256,512,1024,2048}
BENCH_REPEATS=${BENCH_REPEATS:-3}
BENCH_LIMIT_S=${BENCH_LIMIT_S:-120}
FLOORS_LIMIT_S=${FLOORS_LIMIT_S:-90}
PARITY_GRID=${PARITY_GRID:-512}
PARITY_LIMIT_S=${PARITY_LIMIT_S:-150}
TESTS_LIMIT_S=${TESTS_LIMIT_S:-240}
TESTS_ARGS=${TESTS_ARGS:-}
TESTS_FILTER=${TESTS_FILTER:-}
ACCURACY_RATIOS=${ACCURACY_RATIOS:-1,5,25}
ACCURACY_TARGET=${ACCURACY_TARGET:-1%}
ACCURACY_LIMIT_S=${ACCURACY_LIMIT_S:-60}
CURVE_GRID=${CURVE_GRID:-2048}
CURVE_LIMIT_S=${CURVE_LIMIT_S:-180}
PROFILE_LIMIT_S=${PROFILE_LIMIT_S:-300}
SPHERE_GRID=${SPHERE_GRID:-2048}
SPHERE_LIMIT_S=${SPHERE_LIMIT_S:-180}
ROUGH_GRID=${ROUGH_GRID:-2048}
ROUGH_LIMIT_S=${ROUGH_LIMIT_S:-180}
REPORTER=(python3 "$ROOT/benches/device_report.py")
STEPS=("$@")
[ ${#STEPS[@]} -eq 0 ] && STEPS=(devices measure bench floors parity)
: >"$BODY"
: >"$LOG"
# wgpu complains on every start where XDG_RUNTIME_DIR is unset (as on the device machine).
if [ -z "${XDG_RUNTIME_DIR:-}" ]; then
  XDG_RUNTIME_DIR=$(mktemp -d)
  export XDG_RUNTIME_DIR
fi

say() { echo "$*" >>"$BODY"; }
log() { echo "[$(($(date +%s) - T0)) s] $*" >>"$LOG"; echo "[$(($(date +%s) - T0)) s] $*" >&2; }
# Seconds left of the session, less the reserve for the report.
left_s() { echo $((SESSION_LIMIT_S - RESERVE_S - ($(date +%s) - T0))); }
# budget NOMINAL MIN: a step's limit, NOMINAL capped by what is left; 0 when under MIN.
budget() {
  local l
  l=$(left_s)
  if [ "$l" -lt "$2" ]; then echo 0; elif [ "$l" -lt "$1" ]; then echo "$l"; else echo "$1"; fi
}
skipped() { say "(skipped: $(left_s) s left of the session's ${SESSION_LIMIT_S} s, and $1 needs at least $2 s)"; say ""; }
# Run a command under a time limit (SIGINT, then SIGKILL 10 s later), output to the log.
limited() {
  local limit=$1
  shift
  timeout -s INT -k 10 "$limit" "$@" >>"$LOG" 2>&1
}
now() { python3 -c 'import time; print(time.time())'; }
since() { python3 -c "import time; print(f'{time.time() - $1:.1f}')"; }

# ---- the binaries ----------------------------------------------------------------------
TEST_BINS=()
if [ -z "${JKRBEM_BIN_DIR:-}" ] && command -v cargo >/dev/null 2>&1; then
  log "building with $(cargo --version)"
  cargo build --release >>"$LOG" 2>&1 || { log "build failed"; exit 1; }
  while read -r name exe; do TEST_BINS+=("$name=$exe"); done < <(
    cargo test --release --no-run --test gpu --message-format=json 2>>"$LOG" |
      python3 -c 'import json, sys
for line in sys.stdin:
    m = json.loads(line)
    if m.get("reason") == "compiler-artifact" and m.get("executable") and m["target"]["kind"] == ["test"]:
        print(m["target"]["name"], m["executable"])')
  BIN=$ROOT/target/release/jkrbem
  COMMIT="$(git rev-parse --short HEAD 2>/dev/null || echo unknown)$(git diff --quiet HEAD 2>/dev/null || echo ' + uncommitted changes')"
else
  DIR=${JKRBEM_BIN_DIR:?no cargo here: set JKRBEM_BIN_DIR to a package from benches/device-package.sh}
  DIR=$(cd "$DIR" && pwd)
  BIN=$DIR/jkrbem
  for t in "$DIR"/tests/*; do [ -x "$t" ] && TEST_BINS+=("$(basename "$t")=$t"); done
  # The test binaries find the CLI at the path it was built at; point that path here.
  if [ -f "$DIR/built-at" ]; then
    built=$(cat "$DIR/built-at")
    if [ "$built" != "$BIN" ] && [ ! -e "$built" ]; then
      mkdir -p "$(dirname "$built")" && ln -sf "$BIN" "$built"
    fi
  fi
  COMMIT=$(cat "$DIR/commit" 2>/dev/null || echo unknown)
fi
[ -x "$BIN" ] || { log "no jkrbem binary at $BIN"; exit 1; }
log "jkrbem: $BIN"

HEADER=$OUT/.header.md
{
  echo "# jkrbem device session"
  echo ""
  echo "- date: $(date -u '+%Y-%m-%d %H:%M UTC')"
  echo "- commit: $COMMIT"
  echo "- host: $(nproc) CPU threads, $(awk '/MemTotal/ {printf "%.0f GiB", $2/1048576}' /proc/meminfo)"
  if command -v nvidia-smi >/dev/null 2>&1; then
    echo "- GPU: $(nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm,clocks.max.mem --format=csv,noheader 2>&1)"
  fi
  echo "- steps: ${STEPS[*]}; session limit ${SESSION_LIMIT_S} s"
} >"$HEADER"

# ---- the Vulkan preflight --------------------------------------------------------------
# The device machine may have no Vulkan loader: unpack Debian's from GL_DIR (packaged by
# device-package.sh). Where the loader finds no hardware driver, point it at NVIDIA's ICD.
PREFLIGHT=()
if ldconfig -p 2>/dev/null | grep -q 'libvulkan\.so\.1'; then
  PREFLIGHT+=("libvulkan.so.1 present")
elif ls "$GL_DIR"/*.deb >/dev/null 2>&1; then
  n=0
  for f in "$GL_DIR"/*.deb; do dpkg -x "$f" / && n=$((n + 1)); done
  ldconfig
  if ldconfig -p | grep -q 'libvulkan\.so\.1'; then
    PREFLIGHT+=("unpacked $n loader packages from $GL_DIR; libvulkan.so.1 found")
  else
    PREFLIGHT+=("unpacked $n loader packages from $GL_DIR, but libvulkan.so.1 is still missing: GPU steps will fail")
  fi
else
  PREFLIGHT+=("no libvulkan.so.1 and no loader packages in $GL_DIR: GPU steps will fail (run benches/device-package.sh and carry $GL_DIR)")
fi
hardware_adapter() { "$BIN" devices 2>/dev/null | grep -E '^[0-9]+\. ' | grep -qv '\[software'; }
if ! hardware_adapter; then
  icd=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
  egl=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
  if [ -z "${VK_DRIVER_FILES:-}" ] && [ -f "$icd" ]; then
    export VK_DRIVER_FILES=$icd
    [ -f "$egl" ] && export __EGL_VENDOR_LIBRARY_FILENAMES=$egl
    if hardware_adapter; then
      PREFLIGHT+=("no hardware adapter at first; VK_DRIVER_FILES=$icd found one")
    else
      PREFLIGHT+=("no hardware adapter, even with VK_DRIVER_FILES=$icd")
    fi
  else
    PREFLIGHT+=("no hardware adapter (software only, or none)")
  fi
else
  PREFLIGHT+=("a hardware adapter found")
fi
{
  echo "- Vulkan preflight: $(IFS=';'; echo "${PREFLIGHT[*]}" | sed 's/;/; /g')"
  echo "- adapter: $("$BIN" devices 2>&1 | grep -E '^1\. ' | head -n 1 || echo none)"
  echo ""
} >>"$HEADER"
log "preflight: ${PREFLIGHT[*]}"

# pyvkfft builds with nvcc in the background while other steps run.
VKFFT_SITE=$OUT/.pyvkfft
VKFFT_BUILD=
if [ -n "${PYVKFFT_SRC:-}" ] && [[ " ${STEPS[*]} " == *" floors "* ]]; then
  (VKFFT_BACKEND=cuda timeout 300 python3 -m pip install -q --no-index --no-deps \
    --no-build-isolation --target "$VKFFT_SITE" "$PYVKFFT_SRC" >"$OUT/pyvkfft-build.txt" 2>&1 &&
    echo ok >>"$OUT/pyvkfft-build.txt") &
  VKFFT_BUILD=$!
fi

# Sample a growing partial states file every 10 s (elapsed s, states, CG iterations, last d̄ c̄ F̄).
watch_states() {
  local stem=$1 trace=$2 t=0
  echo "elapsed_s,states,cg_iterations,d_bar,c_bar,f_bar" >"$trace"
  while sleep 10; do
    t=$((t + 10))
    "${REPORTER[@]}" trace "$stem" "$t" >>"$trace" 2>/dev/null
  done
}

# One pull-off under a limit: its table row (from its JSON, or its partial states if cut).
pulloff() {
  local label=$1 limit=$2
  shift 2
  local stem=$OUT/$label
  log "pull-off $label (limit $limit s): $*"
  watch_states "$stem" "$stem.trace.csv" &
  local watcher=$!
  local start rc wall
  start=$(now)
  limited "$limit" "$BIN" simulate "$@" --out "$stem.csv" --summary "$stem.json"
  rc=$?
  wall=$(since "$start")
  kill "$watcher" 2>/dev/null
  wait "$watcher" 2>/dev/null
  log "pull-off $label: exit $rc after $wall s"
  "${REPORTER[@]}" row "$label" "$rc" "$wall" "$stem" "$*" >>"$BODY" 2>>"$LOG"
}
pulloff_header() { python3 -c 'import sys; sys.path.insert(0, sys.argv[1]); import device_report; print(device_report.ROW_HEADER)' "$ROOT/benches" >>"$BODY"; }

# One pull-off on the GPU as a step of its own: NOMINAL_LIMIT TITLE LABEL FLAGS... (its section,
# skipped with a line where the session has under 30 s left).
gpu_pulloff_step() {
  local nominal=$1 title=$2 label=$3 lim
  shift 3
  lim=$(budget "$nominal" 30)
  say "## $title (limit ${lim} s)"
  say ""
  if [ "$lim" = 0 ]; then skipped "$label" 30; return; fi
  pulloff_header
  pulloff "$label" "$lim" "$@" --backend gpu
  say ""
}

# One `jkrbem bench` into $OUT/<name>.csv (and <name>-profile.csv), its text into the body.
bench() {
  local name=$1 limit=$2
  shift 2
  log "bench $name (limit $limit s): $*"
  timeout -s INT -k 10 "$limit" "$BIN" bench "$@" --out "$OUT/.$name" >"$OUT/$name.txt" 2>&1 ||
    echo "(bench exited with $?)" >>"$OUT/$name.txt"
  say '```'
  grep -v -E '^(jkrbem: )?bench: ' "$OUT/$name.txt" | grep -v -E '^written: ' >>"$BODY"
  say '```'
  cat "$OUT/$name.txt" >>"$LOG"
  cp "$OUT/.$name/bench.csv" "$OUT/$name.csv" 2>/dev/null
  cp "$OUT/.$name/profile.csv" "$OUT/$name-profile.csv" 2>/dev/null
  cp "$OUT/.$name/pulloff-profile.csv" "$OUT/$name-pulloff-profile.csv" 2>/dev/null
  rm -rf "${OUT:?}/.$name"
}

for step in "${STEPS[@]}"; do
  log "step $step ($(left_s) s left)"
  case $step in
  devices)
    say "## Adapters (\`jkrbem devices\`)"
    say ""
    say '```'
    timeout -k 5 30 "$BIN" devices >>"$BODY" 2>&1 || say "(jkrbem devices exited with $?)"
    say '```'
    say ""
    ;;
  measure)
    gpu_pulloff_step "$MEASURE_LIMIT_S" "${MEASURE_GRID} grid, R1/R2 = ${MEASURE_RATIO}, adhesive force" \
      "gpu-${MEASURE_GRID}-measure" --ratio "$MEASURE_RATIO" --grid "$MEASURE_GRID" --measure adhesive-force
    ;;
  curve)
    gpu_pulloff_step "$CURVE_LIMIT_S" "${CURVE_GRID} grid, R1/R2 = ${MEASURE_RATIO}, whole curve" \
      "gpu-${CURVE_GRID}-curve" --ratio "$MEASURE_RATIO" --grid "$CURVE_GRID"
    ;;
  profile)
    lim=$(budget "$PROFILE_LIMIT_S" 30)
    say "## Whole pull-off profile: R1/R2 = ${MEASURE_RATIO} at Nx = ${MEASURE_GRID}, adhesive force (\`jkrbem bench --profile\`, limit ${lim} s)"
    say ""
    if [ "$lim" = 0 ]; then skipped profile 30; continue; fi
    bench profile "$lim" --backends gpu --ratio "$MEASURE_RATIO" --grids "$MEASURE_GRID" \
      --pulloff-max-grid "$MEASURE_GRID" --measure adhesive-force --repeats 1 --cg-iterations 10 --profile
    say ""
    ;;
  sphere)
    gpu_pulloff_step "$SPHERE_LIMIT_S" "${SPHERE_GRID}² sphere, whole curve" \
      "gpu-${SPHERE_GRID}-sphere-curve" --ratio 1 --grid "$SPHERE_GRID"
    ;;
  rough)
    # The grid's Δx: a 64² smooth sphere's (the same margin, 0.08) scaled to ROUGH_GRID. The map:
    # twice the grid's elements at that spacing, so that it covers the domain.
    limited 60 "$BIN" simulate --ratio 1 --grid 64 --measure adhesive-force --backend cpu \
      --out "$OUT/.probe.csv" --summary "$OUT/.probe.json"
    dx=$(python3 -c 'import json, sys; r = json.load(open(sys.argv[1]))["runs"][0]; print(r["dx"] * r["nx"] / int(sys.argv[2]))' \
      "$OUT/.probe.json" "$ROUGH_GRID" 2>>"$LOG")
    rm -f "$OUT/.probe.csv" "$OUT/.probe.json"
    if [ -z "$dx" ]; then
      say "## ${ROUGH_GRID}² rough sphere"; say ""; say "(skipped: the probe run gave no Δx)"; say ""
      continue
    fi
    map=$OUT/rough-${ROUGH_GRID}.npy
    cutoff=$(python3 -c "print(8 * $dx)")
    "$BIN" roughness --out "$map" --grid $((2 * ROUGH_GRID)) --spacing "$dx" --hurst 0.8 \
      --rms-slope 0.1 --cutoff "$cutoff" --seed 1 >>"$LOG" 2>&1
    # shellcheck disable=SC2086 # ROUGH_FLAGS is a word list
    gpu_pulloff_step "$ROUGH_LIMIT_S" "${ROUGH_GRID}² rough sphere (rms slope 0.1, Hurst 0.8, cut-off 8 Δx = $cutoff), adhesive force" \
      "gpu-${ROUGH_GRID}-rough-measure" --ratio 1 --grid "$ROUGH_GRID" --roughness "$map" \
      --spacing "$dx" ${ROUGH_FLAGS:-} --measure adhesive-force
    rm -f "$map"
    ;;
  bench)
    lim=$(budget "$BENCH_LIMIT_S" 20)
    say "## Kernels and CG iterations (\`jkrbem bench --profile\`, limit ${lim} s)"
    say ""
    if [ "$lim" = 0 ]; then skipped bench 20; continue; fi
    profile=()
    "$BIN" bench --help 2>/dev/null | grep -q -- "--profile" && profile=(--profile)
    bench bench $((lim * 2 / 3)) --backends cpu,gpu --grids "$GRIDS" --pulloff-max-grid 0 \
      --repeats "$BENCH_REPEATS" --cg-iterations 10 "${profile[@]}"
    lim=$(budget $((lim / 3)) 10)
    if [ "$lim" != 0 ]; then
      say ""
      say "The measure run's grid: R1/R2 = ${MEASURE_RATIO}, Nx = ${MEASURE_GRID}, GPU only:"
      say ""
      bench bench-measure "$lim" --backends gpu --ratio "$MEASURE_RATIO" --grids "$MEASURE_GRID" \
        --pulloff-max-grid 0 --repeats "$BENCH_REPEATS" --cg-iterations 10 "${profile[@]}"
    fi
    say ""
    ;;
  floors)
    lim=$(budget "$FLOORS_LIMIT_S" 15)
    say "## Floors: cuFFT, VkFFT and copy bandwidth (same device, limit ${lim} s)"
    say ""
    if [ "$lim" = 0 ]; then skipped floors 15; continue; fi
    if [ -n "$VKFFT_BUILD" ]; then
      # The build gets what is left of the step's limit, no more.
      (sleep $((lim / 3)); kill "$VKFFT_BUILD" 2>/dev/null) &
      wait "$VKFFT_BUILD"
      if grep -q '^ok$' "$OUT/pyvkfft-build.txt" 2>/dev/null; then
        export PYTHONPATH=$VKFFT_SITE${PYTHONPATH:+:$PYTHONPATH}
      else
        say "(pyvkfft did not build: $(tail -n 3 "$OUT/pyvkfft-build.txt" 2>/dev/null | tr '\n' ' '))"
      fi
      lim=$(budget "$lim" 10)
    fi
    say '```'
    timeout -k 10 "$lim" python3 benches/cufft_floor.py --grids "$GRIDS" --out "$OUT/floors.csv" >"$OUT/floors.txt" 2>&1 ||
      echo "(cufft_floor.py exited with $?: no floors measured)" >>"$OUT/floors.txt"
    cat "$OUT/floors.txt" >>"$BODY"
    cat "$OUT/floors.txt" >>"$LOG"
    say '```'
    say ""
    ;;
  parity)
    lim=$(budget "$PARITY_LIMIT_S" 20)
    say "## Parity: R1/R2 = 5 at Nx = ${PARITY_GRID}, adhesive force, GPU (f32) and CPU (f64) side by side (limit ${lim} s each)"
    say ""
    if [ "$lim" = 0 ]; then skipped parity 20; continue; fi
    pulloff_header
    pulloff "cpu-parity-${PARITY_GRID}-measure" "$lim" --ratio 5 --grid "$PARITY_GRID" --backend cpu --measure adhesive-force &
    cpu_job=$!
    pulloff "gpu-parity-${PARITY_GRID}-measure" "$lim" --ratio 5 --grid "$PARITY_GRID" --backend gpu --measure adhesive-force
    wait "$cpu_job"
    say ""
    "${REPORTER[@]}" parity "$OUT/gpu-parity-${PARITY_GRID}-measure" "$OUT/cpu-parity-${PARITY_GRID}-measure" >>"$BODY" 2>>"$LOG"
    say ""
    ;;
  tests)
    lim=$(budget "$TESTS_LIMIT_S" 30)
    say "## GPU tests (JKRBEM_REQUIRE_GPU=1 ${TESTS_ARGS} ${TESTS_FILTER}, limit ${lim} s)"
    say ""
    if [ "$lim" = 0 ]; then skipped tests 30; continue; fi
    say "| test binary | result | wall (s) |"
    say "| --- | --- | ---: |"
    ran=0
    for entry in "${TEST_BINS[@]}"; do
      name=${entry%%=*}
      exe=${entry#*=}
      [ "$name" = gpu ] || continue
      ran=1
      log "tests: $exe $TESTS_ARGS $TESTS_FILTER"
      start=$(now)
      # shellcheck disable=SC2086 # TESTS_ARGS and TESTS_FILTER are word lists
      JKRBEM_REQUIRE_GPU=1 timeout -k 10 "$lim" "$exe" --test-threads 4 $TESTS_ARGS $TESTS_FILTER >"$OUT/test-$name.txt" 2>&1
      rc=$?
      wall=$(since "$start")
      result=$(grep -E '^test result' "$OUT/test-$name.txt" | tail -n 1)
      [ "$rc" = 124 ] || [ "$rc" = 137 ] && result="cut at its limit ($(grep -cE ' \.\.\. ok$' "$OUT/test-$name.txt") passed so far)"
      say "| $name | ${result:-exit $rc, no result line} (exit $rc) | $wall |"
      grep -E '^test .* FAILED$|^test .*\.\.\. FAILED' "$OUT/test-$name.txt" | head -n 20 | sed 's/^/  - /' >>"$BODY"
      cat "$OUT/test-$name.txt" >>"$LOG"
    done
    [ "$ran" = 1 ] || say "| gpu | **no test binary found** (package with benches/device-package.sh) | — |"
    say ""
    ;;
  accuracy)
    say "## \`--accuracy ${ACCURACY_TARGET}\` on the GPU (limit ${ACCURACY_LIMIT_S} s each)"
    say ""
    IFS=',' read -r -a ratios <<<"$ACCURACY_RATIOS"
    for r in "${ratios[@]}"; do
      lim=$(budget "$ACCURACY_LIMIT_S" 15)
      if [ "$lim" = 0 ]; then say "- R1/R2 = $r: skipped ($(left_s) s left)"; continue; fi
      stem=$OUT/accuracy-r$r
      log "accuracy R1/R2 = $r (limit $lim s)"
      start=$(now)
      # --time-limit lets the run stop by itself, with its summary, before the hard limit.
      limited $((lim + 10)) "$BIN" simulate --ratio "$r" --accuracy "$ACCURACY_TARGET" --backend gpu \
        --time-limit "${lim}s" --out "$stem.csv" --summary "$stem.json"
      rc=$?
      "${REPORTER[@]}" accuracy "$stem" "$r" "$rc" "$(since "$start")" >>"$BODY" 2>>"$LOG"
    done
    say ""
    ;;
  *)
    say "(unknown step $step: skipped)"
    log "unknown step $step"
    ;;
  esac
done
[ -n "$VKFFT_BUILD" ] && kill "$VKFFT_BUILD" 2>/dev/null

# The report: the header, the headline and targets, then every step's table.
{
  cat "$HEADER"
  echo "## Headline"
  echo ""
  "${REPORTER[@]}" headline "$OUT" 2>>"$LOG"
  echo ""
  cat "$BODY"
  echo "Session wall time: $(($(date +%s) - T0)) s of ${SESSION_LIMIT_S} s."
} >"$REPORT.tmp" && mv -f "$REPORT.tmp" "$REPORT"
rm -rf "$VKFFT_SITE" "$BODY" "$HEADER"
cat "$REPORT"
# A device call brings back a few files only: keep the report and the log, pack the rest.
(cd "$OUT" && find . -maxdepth 1 -type f ! -name report.md ! -name log.txt ! -name results.tar.gz -printf '%P\n' |
  tar czf results.tar.gz -T - --remove-files 2>/dev/null)
exit 0
