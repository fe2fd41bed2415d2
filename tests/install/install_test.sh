#!/usr/bin/env bash
# Installs coinroll from BUILD_DIR into a temporary prefix, then builds the consumer program
# against the installed package twice, with find_package and with pkg-config, and checks what
# it prints: the columns equal the CSV of the installed `coinroll simulate` (same scene, to the
# last digit), the still has the coin in it, a bad scene is refused. Also checks the man page
# and the bash completion that were installed, and the Python package where Debian's python3
# finds it, when the build has it.
# Usage: tests/install/install_test.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
source_dir=$1 build_dir=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
prefix=$work/prefix

cmake --install "$build_dir" --prefix "$prefix" >/dev/null
for file in bin/coinroll include/coinroll/coinroll.h lib/cmake/coinroll/coinrollConfig.cmake lib/pkgconfig/coinroll.pc \
            share/man/man1/coinroll.1 share/bash-completion/completions/coinroll; do
  [[ -e $prefix/$file ]] || { echo "not installed: $file"; exit 1; }
done
libdir=$(dirname "$(find "$prefix" -name 'libcoinroll.so' | head -1)")

cat > "$work/scene.json" <<'SCENE'
{"coin": {"shape": "disk", "radius": 0.0375, "mass": 0.4}, "initial": {"theta": 10, "omega_Z": 12},
 "duration": 0.5, "render": {"width": 160, "height": 120}}
SCENE
"$prefix/bin/coinroll" simulate "$work/scene.json" --sample-dt 0.05 --csv "$work/cli.csv" 2>/dev/null

check_consumer() {  # $1: how it was built, $2: the consumer binary
  LD_LIBRARY_PATH=$libdir "$2" "$work/scene.json" > "$work/out.txt"
  /usr/bin/python3 - "$work/cli.csv" "$work/out.txt" "$1" <<'PY'
import csv
import sys
cli, out, how = sys.argv[1:4]
rows = list(csv.DictReader(open(cli)))
lines = open(out).read().splitlines()
columns = [tuple(map(float, line.split(","))) for line in lines if line[0].isdigit() and "," in line]
assert len(columns) == len(rows) == 11, (len(columns), len(rows))
for (t, energy), row in zip(columns, rows):
    assert (t, energy) == (float(row["t"]), float(row["energy"])), (t, energy, row["t"], row["energy"])
still = next(line for line in lines if line.startswith("still "))
size, pixels = still.split()[1].rstrip(","), int(still.split()[2])
assert size == "160x120" and pixels > 500, still
assert any(line.startswith("bad scene refused: ") and "duration" in line for line in lines), lines[-1]
print(f"{how}: 11 rows equal to the CLI's CSV; {still}; {lines[-1]}")
PY
}

cmake -S "$source_dir/tests/install/consumer" -B "$work/consumer" -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
cmake --build "$work/consumer" >/dev/null
check_consumer "find_package" "$work/consumer/consumer"

pkg_config_path=$(dirname "$(find "$prefix" -name coinroll.pc)")
read -r -a flags <<< "$(PKG_CONFIG_PATH=$pkg_config_path pkg-config --cflags --libs coinroll)"
c++ "$source_dir/tests/install/consumer/main.cpp" "${flags[@]}" -o "$work/consumer_pc"
check_consumer "pkg-config" "$work/consumer_pc"

# The man page renders, and the completion offers a command's own options.
if command -v man >/dev/null; then
  man -l "$prefix/share/man/man1/coinroll.1" 2>/dev/null | grep -q "sweep-merge" || { echo "man page lacks sweep-merge"; exit 1; }
else  # a minimal system without man-db: the source at least
  grep -q '^\.SS sweep-merge' "$prefix/share/man/man1/coinroll.1" || { echo "man page lacks sweep-merge"; exit 1; }
fi
completed=$(bash -c 'source "$1"; COMP_WORDS=(coinroll sweep --sh); COMP_CWORD=2; _coinroll; echo "${COMPREPLY[*]}"' _ \
            "$prefix/share/bash-completion/completions/coinroll")
[[ $completed == "--shard" ]] || { echo "completion of 'coinroll sweep --sh' gave '$completed'"; exit 1; }
echo "man page and completion installed and working"

if [[ -f $build_dir/python/coinroll/__init__.py ]]; then
  PYTHONPATH=$prefix/lib/python3/dist-packages /usr/bin/python3 - "$work/scene.json" "$work/cli.csv" "$prefix" <<'PY'
import csv
import sys
import coinroll
scene, cli, prefix = sys.argv[1:4]
assert coinroll.__file__.startswith(prefix), coinroll.__file__
run = coinroll.simulate(scene, sample_dt=0.05)
rows = list(csv.DictReader(open(cli)))
assert [float(row["energy"]) for row in rows] == list(run["energy"])
print(f"python package installed: {coinroll.__file__}, {run.rows} rows equal to the CLI's CSV")
PY
fi
