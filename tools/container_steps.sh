#!/usr/bin/env bash
# The Containerfile's steps, also runnable on a Debian 12 host: the image runs this file, so a host
# run checks the image's recipe (all of it but FROM and COPY) where no registry can be reached.
#
#   tools/container_steps.sh packages   install the pinned list (tools/container/packages.txt),
#                                       then the rest (tools/setup.sh); check every pin
#   tools/container_steps.sh build      check every pin, configure, build, run every test, install,
#                                       and check the installed coinroll draws the tested pixels
#   tools/container_steps.sh            both
#
# COINROLL_BUILD_DIR (default build-container) keeps the host's own build/ untouched;
# COINROLL_PREFIX (default $COINROLL_BUILD_DIR/prefix) is where coinroll is installed: the image
# passes /usr/local, a host run installs inside its build directory.
set -euo pipefail
cd "$(dirname "$0")/.."

readonly list=tools/container/packages.txt
readonly build=${COINROLL_BUILD_DIR:-build-container}
readonly prefix=${COINROLL_PREFIX:-$build/prefix}

say() { echo "container_steps: $*" >&2; }

pins=()  # name=version, in the list's order
while IFS= read -r line || [ -n "$line" ]; do
  line=${line%%#*}
  line=${line//[[:space:]]/}
  [ -n "$line" ] || continue
  if [[ $line != ?*=?* ]]; then
    say "$list: '$line' is not name=version"
    exit 1
  fi
  pins+=("$line")
done <"$list"

# Fills `missing` with the pins not installed; a package installed at another version fails here,
# naming both versions. A host's Mesa or FFmpeg is never replaced behind its owner's back; a fresh
# image has none of them, so nothing fails there.
missing=()
find_missing_pins() {
  local pin name want have differ=0
  missing=()
  for pin in "${pins[@]}"; do
    name=${pin%%=*}
    want=${pin#*=}
    have=$(dpkg-query -W -f='${db:Status-Status} ${Version}' "$name" 2>/dev/null || true)
    if [[ $have != "installed "* ]]; then
      missing+=("$pin")
    elif [ "${have#installed }" != "$want" ]; then
      say "$name is ${have#installed } here, but $list pins $want"
      differ=1
    fi
  done
  if [ "$differ" -ne 0 ]; then
    say "install the pinned versions (apt-get install name=version)," \
        "or move the pins and remake the goldens"
    exit 1
  fi
}

check_pins() {
  find_missing_pins
  if [ ${#missing[@]} -ne 0 ]; then
    say "pinned but not installed: ${missing[*]}"
    exit 1
  fi
  say "all ${#pins[@]} pinned packages are installed at their pinned versions"
}

install_packages() {
  find_missing_pins
  if [ ${#missing[@]} -ne 0 ]; then
    # env after sudo: sudo drops the caller's environment, and a debconf question would hang a build.
    local apt=(env DEBIAN_FRONTEND=noninteractive apt-get)
    [ "$(id -u)" -eq 0 ] || apt=(sudo "${apt[@]}")
    say "installing ${missing[*]}"
    "${apt[@]}" update -qq
    # One call with every pin: apt resolves the exact-version dependencies among them together, and
    # a version the archive no longer has fails here by name.
    "${apt[@]}" install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  fi
  # The unpinned rest (compiler, CMake, libraries, Python for the checks) from the list the README's
  # setup uses. It skips what is installed, and it runs after the pins so that nothing it installs
  # brings in another Mesa or FFmpeg first; check_pins catches one brought in by an upgrade.
  tools/setup.sh
  check_pins
}

build_and_test() {
  check_pins
  # The README's test command (tools/test.sh) in a build directory of its own.
  cmake -B "$build"
  cmake --build "$build" -j"$(nproc)"
  ctest --test-dir "$build" --output-on-failure -j"$(nproc)"
  cmake --install "$build" --prefix "$prefix"

  # What a user's CI job does with the image: the installed coinroll, run from the prefix, must draw
  # the same pixels as the coinroll the tests just ran.
  local check="$build/container_check" still=(still examples/steady_circle.json --time 1.5
    --set render.width=320 --set render.height=180)
  mkdir -p "$check"
  "$build/coinroll" "${still[@]}" -o "$check/tested.png"
  "$prefix/bin/coinroll" "${still[@]}" -o "$check/installed.png"
  "$prefix/bin/coinroll" compare "$check/tested.png" "$check/installed.png"
  say "coinroll installed in $prefix draws the tested pixels"
}

case "${1:-all}" in
  packages) install_packages ;;
  build) build_and_test ;;
  all)
    install_packages
    build_and_test
    ;;
  *)
    say "unknown step '$1' (packages, build or nothing for both)"
    exit 2
    ;;
esac
