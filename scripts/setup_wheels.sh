#!/usr/bin/env bash
# Idempotent: one venv per scripts/requirements-bpy-<line>.txt, .venv-bpy-<line>, holding that
# Blender LTS line's bpy wheel, for the smoke matrix of `make test` (make test-wheels,
# tests/package). The main .venv (scripts/setup.sh) keeps the 5.0 wheel. The add-on is found
# through the tests' own path (tests/blender/conftest.py), not installed. A venv whose stamp
# equals its requirements file is left alone; any other is made anew.
set -euo pipefail
cd "$(dirname "$0")/.."

PY=${STRATUM_PYTHON:-python3.11}
command -v "$PY" >/dev/null || PY=/usr/bin/python3.11

for requirements in scripts/requirements-bpy-*.txt; do
  line=${requirements#scripts/requirements-bpy-}
  venv=.venv-bpy-${line%.txt}
  stamp=$venv/.stratum-setup
  if [ -f "$stamp" ] && cmp -s "$stamp" "$requirements"; then
    continue
  fi
  echo "setup: creating $venv from $requirements"
  rm -rf "$venv"
  "$PY" -m venv "$venv"
  "$venv/bin/python" -m pip install -q -r "$requirements"
  cp "$requirements" "$stamp"
done
