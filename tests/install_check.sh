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
# The scratch prefix as the .pc file's prefix, its blanks and backslashes escaped (pkg-config
# splits values at blanks); pkg-config's output is then shell words, read back with eval.
pc="$work/prefix/lib/pkgconfig/sgapi.pc"
{
    printf 'prefix=%s\n' "$(printf '%s' "$work/prefix" | sed 's/[\\ ]/\\&/g')"
    grep -v '^prefix=' "$pc"
} >"$pc.new"
mv "$pc.new" "$pc"
flags=$(PKG_CONFIG_PATH="$work/prefix/lib/pkgconfig" pkg-config --cflags --libs --static sgapi)
eval "set -- $flags"
cc -std=c11 "$src/tests/consumer/main.c" -o "$work/consumer_pc" "$@"
LD_LIBRARY_PATH="$work/prefix/lib" "$work/consumer_pc"
