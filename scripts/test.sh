#!/usr/bin/env bash
# The tests: install what is missing, build, and run every test with ctest (the library tests,
# each chapter in --quick mode, and the documentation's no-warnings check).  Exits non-zero if
# anything fails.  Extra arguments go to ctest, e.g. `bash scripts/test.sh -R app` or `-L chapter`.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
sph_setup

sph_step "Testing"
ctest --test-dir "$SPH_BUILD_DIR" --output-on-failure -j "$SPH_JOBS" --no-tests=error "$@"
