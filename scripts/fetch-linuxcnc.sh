#!/usr/bin/env bash
# Downloads Debian's linuxcnc-uspace package (without installing it) and unpacks it into
# .cache/linuxcnc, so tests can read LinuxCNC's own sample configurations (hexapod-sim) and later run
# its reference programs (rs274). Idempotent and silent when already unpacked. Never fatal: without
# the package the tests that need it are skipped and say so.
set -uo pipefail
cd "$(dirname "$0")/.."
dest=.cache/linuxcnc
marker=$dest/.unpacked
[ -f "$marker" ] && exit 0
mkdir -p "$dest"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
if ! (cd "$tmp" && apt-get download linuxcnc-uspace >/dev/null 2>&1); then
  apt-get update -qq >/dev/null 2>&1 || true
  if ! (cd "$tmp" && apt-get download linuxcnc-uspace >/dev/null 2>&1); then
    echo "fetch-linuxcnc: could not download linuxcnc-uspace; LinuxCNC reference tests will be skipped" >&2
    exit 0
  fi
fi
dpkg -x "$tmp"/linuxcnc-uspace_*.deb "$dest" && touch "$marker"
