#!/usr/bin/env bash
# Install what aster-rs needs on a fresh Debian (12+) machine: a Rust
# toolchain if none is on PATH, the HDF5 library the MED layer links against,
# and the reference MED tools the tests compare our files with.
# Idempotent; run as root or with sudo available.
set -euo pipefail

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi

packages=(pkg-config libhdf5-dev libmed-tools python3-med python3-h5py)
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
