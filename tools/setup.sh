# Sourced by tools/test, tools/run and tools/bench: installs the Debian packages
# the project needs (only what is missing), then configures and builds into build/.
# Environment: TAEBP_BUILD_DIR (default build), TAEBP_JOBS (default nproc),
# TAEBP_CMAKE_ARGS (more cmake -D options), CI=true turns warnings into errors.

TAEBP_ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
export SUMO_HOME=${SUMO_HOME:-/usr/share/sumo}

# Package -> why it is here: see README.md, "Dependencies".
TAEBP_PACKAGES=(
  build-essential cmake pkg-config
  sumo sumo-tools
  libeigen3-dev libyaml-cpp-dev libcli11-dev nlohmann-json3-dev libboost-dev
  libglpk-dev libgtest-dev libgmock-dev
  openmpi-bin libopenmpi-dev
  python3 python3-matplotlib
  xvfb xauth
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

taebp_install_packages() {
  local missing optional
  mapfile -t missing < <(taebp_missing_packages "${TAEBP_PACKAGES[@]}")
  mapfile -t optional < <(taebp_missing_packages "${TAEBP_OPTIONAL_PACKAGES[@]}")
  ((${#missing[@]} + ${#optional[@]} == 0)) && return 0
  local sudo=()
  [[ $(id -u) -ne 0 ]] && sudo=(sudo)
  local apt=("${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get)
  echo "taebp: installing missing Debian packages: ${missing[*]} ${optional[*]}" >&2
  "${apt[@]}" update -qq
  if ((${#missing[@]} > 0)); then
    "${apt[@]}" install -y -qq --no-install-recommends "${missing[@]}"
  fi
  if ((${#optional[@]} > 0)); then
    "${apt[@]}" install -y -qq --no-install-recommends "${optional[@]}" ||
      echo "taebp: warning: could not install ${optional[*]}: the tests that need them skip" >&2
  fi
}

taebp_build() {
  local build=${TAEBP_BUILD_DIR:-$TAEBP_ROOT/build}
  local werror=OFF
  [[ ${CI:-} == true ]] && werror=ON
  # TAEBP_CMAKE_ARGS: more -D options (tools/test --sanitize: -DTAEBP_SANITIZE=ON).
  # shellcheck disable=SC2086
  cmake -S "$TAEBP_ROOT" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTAEBP_WERROR=$werror \
    ${TAEBP_CMAKE_ARGS:-} >/dev/null
  cmake --build "$build" -j "${TAEBP_JOBS:-$(nproc)}"
}

taebp_setup() {
  taebp_install_packages
  taebp_build
}
