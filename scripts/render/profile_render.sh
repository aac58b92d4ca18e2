#!/bin/bash
# Where the path tracer spends its time (issue 15, target 2; docs/performance.md): captures a
# .blend's render geometry as a native scene file through Blender (capture_scene.py), renders it
# with build/stratum-native under `perf record` (Debian linux-perf) and prints the symbols with
# the most samples, their own time (--no-children).
#
#   scripts/render/profile_render.sh [SCENE.blend] [name=value ...]
#
# Defaults: the bundled Cornell box, 128x128, 128 spp, the scene's own settings otherwise;
# name=value words override them (e.g. sampler=sobol triangle_sampling=area threads=1).
set -euo pipefail
cd "$(dirname "$0")/../.."
blend=scenes/cornell_box.blend
if [[ $# -gt 0 && $1 == *.blend ]]; then blend=$1; shift; fi
out=out/profile
mkdir -p "$out"
name=$(basename "$blend" .blend)
settings=$(${BLENDER:-blender} -b "$blend" --factory-startup -noaudio --python scripts/run_in_blender.py \
  -- scripts.render.capture_scene "$out/$name.json" 2>/dev/null | sed -n 's/^SETTINGS //p')
if [[ -z $settings ]]; then echo "profile_render: could not capture $blend" >&2; exit 1; fi
# The scene's settings first, then the defaults of this profile, then the caller's words: the
# last value of a name wins in stratum-native.
# shellcheck disable=SC2086
perf record -q -o "$out/$name.perf" build/stratum-native render "$out/$name.json" "$out/$name.exr" \
  $settings width=128 height=128 samples=128 "$@"
echo "time by library:"
perf report -i "$out/$name.perf" --no-children --sort dso --stdio 2>/dev/null | grep -E '^ +[0-9]' | head -n 6
echo "time by symbol (Embree's are unnamed addresses: see its line above):"
perf report -i "$out/$name.perf" --no-children --sort dso,sym --stdio 2>/dev/null |
  grep -E '^ +[0-9]' | head -n "${TOP:-30}"
