#!/usr/bin/env bash
# gaitlab set-up: installs what is missing, and nothing else, so that a second run is a no-op.
#
#   1. Debian packages (emscripten, cmake, g++, ninja, GoogleTest, nlohmann-json, chromium, ...)
#   2. npm dependencies, from the committed package-lock.json
#   3. Bullet 3.24 source, from Debian's source package, verified by sha256
#
# Called by `npm start`, `npm test` and `npm run build`.
# `scripts/setup.sh bullet` runs only step 3 (the tests use it on a scratch folder).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/lib.sh
steps=${*:-packages npm bullet}
want() { [[ " $steps " == *" $1 "* ]]; }

# ---------------------------------------------------------------------------------------------
# 1. System packages. Each entry: the command (or file) that proves it is there, the Debian
#    package that provides it, and how to get it elsewhere.
# ---------------------------------------------------------------------------------------------
need=(
  "cmd:cmake|cmake|https://cmake.org/download/ (3.20 or newer)"
  "cmd:g++|g++|a C++17 compiler (g++ 10+ or clang 12+)"
  "cmd:ninja|ninja-build|https://ninja-build.org/"
  "cmd:emcc|emscripten|emsdk: https://emscripten.org/docs/getting_started/downloads.html (then 'source emsdk_env.sh')"
  "file:/usr/share/nodejs/acorn/package.json|node-acorn|comes with emsdk (Debian's emscripten needs node-acorn)"
  "file:/usr/src/googletest/CMakeLists.txt|googletest|https://github.com/google/googletest (set GTEST_ROOT)"
  "file:/usr/include/nlohmann/json.hpp|nlohmann-json3-dev|https://github.com/nlohmann/json (header only)"
  "file:/usr/include/eigen3/Eigen/Core|libeigen3-dev|https://eigen.tuxfamily.org (header only, 3.4)"
  "cmd:chromium|chromium|any Chromium/Chrome; set CHROMIUM=/path/to/chrome"
  "cmd:xz|xz-utils|xz (to unpack the Bullet tarball)"
  "cmd:curl|curl|curl (to fetch the Bullet tarball)"
)

missing_pkgs=()
missing_help=()
want packages || need=()
for entry in "${need[@]}"; do
  probe=${entry%%|*}; rest=${entry#*|}; pkg=${rest%%|*}; help=${rest#*|}
  case $probe in
    cmd:chromium) [ -n "${CHROMIUM:-}" ] && [ -x "${CHROMIUM}" ] && continue; have_cmd chromium && continue ;;
    cmd:emcc) have_cmd emcc && continue ;;
    cmd:*) have_cmd "${probe#cmd:}" && continue ;;
    file:*) [ -e "${probe#file:}" ] && continue ;;
  esac
  # emsdk users have acorn inside emsdk; only Debian's emcc needs node-acorn.
  if [ "$pkg" = node-acorn ] && have_cmd emcc && [ "$(readlink -f "$(command -v emcc)")" != /usr/share/emscripten/emcc.py ] \
     && [ "$(readlink -f "$(command -v emcc)")" != /usr/share/emscripten/emcc ]; then continue; fi
  missing_pkgs+=("$pkg"); missing_help+=("  - $pkg: $help")
done

if [ ${#missing_pkgs[@]} -gt 0 ]; then
  if [ "$(id -u)" = 0 ] && [ -f /etc/debian_version ] && have_cmd apt-get; then
    say "installing Debian packages: ${missing_pkgs[*]}"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    apt-get install -y -qq --no-install-recommends "${missing_pkgs[@]}" >/dev/null
  else
    why="not root"; [ -f /etc/debian_version ] || why="not a Debian system"
    fail "these tools are missing and cannot be installed automatically ($why):
$(printf '%s\n' "${missing_help[@]}")
On Debian/Ubuntu as root: apt-get install ${missing_pkgs[*]}"
  fi
fi

# ---------------------------------------------------------------------------------------------
# 2. npm dependencies: `npm ci` only when package-lock.json changed since the last install.
# ---------------------------------------------------------------------------------------------
lock_sum=$(sha256sum package-lock.json | cut -d' ' -f1)
if want npm && [ "$(cat node_modules/.gaitlab-lock-sha256 2>/dev/null || true)" != "$lock_sum" ]; then
  say "installing npm dependencies (npm ci)"
  npm ci --no-audit --no-fund --loglevel=error
  echo "$lock_sum" > node_modules/.gaitlab-lock-sha256
fi

# ---------------------------------------------------------------------------------------------
# 3. Bullet Physics 3.24, from Debian's source package (the +dfsg tarball drops only non-free
#    data files; all of src/ is there). Verified by sha256; a bad download is deleted.
# ---------------------------------------------------------------------------------------------
BULLET_TARBALL=bullet_3.24+dfsg.orig.tar.xz
BULLET_SHA256=43c1edae2024ba18bb5d7bfd3bb2394b066a79151a29789504a2d8efcdc333d7
THIRD_PARTY=${GAITLAB_THIRD_PARTY:-third_party}
BULLET_DIR=$THIRD_PARTY/bullet3
mkdir -p "$THIRD_PARTY"
if want bullet && [ ! -f "$BULLET_DIR/.verified" ]; then
  tarball=$THIRD_PARTY/$BULLET_TARBALL
  if [ ! -f "$tarball" ]; then
    # The mirror is the one this machine's apt already uses (Debian's pool layout is the same
    # on every mirror); BULLET_MIRROR overrides it.
    mirror=${BULLET_MIRROR:-$(debian_mirror)}
    [ -n "$mirror" ] || fail "cannot find a Debian mirror in /etc/apt/sources.list*; set BULLET_MIRROR=<mirror>/debian"
    url="$mirror/pool/main/b/bullet/$BULLET_TARBALL"
    say "fetching Bullet 3.24 source: $url"
    curl -fsSL --retry 3 -o "$tarball.part" "$url" || { rm -f "$tarball.part"; fail "download of $url failed"; }
    mv "$tarball.part" "$tarball"
  fi
  got=$(sha256sum "$tarball" | cut -d' ' -f1)
  if [ "$got" != "$BULLET_SHA256" ]; then
    rm -f "$tarball"
    fail "Bullet tarball checksum mismatch (corrupt or partial download), deleted it.
  expected $BULLET_SHA256
  got      $got
Run the command again to download it afresh."
  fi
  rm -rf "$BULLET_DIR" "$THIRD_PARTY/bullet3-3.24"
  tar -xJf "$tarball" -C "$THIRD_PARTY"
  mv "$THIRD_PARTY/bullet3-3.24" "$BULLET_DIR"
  echo "$BULLET_SHA256" > "$BULLET_DIR/.verified"
  say "Bullet 3.24 unpacked and verified in $BULLET_DIR"
fi
