# Shared set-up for scripts/test and scripts/demo (sourced, not run): installs the
# Debian packages fastnorm needs when missing (as root, or through sudo), then
# configures a build directory. Usage: fastnorm_configure BUILD_DIR [cmake options…]
set -euo pipefail

fastnorm_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
fastnorm_packages=(cmake g++ gfortran libeigen3-dev catch2
  python3-dev pybind11-dev python3-numpy python3-matplotlib python3-pytest python3-pip python3-setuptools
  python3-distributed python3-xarray python3-netcdf4 netcdf-bin)

fastnorm_install_packages() {
  local missing=()
  for package in "${fastnorm_packages[@]}"; do
    dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" ||
      missing+=("$package")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "fastnorm: installing Debian packages: ${missing[*]}"
  local as_root=()
  if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null || { echo "fastnorm: need root or sudo to install ${missing[*]}" >&2; exit 1; }
    as_root=(sudo)
  fi
  "${as_root[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${as_root[@]}" apt-get install -y -qq "${missing[@]}"
}

fastnorm_configure() {
  local build_dir=$1
  shift
  fastnorm_install_packages
  cmake -S "$fastnorm_root" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release "$@"
}

fastnorm_jobs=$(nproc 2>/dev/null || echo 2)
