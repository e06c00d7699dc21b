#!/usr/bin/env bash
# The README's main job: install the Debian packages, build the `rangefit` tool (Release) and
# detect the bore in the shipped example scan from its CAD prior, printing the pose.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DRANGEFIT_BUILD_TESTS=OFF \
  -DRANGEFIT_BUILD_BENCHMARKS=OFF
cmake --build build -j"$(nproc)" --target rangefit
# CAD prior of data/examples/README.md; the true bore: entrance (120, -40, 300) mm,
# axis (0.5000, -0.2962, 0.8138), radius 5 mm.
build/daemon/rangefit bore --cloud data/examples/bore_plate_r5.ply \
  --cad-entrance 120.3,-40.2,300.1 --cad-axis 0.5,-0.32,0.81 --cad-radius 5 \
  --cad-plane-normal 0,-0.342,0.94 --view-dir 0.8192,-0.1962,0.5390
