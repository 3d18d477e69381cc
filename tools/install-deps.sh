#!/usr/bin/env bash
# Install the Debian 12 packages rockdem needs, only those that are missing. Needs root (or sudo).
set -eu
pkgs="build-essential pkg-config libhdf5-dev libgsl-dev libsundials-dev libcmocka-dev libqhull-dev hdf5-tools
      python3-h5py python3-numpy python3-scipy python3-matplotlib python3-pil python3-statsmodels
      python3-xarray python3-h5netcdf python3-venv python3-pip python3-setuptools
      python3-wheel python3-build python3-pytest python3-pandas
      hdf5-filter-plugin-blosc-serial
      libopenmpi-dev openmpi-bin clang-format"  # BLOSC: FEMA P695 sets (src/records/record_fema.c); MPI: make mpi; pytest: tests/cli/pytest.sh;
                   # build, wheel: pip install ./tools and its sdist (docs/PYTHON.md); clang-format: tests/cli/format.sh
missing=""
for p in $pkgs; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
[ -z "$missing" ] && exit 0
echo "rockdem: installing missing packages:$missing"
sudo=""
[ "$(id -u)" -ne 0 ] && sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
# shellcheck disable=SC2086
$sudo apt-get install -y -qq --no-install-recommends $missing
