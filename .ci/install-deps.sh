#!/usr/bin/env bash
# Installs the Debian packages railwear needs to build, test and plot. Idempotent: packages that
# are already installed are left as they are. Run as root (or with sudo available).
set -euo pipefail
packages=(
  cmake gcc g++ make python3-dev pybind11-dev python3-numpy valgrind
  libeigen3-dev libgsl-dev libfftw3-dev pkg-config libceres-dev libsqlite3-dev sqlite3
  libcli11-dev libtomlplusplus-dev nlohmann-json3-dev libspdlog-dev libfmt-dev
  libgtest-dev libbenchmark-dev gnuplot-nox
  libopenmpi-dev openmpi-bin
  slurmctld slurmd slurm-client munge
  calculix-ccx gmsh
)
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages already installed"
  exit 0
fi
echo "install-deps: installing ${missing[*]}"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
