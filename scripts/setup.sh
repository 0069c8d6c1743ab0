#!/usr/bin/env bash
# Install microslip with every optional extra, and the CalculiX solver (Debian package
# calculix-ccx, binary ccx) when it is missing. Safe to run again: it only installs what is absent.
set -euo pipefail
cd "$(dirname "$0")/.."

if ! command -v ccx >/dev/null 2>&1; then
  if [ "$(id -u)" -eq 0 ]; then SUDO=""; elif command -v sudo >/dev/null 2>&1; then SUDO="sudo"; else
    echo "setup: ccx (CalculiX) is missing and this user cannot run apt-get; the finite-element" \
         "commands will say how to install it" >&2
    SUDO="skip"
  fi
  if [ "$SUDO" != "skip" ]; then
    echo "setup: installing CalculiX (apt-get install calculix-ccx)" >&2
    $SUDO apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq calculix-ccx >/dev/null
  fi
fi

python3 -m pip install --quiet --disable-pip-version-check --root-user-action=ignore -e ".[all]"
