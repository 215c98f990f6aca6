#!/usr/bin/env bash
# Installs pcr's build and test dependencies from Debian's packages.
# Idempotent: does nothing (and needs no network) when everything is already installed.
# Works as root without sudo; uses sudo only when not root.
set -euo pipefail

packages=(
  cmake g++ make ninja-build pkg-config
  libeigen3-dev
  coinor-libipopt-dev
  libopenblas0-serial
  liburdfdom-dev
  libboost-test-dev
  libbenchmark-dev
  gnuplot-nox
  python3-dev pybind11-dev python3-numpy python3-pytest python3-matplotlib python3-distributed
)
# libopenblas0-serial: the BLAS and LAPACK behind Ipopt's MUMPS (Debian's alternatives pick it over the
# reference BLAS once installed; the serial build, so that it starts no threads of its own beside pcr's):
# the dense kernels of MUMPS's fronts were a quarter of a planar_rollers FK solve that ends in the energy
# minimisation (docs/design.md "Ipopt").
# Optional extras: clang for the libFuzzer target (PCR_EXTRA_PACKAGES="clang").
read -r -a extra <<< "${PCR_EXTRA_PACKAGES:-}"
packages+=("${extra[@]}")

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

as_root=()
[ "$(id -u)" -eq 0 ] || as_root=(sudo)
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${as_root[@]}" apt-get update -qq
"${as_root[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
