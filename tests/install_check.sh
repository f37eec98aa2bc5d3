#!/bin/sh
# Installs the built library into a scratch prefix and builds a user project against it, once
# through the CMake package config and once through pkg-config.
set -eu
build=$1
src=$2
work=$3
rm -rf "$work"
cmake --install "$build" --prefix "$work/prefix" >/dev/null
cmake -S "$src/tests/consumer" -B "$work/consumer" -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/consumer" >/dev/null
"$work/consumer/consumer_static"
LD_LIBRARY_PATH="$work/prefix/lib" "$work/consumer/consumer_shared"
sed -i "s|^prefix=.*|prefix=$work/prefix|" "$work/prefix/lib/pkgconfig/sgapi.pc"
flags=$(PKG_CONFIG_PATH="$work/prefix/lib/pkgconfig" pkg-config --cflags --libs --static sgapi)
# shellcheck disable=SC2086
cc -std=c11 "$src/tests/consumer/main.c" -o "$work/consumer_pc" $flags
LD_LIBRARY_PATH="$work/prefix/lib" "$work/consumer_pc"
