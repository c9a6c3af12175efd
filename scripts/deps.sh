#!/usr/bin/env bash
# Install the system packages SkyForge needs, when they are missing:
#   libhdf5-dev, pkg-config  (HDF5 output through the hdf5-metno crate)
#   plus any packages named as arguments (scripts/test.sh adds gnss-sdr and rtklib, the
#   third-party programs of the interoperability tests)
# Uses apt-get (Debian/Ubuntu) and needs root or sudo. Prints what it does.
set -euo pipefail

missing=()
dpkg -s libhdf5-dev >/dev/null 2>&1 || missing+=(libhdf5-dev)
command -v pkg-config >/dev/null 2>&1 || missing+=(pkg-config)
for pkg in "$@"; do
  dpkg -s "$pkg" >/dev/null 2>&1 || missing+=("$pkg")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "deps: system packages present"
  exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null 2>&1 || { echo "deps: need root to install: ${missing[*]}" >&2; exit 1; }
  sudo="sudo"
fi
echo "deps: installing ${missing[*]} with apt-get"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y --no-install-recommends "${missing[@]}"
