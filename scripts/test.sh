#!/usr/bin/env bash
# Configures, builds and runs every test (ctest). Extra arguments go to cmake's
# configure step, e.g. -DVIO_WERROR=ON as CI does.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "$@"
cmake --build build -j2
ctest --test-dir build --output-on-failure -j2
