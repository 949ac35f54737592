# Shared by figures.sh and test.sh (sourced, not run): install the Debian packages that are
# missing, configure (Release) and build.  Every step is skipped or incremental when there is
# nothing to do, so a second run takes seconds.
#
# Environment: BUILD_DIR  the build directory (default: build/ in the source tree)
#              JOBS       parallel build and test jobs (default: the number of cores)

SPH_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
SPH_BUILD_DIR="${BUILD_DIR:-$SPH_ROOT/build}"
SPH_JOBS="${JOBS:-$(nproc 2>/dev/null || echo 2)}"

# What the build needs beyond git, cmake and g++ (make: cmake only recommends it).
SPH_PACKAGES=(make pkg-config libeigen3-dev libpng-dev libfreetype-dev fonts-dejavu-core
              libosmesa6-dev libcli11-dev catch2 doxygen libjs-mathjax clang-format)

sph_step() { printf '\n==> %s\n' "$*"; }

# ---- 1. Packages: ask dpkg what is missing; run apt-get only if something is ----------------
sph_install_packages() {
  if ! command -v dpkg-query >/dev/null 2>&1; then
    echo "Not a Debian system: make sure these (or their equivalents) are installed:"
    echo "  ${SPH_PACKAGES[*]}"
    return 0
  fi
  local missing=() package
  for package in "${SPH_PACKAGES[@]}"; do
    local status
    status="$(dpkg-query -W -f='${Status}' "$package" 2>/dev/null || true)"
    if [[ "$status" != "install ok installed" ]]; then
      missing+=("$package")
    fi
  done
  if ((${#missing[@]} == 0)); then
    return 0
  fi
  sph_step "Installing ${missing[*]}"
  local sudo=()
  if ((EUID != 0)); then
    if ! command -v sudo >/dev/null 2>&1; then
      echo "error: these packages are missing and this is not root (and there is no sudo):" >&2
      echo "  apt-get install --no-install-recommends ${missing[*]}" >&2
      return 1
    fi
    sudo=(sudo)
  fi
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -q || return 1
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -q \
    --no-install-recommends -o Dpkg::Use-Pty=0 "${missing[@]}" || return 1
}

# ---- 2. Configure: cheap when nothing changed; new chapters are found here -------------------
sph_configure() {
  sph_step "Configuring $SPH_BUILD_DIR (Release)"
  cmake -S "$SPH_ROOT" -B "$SPH_BUILD_DIR" -DCMAKE_BUILD_TYPE=Release || return 1
}

# ---- 3. Build: everything (libraries, chapters, tests, tools), incrementally -----------------
sph_build() {
  sph_step "Building with $SPH_JOBS jobs"
  cmake --build "$SPH_BUILD_DIR" -j "$SPH_JOBS" || return 1
}

sph_setup() {
  sph_install_packages || return 1
  sph_configure || return 1
  sph_build || return 1
}
