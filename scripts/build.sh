#!/usr/bin/env bash
# gaitlab build: the same C++ tree twice, natively (CMake + Ninja) and as threaded WebAssembly
# (Emscripten). Ninja rebuilds only what changed, so a second run with nothing changed is a no-op.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/lib.sh

if [ ! -f build/native/build.ninja ]; then
  say "configuring the native build"
  cmake -S native -B build/native -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
say "building native (build/native)"
ninja -C build/native || fail "native build failed"

if [ ! -f build/wasm/build.ninja ]; then
  say "configuring the WebAssembly build"
  emcmake cmake -S native -B build/wasm -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
say "building WebAssembly (build/wasm)"
ninja -C build/wasm || fail "WebAssembly build failed"

# The web page as static files (build/web): what a static host serves. Vite rebuilds it in about
# a second; the dev server (npm start) does not need it.
say "building the web page (build/web)"
npx --no-install vite build -c web/vite.config.ts --logLevel warn || fail "web build failed"
