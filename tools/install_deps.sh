#!/usr/bin/env bash
# Installs rbla's build and test dependencies from Debian 12 packages (nothing else is fetched).
# Skips apt entirely when everything is already there, so repeated runs are fast and offline.
set -euo pipefail
packages=(
  build-essential cmake pkg-config           # GCC 12, CMake 3.25
  libeigen3-dev                              # dense and sparse linear algebra
  libsuitesparse-dev libopenblas-dev         # CHOLMOD sparse Cholesky on an optimised BLAS
  libnlopt-dev                               # small outer optimisations (critical parameters)
  nlohmann-json3-dev libvalijson-dev         # JSON and JSON Schema validation
  libcli11-dev libgtest-dev                  # command line, tests
  python3                                    # sample generator and plugin core (standard library)
  coinor-clp                                 # independent LP solver for the cross-check scripts
  chromium                                   # headless browser for the viewer tests
  clang libclang-rt-14-dev                   # clang with libFuzzer and its sanitizer runtimes
                                             # (tools/fuzz.sh, tools/sanitize.sh)
)
# Node.js and npm (.3dm exchange with rhino3dm, the three.js viewer, their tests): any install on
# PATH will do; Debian's packages only when there is none.
command -v node >/dev/null || packages+=(nodejs)
command -v npm >/dev/null || packages+=(npm)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install_deps: all ${#packages[@]} packages present"
  exit 0
fi
sudo=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "install_deps: need root (or sudo) to install: ${missing[*]}" >&2; exit 1; }
  sudo="sudo"
fi
echo "install_deps: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
