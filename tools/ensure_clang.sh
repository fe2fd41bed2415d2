#!/usr/bin/env bash
# Installs clang and its sanitizer and libFuzzer runtimes (Debian's clang 14) when missing: the
# sanitizer and fuzz stages build with them, the README's commands do not need them.
set -euo pipefail
if command -v clang++ >/dev/null && dpkg-query -W -f='${Status}' libclang-rt-14-dev 2>/dev/null | grep -q "install ok installed"; then
  exit 0
fi
echo "ensure_clang: installing clang and its sanitizer runtimes" >&2
sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends clang libclang-rt-14-dev >/dev/null
