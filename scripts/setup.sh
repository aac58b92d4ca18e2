#!/usr/bin/env bash
# Idempotent machine setup: Debian packages (apt-get), the project's .venv (PyPI) and the LTS
# bpy wheels' venvs (scripts/setup_wheels.sh).
# Safe to run repeatedly; does nothing when everything is already present.
set -euo pipefail
cd "$(dirname "$0")/.."

DEB_PACKAGES=(
  build-essential cmake ninja-build pkg-config clang-format
  clang libclang-rt-14-dev
  blender
  libembree-dev libopenimageio-dev libopencolorio-dev libtbb-dev
  nlohmann-json3-dev googletest libgtest-dev
  libbenchmark-dev  # make microbench: Google Benchmark (native/bench)
  linux-perf  # make profile: scripts/render/profile_render.sh
  python3-numpy python3-pytest python3-venv
  chromium chromium-driver
  valgrind  # make sanitize: memcheck of the native determinism tests
  xvfb xauth  # make test-ui: Blender 3.4 with its UI (viewport, panels) on a virtual display
)

missing=()
for p in "${DEB_PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing Debian packages: ${missing[*]}"
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

PY=${STRATUM_PYTHON:-python3.11}
command -v "$PY" >/dev/null || PY=/usr/bin/python3.11
if [ ! -x .venv/bin/python ]; then
  echo "setup: creating .venv with $PY"
  "$PY" -m venv .venv
fi
stamp=.venv/.stratum-setup
req=scripts/requirements.txt
if [ ! -f "$stamp" ] || [ "$req" -nt "$stamp" ] || [ addon/pyproject.toml -nt "$stamp" ] \
   || [ addon/stratum/blender_manifest.toml -nt "$stamp" ]; then  # the manifest: the version
  .venv/bin/python -m pip install -q --upgrade pip
  .venv/bin/python -m pip install -q -r "$req"
  .venv/bin/python -m pip install -q -e addon
  touch "$stamp"
fi

bash scripts/setup_wheels.sh
