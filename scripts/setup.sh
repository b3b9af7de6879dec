#!/usr/bin/env bash
# Installs the Debian 12 packages pkm needs to build, test and benchmark.
# Idempotent: prints nothing and changes nothing when every package is present.
# Usage: scripts/setup.sh        (run as root, or with sudo available)
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config clang lld
  libeigen3-dev libceres-dev libfmt-dev libcli11-dev nlohmann-json3-dev
  libgoogle-glog-dev libgflags-dev libsuitesparse-dev libatlas-base-dev libgfortran-12-dev
  libunwind-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  clang-format bc
  libboost-python1.74.0 libboost1.74-dev libsqlite3-dev
  chromium
  linuxcnc-uspace linuxcnc-uspace-dev
  libcpp-httplib-dev
  python3-numpy python3-scipy
  python3-dev pybind11-dev python3-pytest python3-matplotlib
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
# The npm packages of the HTML report (uPlot, playwright-core; docs/report.md) and of the web
# application (esbuild, three.js, Blockly, CodeMirror, uPlot; docs/web.md), from their lock files,
# when node_modules is missing or older than package-lock.json.
root="$(cd "$(dirname "$0")/.." && pwd)"
for dir in "$root/web/report" "$root/web/app"; do
  if [ ! -d "$dir/node_modules" ] || [ "$dir/package-lock.json" -nt "$dir/node_modules" ]; then
    echo "setup: npm ci in ${dir#$root/}"
    (cd "$dir" && npm ci --no-audit --no-fund >/dev/null && touch node_modules)
  fi
done

# LinuxCNC's rtapi_app refuses to run as root: the tests that start LinuxCNC run it as this
# unprivileged user (with a home folder, where LinuxCNC keeps its logs) when they run as root.
ensure_linuxcnc_user() {
  if [ "$(id -u)" -eq 0 ] && ! id pkm-linuxcnc >/dev/null 2>&1; then
    useradd --system --create-home --shell /usr/sbin/nologin pkm-linuxcnc
  fi
}

if [ ${#missing[@]} -eq 0 ]; then ensure_linuxcnc_user; exit 0; fi

echo "setup: installing missing packages: ${missing[*]}"
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then sudo_cmd=(sudo); else
    echo "setup: need root (or sudo) to install: ${missing[*]}" >&2; exit 1
  fi
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
ensure_linuxcnc_user
echo "setup: done"
