#!/usr/bin/env bash
# Install microslip with every optional extra into its own virtual environment, .venv/ in the
# checkout (a Debian system python3 refuses `pip install`, PEP 668), then the CalculiX solver
# (Debian package calculix-ccx, binary ccx) when it is missing, then compile the numba kernels
# once so that the first command does not pay for it. Safe to run again: it only installs
# what is absent. Afterwards run everything with .venv/bin/python.
set -euo pipefail
cd "$(dirname "$0")/.."

if [ "$(id -u)" -eq 0 ]; then SUDO=""; elif command -v sudo >/dev/null 2>&1; then SUDO="sudo"; else SUDO="skip"; fi

apt_install() {  # apt_install PACKAGE...: install Debian packages, or say why not
  if [ "$SUDO" = "skip" ] || ! command -v apt-get >/dev/null 2>&1; then
    echo "setup: cannot install $* (needs apt-get as root); install it and run this again" >&2
    return 1
  fi
  echo "setup: installing $* (apt-get)" >&2
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "$@" >/dev/null
}

PY="${PYTHON:-python3}"
if ! command -v "$PY" >/dev/null 2>&1; then
  apt_install python3 python3-venv
fi

# The virtual environment. Debian splits venv/ensurepip into python3-venv.
if [ ! -x .venv/bin/python ]; then
  if ! "$PY" -m venv .venv 2>/dev/null; then
    rm -rf .venv
    apt_install python3-venv
    "$PY" -m venv .venv
  fi
fi
VPY=.venv/bin/python
"$VPY" -m pip install --quiet --disable-pip-version-check --upgrade pip >/dev/null
"$VPY" -m pip install --quiet --disable-pip-version-check -e ".[all]"

if ! command -v ccx >/dev/null 2>&1; then
  apt_install calculix-ccx || echo "setup: the finite-element commands that need CalculiX will" \
    "say how to install it" >&2
fi

# Headless Chromium (Debian packages chromium, chromium-driver) for the browser test of
# `microslip report` (tests/test_report.py); without it that test is skipped with the reason.
if ! command -v chromium >/dev/null 2>&1; then
  apt_install chromium chromium-driver || echo "setup: the report's browser test will be" \
    "skipped" >&2
fi

# Compile and cache the numba kernels that `microslip reproduce` runs, now rather than in the
# user's first command: about 50 s of CPU time, so about a minute on an idle 2-core machine
# and several minutes on a busy one (it says how long it took). A single `microslip loop`
# needs none of them; the first `sweep` compiles its batch kernels (about 30 s of CPU).
echo "setup: compiling the numba kernels (about a minute; longer on a busy machine)" >&2
"$VPY" -m microslip.warmup
