# Sourced by tools/test, tools/run, tools/bench and tools/docs: installs the
# Debian packages the project needs (only what is missing), then configures and
# builds into build/. Progress goes to stderr.
# Environment: TAEBP_BUILD_DIR (default build), TAEBP_JOBS (default nproc),
# CI=true turns warnings into errors.

TAEBP_ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
export SUMO_HOME=${SUMO_HOME:-/usr/share/sumo}
TAEBP_BUILD=${TAEBP_BUILD_DIR:-$TAEBP_ROOT/build}
# Debian's interpreter (the python3-* packages belong to it), not a pyenv or
# venv python3 earlier on PATH.
TAEBP_PYTHON=/usr/bin/python3

# Package -> why it is here: see README.md, "Dependencies".
TAEBP_PACKAGES=(
  build-essential cmake pkg-config
  sumo sumo-tools
  libeigen3-dev libyaml-cpp-dev libcli11-dev nlohmann-json3-dev libboost-dev
  libglpk-dev libgtest-dev libgmock-dev libpugixml-dev
  openmpi-bin libopenmpi-dev
  python3 python3-dev python3-pybind11 python3-numpy python3-pandas python3-pytest
  python3-matplotlib python3-pil
  xvfb xauth
  doxygen
)

taebp_say() { echo "taebp: $*" >&2; }

taebp_install_packages() {
  local missing=() p
  for p in "${TAEBP_PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  ((${#missing[@]} == 0)) && return 0
  taebp_say "installing ${#missing[@]} missing Debian packages (first time: a few minutes): ${missing[*]}"
  local sudo=()
  [[ $(id -u) -ne 0 ]] && sudo=(sudo)
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -qq
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}"
}

taebp_configure() {
  local werror=OFF
  [[ ${CI:-} == true ]] && werror=ON
  if [[ ! -f $TAEBP_BUILD/CMakeCache.txt ]]; then
    taebp_say "configuring $TAEBP_BUILD (first time)"
  fi
  cmake -S "$TAEBP_ROOT" -B "$TAEBP_BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTAEBP_WERROR=$werror >/dev/null
}

# taebp_build [TARGET...]: builds the targets (default: everything), with
# cmake's [NN%] progress lines; the first full build takes several minutes on
# 2 cores, later ones only rebuild what changed.
taebp_build() {
  taebp_configure
  local args=()
  (($# > 0)) && args=(--target "$@")
  if [[ ! -x $TAEBP_BUILD/taebp ]]; then
    taebp_say "building ${*:-everything} (first time: several minutes on 2 cores)"
  fi
  cmake --build "$TAEBP_BUILD" -j "${TAEBP_JOBS:-$(nproc)}" "${args[@]}" >&2
}

taebp_setup() {
  taebp_install_packages
  taebp_build "$@"
}
