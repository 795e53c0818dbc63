# Sourced by tools/test, tools/run, tools/bench and tools/docs: installs the
# Debian packages the project needs (only what is missing), then configures and
# builds into build/. Progress goes to stderr.
# Environment: TAEBP_BUILD_DIR (default build), TAEBP_JOBS (default nproc),
# TAEBP_CMAKE_ARGS (more cmake -D options), CI=true turns warnings into errors.

TAEBP_ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
export SUMO_HOME=${SUMO_HOME:-/usr/share/sumo}
TAEBP_BUILD=${TAEBP_BUILD_DIR:-$TAEBP_ROOT/build}
# Debian's interpreter (the python3-* packages belong to it), not a pyenv or
# venv python3 earlier on PATH.
TAEBP_PYTHON=/usr/bin/python3

# Package -> why it is here: see docs/dependencies.md, "Dependencies and why".
TAEBP_PACKAGES=(
  build-essential cmake pkg-config
  sumo sumo-tools
  libeigen3-dev libyaml-cpp-dev libcli11-dev nlohmann-json3-dev libboost-dev
  libglpk-dev libgtest-dev libgmock-dev libpugixml-dev
  openmpi-bin libopenmpi-dev
  python3 python3-dev python3-pybind11 python3-numpy python3-pandas python3-pytest
  python3-matplotlib python3-pil python3-seaborn
  xvfb xauth
  doxygen mkdocs mkdocs-material
  strace
)
# Wanted but not required: when they cannot be installed, a warning, and the
# tests that need them say that they skip. slurm-wlm + munge: the real
# single-node Slurm cluster of `ctest -R slurm.real` (~20 s to install; in a
# container policy-rc.d keeps their services from starting; on a systemd
# machine slurmctld/slurmd stay idle without /etc/slurm/slurm.conf).
TAEBP_OPTIONAL_PACKAGES=(slurm-wlm munge)

taebp_missing_packages() {
  local p
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || echo "$p"
  done
}

taebp_say() { echo "taebp: $*" >&2; }

taebp_install_packages() {
  local missing optional
  mapfile -t missing < <(taebp_missing_packages "${TAEBP_PACKAGES[@]}")
  mapfile -t optional < <(taebp_missing_packages "${TAEBP_OPTIONAL_PACKAGES[@]}")
  ((${#missing[@]} + ${#optional[@]} == 0)) && return 0
  local sudo=()
  [[ $(id -u) -ne 0 ]] && sudo=(sudo)
  local apt=("${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get)
  taebp_say "installing missing Debian packages (first time: a few minutes): ${missing[*]} ${optional[*]}"
  "${apt[@]}" update -qq
  if ((${#missing[@]} > 0)); then
    "${apt[@]}" install -y -qq --no-install-recommends "${missing[@]}"
  fi
  if ((${#optional[@]} > 0)); then
    "${apt[@]}" install -y -qq --no-install-recommends "${optional[@]}" ||
      echo "taebp: warning: could not install ${optional[*]}: the tests that need them skip" >&2
  fi
}

taebp_configure() {
  local werror=OFF
  [[ ${CI:-} == true ]] && werror=ON
  local build=${TAEBP_BUILD_DIR:-$TAEBP_ROOT/build}
  if [[ ! -f $build/CMakeCache.txt ]]; then
    taebp_say "configuring $build (first time)"
  fi
  # TAEBP_CMAKE_ARGS: more -D options (tools/test --sanitize: -DTAEBP_SANITIZE=ON).
  # shellcheck disable=SC2086
  cmake -S "$TAEBP_ROOT" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTAEBP_WERROR=$werror \
    ${TAEBP_CMAKE_ARGS:-} >/dev/null
}

# taebp_build [TARGET...]: builds the targets (default: everything), with
# cmake's [NN%] progress lines; the first full build takes several minutes on
# 2 cores, later ones only rebuild what changed.
taebp_build() {
  taebp_configure
  local build=${TAEBP_BUILD_DIR:-$TAEBP_ROOT/build}
  local args=()
  (($# > 0)) && args=(--target "$@")
  if [[ ! -x $build/taebp ]]; then
    taebp_say "building ${*:-everything} (first time: several minutes on 2 cores)"
  fi
  cmake --build "$build" -j "${TAEBP_JOBS:-$(nproc)}" "${args[@]}" >&2
}

taebp_setup() {
  taebp_install_packages
  taebp_build "$@"
}
