#!/usr/bin/env bash
# Install what aster-rs needs on a fresh Debian (12+) machine: a Rust
# toolchain if none is on PATH, the HDF5 library the MED layer links against,
# and the reference MED tools the tests compare our files with.
# Idempotent; run as root or with sudo available.
set -euo pipefail

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi

# HDF5 for the MED layer; the reference MED tools (mdump, medconforme, python3-med) and h5py the tests
# and benchmarks compare with; the shared libraries the gmsh wheel loads.
packages=(pkg-config libhdf5-dev libmed-tools python3-med python3-h5py
          libglu1-mesa libgl1 libxrender1 libxcursor1 libxfixes3 libxext6 libxft2 libfontconfig1 libxinerama1 libgomp1)
missing=()
for p in "${packages[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if ! command -v cargo >/dev/null 2>&1; then
  # Debian's own toolchain; a rustup toolchain already on PATH is preferred.
  missing+=(cargo rustc)
fi
if ! command -v cc >/dev/null 2>&1; then
  missing+=(build-essential)
fi
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup-debian: installing ${missing[*]}"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${missing[@]}" >/dev/null
else
  echo "setup-debian: all packages present"
fi

# meshio (and the h5py it needs) and gmsh for the interoperability tests, for the python3 first on PATH.
if ! python3 -c "import meshio, h5py, gmsh" >/dev/null 2>&1; then
  echo "setup-debian: installing meshio h5py gmsh with pip"
  python3 -m pip install -q meshio h5py gmsh 2>/dev/null \
    || python3 -m pip install -q --break-system-packages meshio h5py gmsh
fi
