# Shared helpers for gaitlab's shell scripts (sourced, not run).
say()  { printf '\033[1;34mgaitlab:\033[0m %s\n' "$*" >&2; }
fail() { printf '\033[1;31mgaitlab: error:\033[0m %s\n' "$*" >&2; exit 1; }
have_cmd() { command -v "$1" >/dev/null 2>&1; }

# The Debian archive this machine's apt uses, e.g. http://<mirror>/debian (no trailing slash).
debian_mirror() {
  local f
  for f in /etc/apt/sources.list.d/*.sources /etc/apt/sources.list /etc/apt/sources.list.d/*.list; do
    [ -f "$f" ] || continue
    grep -hoE '(URIs:|deb)[[:space:]]+(\[[^]]*\][[:space:]]+)?https?://[^[:space:]]+/debian/?([[:space:]]|$)' "$f" \
      | grep -oE 'https?://[^[:space:]]+' | sed 's:/$::' | head -n1 && return 0
  done | head -n1
}

# Debian's emscripten needs acorn from node-acorn for optimized links.
export NODE_PATH=${NODE_PATH:+$NODE_PATH:}/usr/share/nodejs
