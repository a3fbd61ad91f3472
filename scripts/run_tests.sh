#!/bin/bash
# README command 2: install, build, run the test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
cd build
# The default suite leaves out the label long (run it with
# `bash scripts/run_tests.sh -L long`, or `ctest -L long` in build/).
[ $# -eq 0 ] && set -- -LE long
ctest -j "$(nproc)" --output-on-failure "$@"
