#!/usr/bin/env bash
# The Blender bridge as an artist uses it (scripts/blender/aaf_bridge.py
# installed as an add-on in Blender 3.4, headless): its panel in the Render
# properties draws every setting and step, its preferences find `aaf`, the
# method list is `aaf filter --help`'s; the panel's operators export a shot,
# render it, filter it and load it into the compositor, whose Combined pass
# then holds aaf's filtered pixels; a cancelled render leaves the earlier one
# and no file behind; a step that fails exits Blender with aaf's exit code
# and one error line, leaving nothing half-written.
# Usage: addon_test.sh AAF_EXECUTABLE WORK_DIR
# Exits 77 (ctest: skipped) when Blender is not installed.
set -euo pipefail
aaf="$(realpath "$1")" work="$2"
blender="${AAF_BLENDER:-$(command -v blender || true)}"
if [ -z "$blender" ]; then
  echo "SKIPPED: Blender is not installed (scripts/install_blender.sh installs Debian's Blender 3.4)"
  exit 77
fi
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
bridge="$here/../../scripts/blender/aaf_bridge.py"
rm -rf "$work" && mkdir -p "$work"
work="$(realpath "$work")"
fail() { echo "FAILED: $*"; exit 1; }
methods=$("$aaf" filter --help | sed -n '/^Subcommands:/,/^$/s/^  \([^ ]*\) .*/\1/p' | paste -sd, -)
[ -n "$methods" ] || fail "aaf filter --help lists no method"

# The add-on is installed into the scratch folder, not the user's.
drive() {  # drive MODE: Blender's exit code; its output in $work/MODE.out and .err
  local code=0
  BLENDER_USER_SCRIPTS="$work/user_scripts" BLENDER_USER_CONFIG="$work/user_config" \
    "$blender" -b --factory-startup --python-exit-code 1 --python "$here/addon_drive.py" -- \
    "$bridge" "$aaf" "$work" 32 24 "$methods" "$1" > "$work/$1.out" 2> "$work/$1.err" || code=$?
  return $code
}

drive drive || { grep -v "^Fra:" "$work/drive.out" | tail -20; cat "$work/drive.err"; fail "driving the add-on"; }
grep "aaf-addon-test" "$work/drive.out"
"$aaf" compare "$work/blender_Combined.exr" "$work/filtered_aaf.exr" --channels R,G,B --fail-above rmse=0 \
  > /dev/null || fail "the compositor's Combined pass is not the filtered beauty aaf wrote"

# expect MODE CODE PATTERN FILES...: exit code, one error line, and exactly FILES in $work/MODE.
expect() {
  local mode=$1 code=$2 pattern=$3 got=0; shift 3
  drive "$mode" || got=$?
  [ "$got" -eq "$code" ] || { tail -5 "$work/$mode.out"; cat "$work/$mode.err"; fail "$mode: exit $got, expected $code"; }
  [ "$(grep -c . "$work/$mode.err")" -eq 1 ] && grep -q "^aaf-bridge: error: .*$pattern" "$work/$mode.err" \
    || { cat "$work/$mode.err"; fail "$mode: stderr is not one 'aaf-bridge: error:' line naming $pattern"; }
  local left
  left=$(cd "$work/$mode" 2>/dev/null && ls -A | sort | paste -sd' ' - || true)
  [ "$left" = "$*" ] || fail "$mode: the folder holds '$left', expected '$*'"
}
# No executable at the preferences' path: nothing is exported before aaf is found.
expect bad-path 3 "$work/nosuch/aaf" 
# aaf refuses an option (usage, exit 2): no filtered file, no partial one.
expect bad-option 2 "aaf filter: --mu" shot.aovs.exr shot.json shot.light.json shot_meshes
echo "OK: the add-on's panel, preferences and operators export, render, filter, load and cancel; failures exit with aaf's code"
