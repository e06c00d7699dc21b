#!/usr/bin/env bash
# The README's main command: installs the Debian packages, builds rangefitd and the `rangefit`
# client (Release), then runs rangefitd on the simulated cell and sends it a bore request and an
# object request over DDS, printing both results (scripts/demo_daemon.sh). Exits non-zero when
# either request fails. Usage: bash scripts/demo.sh [TIME_SCALE]  (1 = real pace, 0 = fastest)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DRANGEFIT_BUILD_TESTS=OFF \
  -DRANGEFIT_BUILD_BENCHMARKS=OFF
cmake --build build -j"$(nproc)" --target rangefitd rangefit
exec bash scripts/demo_daemon.sh "$PWD/build" "${1:-1}"
