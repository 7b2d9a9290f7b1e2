#!/usr/bin/env bash
# Installs a build into a scratch prefix and builds examples/minimal (C++) and examples/c (C99)
# against it, once through find_package(bmfr) and once through pkg-config, and runs them.
#   consumer_test.sh BUILD_DIR SOURCE_DIR SCRATCH [--shared]
# With --shared, BUILD_DIR is configured as a shared-library build of the library alone first,
# and the library must export the public API only.
set -euo pipefail
build=$1 src=$2 scratch=$3 mode=${4:-}
rm -rf "$scratch"
mkdir -p "$scratch"
prefix=$scratch/prefix
if [ "$mode" = --shared ]; then
    cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=Release -DBUILD_SHARED_LIBS=ON \
          -DBMFR_BUILD_TESTS=OFF -DBMFR_PYTHON=OFF > "$scratch/configure.log"
    cmake --build "$build" --target bmfr_library -j "$(nproc)" > "$scratch/build.log"
    cmake --install "$build" --prefix "$prefix" --component library > /dev/null
else
    cmake --install "$build" --prefix "$prefix" > /dev/null
fi

# 1. CMake: find_package(bmfr 0.3 REQUIRED) and bmfr::bmfr.
cmake -S "$src/examples/minimal" -B "$scratch/cmake-build" -DCMAKE_PREFIX_PATH="$prefix" \
      -DCMAKE_BUILD_TYPE=Release > "$scratch/consumer-configure.log"
cmake --build "$scratch/cmake-build" > "$scratch/consumer-build.log"
LD_LIBRARY_PATH="$prefix/lib" "$scratch/cmake-build/denoise_one_frame"

# The C example the same way, a C99 program.
cmake -S "$src/examples/c" -B "$scratch/cmake-build-c" -DCMAKE_PREFIX_PATH="$prefix" \
      -DCMAKE_BUILD_TYPE=Release > "$scratch/consumer-c-configure.log"
cmake --build "$scratch/cmake-build-c" > "$scratch/consumer-c-build.log"
LD_LIBRARY_PATH="$prefix/lib" "$scratch/cmake-build-c/denoise_frame"

# 2. pkg-config, with nothing but the installed prefix on the include and library paths.
pcdir=$(dirname "$(find "$prefix" -name bmfr.pc | head -1)")
flags=$(PKG_CONFIG_PATH="$pcdir" pkg-config --cflags --libs bmfr)
c++ -o "$scratch/pc-example" "$src/examples/minimal/denoise_one_frame.cpp" $flags
LD_LIBRARY_PATH="$prefix/lib" "$scratch/pc-example"
# bmfr.pc's flags are the C++ API's (-std=c++20): a C compile leaves that one out.
cflags=$(PKG_CONFIG_PATH="$pcdir" pkg-config --cflags bmfr | sed 's/-std=c++[0-9]*//')
cc -std=c99 -pedantic -Wall -Werror -c "$src/examples/c/denoise_frame.c" -o "$scratch/pc-c.o" \
   $cflags
c++ -o "$scratch/pc-c-example" "$scratch/pc-c.o" $flags -lm
LD_LIBRARY_PATH="$prefix/lib" "$scratch/pc-c-example"
echo "pkg-config: $(PKG_CONFIG_PATH="$pcdir" pkg-config --modversion bmfr)"

# The installed headers stand alone: nothing under include/ reaches into src/.
if grep -rn '#include "' "$prefix/include/bmfr"; then
    echo "installed headers include private files" >&2
    exit 1
fi

if [ "$mode" = --shared ]; then
    "$(dirname "$0")/check_exports.sh" "$(find "$prefix" -name 'libbmfr.so.*' | head -1)"
fi
echo "consumer test passed"
