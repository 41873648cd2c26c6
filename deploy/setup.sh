#!/usr/bin/env bash
# Installs Rupture's build and run dependencies from Debian 12 packages (needs root or sudo).
set -euo pipefail
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
PACKAGES=(build-essential cmake pkg-config curl python3 python3-yaml
          libeigen3-dev libcpp-httplib-dev nlohmann-json3-dev libsqlite3-dev
          libhdf5-dev hdf5-tools libgtest-dev libgmock-dev
          librsvg2-dev fonts-dejavu-core)
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
echo "dependencies installed"
