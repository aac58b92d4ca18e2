#!/usr/bin/env bash
# Installs the Stratum add-on into Blender's user add-on folder as a symlink to this checkout
# (addon/stratum), so `blender -b scene.blend --addons stratum -E STRATUM ...` works.
# Idempotent: re-running it refreshes the link. Blender: $STRATUM_BLENDER or `blender`.
set -euo pipefail
cd "$(dirname "$0")/.."
BLENDER=${STRATUM_BLENDER:-blender}
SRC="$PWD/addon/stratum"

addons_dir=$("$BLENDER" -b --factory-startup --python-expr \
  'import bpy; print("STRATUM_ADDONS_DIR=" + bpy.utils.user_resource("SCRIPTS", path="addons"))' \
  2>/dev/null | sed -n 's/^STRATUM_ADDONS_DIR=//p' | tail -n 1)
if [ -z "$addons_dir" ]; then
  echo "install_addon: could not ask $BLENDER for its user add-on folder" >&2
  exit 1
fi
mkdir -p "$addons_dir"
dest="$addons_dir/stratum"
if [ -e "$dest" ] && [ ! -L "$dest" ]; then
  echo "install_addon: $dest exists and is not a symlink; remove it first" >&2
  exit 1
fi
ln -sfn "$SRC" "$dest"
echo "install_addon: $dest -> $SRC"
if [ ! -f "$SRC/lib/libstratum.so" ] && [ -z "${STRATUM_LIBRARY:-}" ]; then
  echo "install_addon: note: $SRC/lib/libstratum.so is not built yet (make build)" >&2
fi
