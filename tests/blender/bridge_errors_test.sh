#!/usr/bin/env bash
# The Blender bridge's failures (scripts/blender/aaf_bridge.py, headless):
# each exits with aaf's code (2 usage, 3 a scene or file it cannot use) and
# one `aaf-bridge: error:` line naming the file, and a failed export leaves
# no file behind (its meshes are written into a temporary folder first). A
# good export over an older one replaces the older meshes.
# Usage: bridge_errors_test.sh WORK_DIR
# Exits 77 (ctest: skipped) when Blender is not installed.
set -euo pipefail
work="$1"
blender="${AAF_BLENDER:-$(command -v blender || true)}"
if [ -z "$blender" ]; then
  echo "SKIPPED: Blender is not installed (scripts/install_blender.sh installs Debian's Blender 3.4)"
  exit 77
fi
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
bridge="$here/../../scripts/blender/aaf_bridge.py"
rm -rf "$work" && mkdir -p "$work/out" "$work/logs"
fail() { echo "FAILED: $*"; exit 1; }

# expect CODE NAMED LOG -- BLENDER_ARGS...: Blender's exit code and its one error line.
expect() {
  local code=$1 named=$2 log="$work/logs/$3"; shift 4
  local got=0
  (cd "$work/out" && "$blender" -b --factory-startup "$@" > "$log.out" 2> "$log.err") || got=$?
  [ "$got" -eq "$code" ] || { cat "$log.err"; fail "$* exited $got, expected $code"; }
  [ "$(grep -c . "$log.err")" -eq 1 ] && grep -q "^aaf-bridge: error: .*$named" "$log.err" \
    || { cat "$log.err"; fail "$*: stderr is not one 'aaf-bridge: error:' line naming $named"; }
  [ -z "$(ls -A "$work/out")" ] || { ls -la "$work/out"; fail "$* left files behind"; }
}

# Blender's factory scene: a cube, a point light and a camera, no area light.
expect 3 "shot.json: .*no area light" no_area_light -- --python "$bridge" -- export shot.json
expect 3 "nosuch/shot.json" missing_folder -- --python "$bridge" -- export nosuch/shot.json
expect 3 "nosuch.exr" load_missing -- --python "$bridge" -- load nosuch.exr
expect 2 "usage" usage -- --python "$bridge" -- frobnicate

# A scene that exports: the factory scene with an area light; a stale meshes
# folder of an earlier export is replaced, not merged.
cat > "$work/logs/area_light.py" <<'PY'
import bpy
bpy.ops.object.light_add(type="AREA", location=(0, 0, 3))
PY
mkdir -p "$work/out/shot_meshes" && echo "stale" > "$work/out/shot_meshes/009_Stale.obj"
(cd "$work/out" && "$blender" -b --factory-startup --python "$work/logs/area_light.py" --python "$bridge" \
  -- export shot.json > "$work/logs/export.out" 2> "$work/logs/export.err") \
  || { cat "$work/logs/export.err"; fail "the export of a scene with an area light failed"; }
[ -f "$work/out/shot.json" ] && [ -f "$work/out/shot.light.json" ] || fail "the export wrote no scene"
[ -f "$work/out/shot_meshes/001_Cube.obj" ] || fail "the export wrote no cube"
[ ! -e "$work/out/shot_meshes/009_Stale.obj" ] || fail "the earlier export's mesh is still there"
leftover=$(ls -A "$work/out" | grep -v -x -e shot.json -e shot.light.json -e shot_meshes || true)
[ -z "$leftover" ] || fail "the export left $leftover"
echo "OK: every bridge failure exits with its code and one error line, leaving nothing behind"
