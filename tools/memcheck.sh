#!/bin/sh
# Renders every scene file of scenes/ with BUILD_DIR's sgapi-render under valgrind memcheck. Any memory error
# or definite/indirect leak fails the run (exit 1); the images go to a scratch folder.
#
#   tools/memcheck.sh BUILD_DIR
set -eu
build=${1:?usage: tools/memcheck.sh BUILD_DIR}
src=$(cd "$(dirname "$0")/.." && pwd)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

valgrind --error-exitcode=1 --leak-check=full --errors-for-leak-kinds=definite,indirect \
    "$build/apps/sgapi-render" "$src"/scenes/*.json -o "$out"
