# Sourced by tools/test, tools/run and tools/bench: installs the Debian packages
# the project needs (only what is missing), then configures and builds into build/.
# Environment: TAEBP_BUILD_DIR (default build), TAEBP_JOBS (default nproc),
# CI=true turns warnings into errors.

TAEBP_ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
export SUMO_HOME=${SUMO_HOME:-/usr/share/sumo}

# Package -> why it is here: see README.md, "Dependencies".
TAEBP_PACKAGES=(
  build-essential cmake pkg-config
  sumo sumo-tools
  libeigen3-dev libyaml-cpp-dev libcli11-dev nlohmann-json3-dev libboost-dev
  libglpk-dev libgtest-dev libgmock-dev libpugixml-dev
  openmpi-bin libopenmpi-dev
  python3 python3-matplotlib
  xvfb xauth
)

taebp_install_packages() {
  local missing=() p
  for p in "${TAEBP_PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  ((${#missing[@]} == 0)) && return 0
  echo "taebp: installing missing Debian packages: ${missing[*]}" >&2
  local sudo=()
  [[ $(id -u) -ne 0 ]] && sudo=(sudo)
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -qq
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}"
}

taebp_build() {
  local build=${TAEBP_BUILD_DIR:-$TAEBP_ROOT/build}
  local werror=OFF
  [[ ${CI:-} == true ]] && werror=ON
  cmake -S "$TAEBP_ROOT" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTAEBP_WERROR=$werror >/dev/null
  cmake --build "$build" -j "${TAEBP_JOBS:-$(nproc)}"
}

taebp_setup() {
  taebp_install_packages
  taebp_build
}
