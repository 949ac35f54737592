#!/usr/bin/env bash
# The main job: install what is missing, build, run every chapter at full resolution (figures,
# console output and summary in figures/NN-name/), build the documentation (build/docs/html),
# and end with the summary table: chapter, figures written, wall time, error against the
# reference.  Exits non-zero if a chapter or the documentation failed.
#
#   bash scripts/figures.sh            every chapter
#   bash scripts/figures.sh 03 04      only the chapters whose names start so (and the docs)
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
sph_setup

status=0
sph_step "Running the chapters"
SPH_ONLY="$*" cmake --build "$SPH_BUILD_DIR" --target figures -j "$SPH_JOBS" || status=1

sph_step "Building the documentation"
cmake --build "$SPH_BUILD_DIR" --target docs || status=1

sph_step "Summary"
if [[ -f "$SPH_BUILD_DIR/figures-log/summary.txt" ]]; then
  cat "$SPH_BUILD_DIR/figures-log/summary.txt"
fi
echo "Figures:       $SPH_ROOT/figures/"
echo "Documentation: $SPH_BUILD_DIR/docs/html/index.html"
exit "$status"
