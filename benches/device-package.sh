#!/usr/bin/env bash
# Package a device session: what a GPU machine with no Rust toolchain and no network needs to
# run `benches/device-session.sh` the first time.
#
#     benches/device-package.sh            # build, strip and copy; fetch the Vulkan loader
#
# Writes, into two folders that .gitignore keeps out of commits (both travel to the device
# machine when named as carried paths):
#   device-pack/jkrbem        the CLI, stripped (release build)
#   device-pack/tests/gpu     the `gpu` test binary, stripped (its tests find the CLI at the
#                             path they were built with: device-pack/built-at, which the
#                             session script links to device-pack/jkrbem)
#   device-pack/built-at      that path
#   device-pack/commit        the commit packaged (with "+ uncommitted changes" if any), for the
#                             report where .git does not travel
#   .gl/*.deb                 Debian's Vulkan / GL loader packages (libvulkan1, libegl1,
#                             libglvnd0, libopengl0, libgl1, libglx0, libgles2), unpacked by the
#                             session script's preflight where the machine has no libvulkan
# then prints the two device commands of docs/gpu.md ("The device session").
#
# Environment:
#   PACK             the package folder (default device-pack)
#   GL_DIR           the loader folder (default .gl); FETCH_LOADERS=0 skips fetching it
#   JKRBEM_EXE, GPU_TEST_EXE
#                    take these already-built binaries instead of building (the slow tier's
#                    dry run, which cannot run cargo inside cargo test)
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$(pwd)
PACK=${PACK:-device-pack}
GL_DIR=${GL_DIR:-.gl}

if [ -z "${JKRBEM_EXE:-}" ] || [ -z "${GPU_TEST_EXE:-}" ]; then
  echo "building (release) ..." >&2
  cargo build --release >&2
  # The test build may rebuild target/release/jkrbem (the path compiled into the tests), so the
  # CLI is copied after it.
  GPU_TEST_EXE=$(cargo test --release --no-run --test gpu --message-format=json 2>/dev/null |
    python3 -c 'import json, sys
for line in sys.stdin:
    m = json.loads(line)
    if m.get("reason") == "compiler-artifact" and m.get("executable") and m["target"]["name"] == "gpu":
        print(m["executable"])' | tail -n 1)
  JKRBEM_EXE=$ROOT/target/release/jkrbem
fi
[ -x "$JKRBEM_EXE" ] || { echo "device-package: no jkrbem binary at $JKRBEM_EXE" >&2; exit 1; }
[ -x "$GPU_TEST_EXE" ] || { echo "device-package: no gpu test binary at '$GPU_TEST_EXE'" >&2; exit 1; }

mkdir -p "$PACK/tests"
PACK=$(cd "$PACK" && pwd)
# Copy to a temporary name, then rename: a package folder is never left half-written.
for pair in "$JKRBEM_EXE:$PACK/jkrbem" "$GPU_TEST_EXE:$PACK/tests/gpu"; do
  src=${pair%%:*}
  dst=${pair#*:}
  cp "$src" "$dst.tmp"
  strip "$dst.tmp" 2>/dev/null || echo "device-package: strip failed for $dst (kept unstripped)" >&2
  mv -f "$dst.tmp" "$dst"
done
echo "$JKRBEM_EXE" >"$PACK/built-at"
commit=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
git diff --quiet HEAD 2>/dev/null || commit="$commit + uncommitted changes"
echo "$commit" >"$PACK/commit"
date -u '+%Y-%m-%d %H:%M UTC' >"$PACK/packaged-at"

if [ "${FETCH_LOADERS:-1}" != 0 ]; then
  if ls "$GL_DIR"/libvulkan1_*.deb >/dev/null 2>&1; then
    echo "loader packages already in $GL_DIR" >&2
  else
    mkdir -p "$GL_DIR" /tmp/amd64/partial
    o=(-oAPT::Architecture=amd64 -oAPT::Architectures=amd64 -oDir::State::Lists=/tmp/amd64)
    apt-get "${o[@]}" update -qq >&2
    (cd "$GL_DIR" && apt-get "${o[@]}" download libvulkan1 libegl1 libglvnd0 libopengl0 libgl1 \
      libglx0 libgles2 >&2)
  fi
fi

size=$(du -sm "$PACK" | cut -f1)
gl_size=$(du -sm "$GL_DIR" 2>/dev/null | cut -f1 || echo 0)
echo "packaged $commit into $PACK (${size} MB) and $GL_DIR (${gl_size:-0} MB); 64 MiB may travel in all"
cat <<EOF

Device commands (docs/gpu.md, "The device session"); carry: ["$(basename "$PACK")", "$GL_DIR"]

1. timeout_s 540:
   JKRBEM_BIN_DIR=$(basename "$PACK") SESSION_LIMIT_S=525 benches/device-session.sh devices measure bench floors parity
2. at once, while the machine is warm; SESSION_LIMIT_S = the device time left less 30 s:
   JKRBEM_BIN_DIR=$(basename "$PACK") SESSION_LIMIT_S=<left> TESTS_ARGS=--include-ignored benches/device-session.sh accuracy curve tests
EOF
