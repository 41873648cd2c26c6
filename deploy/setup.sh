#!/usr/bin/env bash
# Installs Rupture's build and run dependencies from Debian 12 packages (needs root or sudo).
# Quiet: one line, apt's output goes to $RUPTURE_SETUP_LOG (default build/setup.log) and is shown
# only when apt fails. Extra packages can be named as arguments (e.g. paraview xvfb).
set -euo pipefail
cd "$(dirname "$0")/.."
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
PACKAGES=(build-essential cmake pkg-config curl python3 python3-yaml
          libeigen3-dev libcpp-httplib-dev nlohmann-json3-dev libsqlite3-dev
          libhdf5-dev hdf5-tools libgtest-dev libgmock-dev
          libcairo2-dev librsvg2-dev fonts-dejavu-core
          libopenmpi-dev openmpi-bin "$@")
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  log="${RUPTURE_SETUP_LOG:-build/setup.log}"
  mkdir -p "$(dirname "$log")"
  echo "== installing ${#missing[@]} Debian packages (${missing[*]}); log: $log"
  if ! { $SUDO apt-get update -qq &&
         DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"; } \
       > "$log" 2>&1; then
    tail -n 20 "$log" >&2
    echo "== apt-get failed; the whole log is in $log" >&2
    exit 1
  fi
fi
echo "== dependencies installed"
