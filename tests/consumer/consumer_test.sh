#!/usr/bin/env bash
# Installs the already-built tree into a scratch prefix and builds and runs
# three tiny consumer projects against it with find_package(aaf CONFIG):
#   core: COMPONENTS core with every package but oneTBB (and Highway, the
#         core's private link-only dependency) disabled (fails if
#         the core's config asks for OpenImageIO, OpenColorIO, Embree, ...);
#         filters a small plane with aaf::fixed_gaussian_filter.
#   io:   COMPONENTS io with the tracer's packages disabled; writes an EXR
#         with aaf::io::write_aovs and reads it back with read_aovs.
#   all:  no COMPONENTS (= all); an unknown component must fail; compiles each
#         installed header on its own; renders an installed scene.
# Also checks what is installed: no internal headers, no test programs.
# Usage: consumer_test.sh CMAKE BUILD_DIR WORK_DIR GENERATOR CXX_COMPILER
# Any failure exits non-zero; there is no skip.
set -euo pipefail
cmake="$1" build="$2" work="$3" generator="$4" cxx="$5"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
fail() { echo "consumer_test: FAILED: $*" >&2; exit 1; }

rm -rf "$work" && mkdir -p "$work"
prefix="$work/prefix"
"$cmake" --install "$build" --prefix "$prefix" >"$work/install.log"

config=$(find "$prefix" -name aafConfig.cmake -print -quit)
[ -n "$config" ] || fail "no aafConfig.cmake under $prefix"
aaf_dir="$(dirname "$config")"
for component in core io trace; do
  [ -f "$aaf_dir/aaf-$component-targets.cmake" ] || fail "no aaf-$component-targets.cmake"
done
for internal in fast_exp.h parallel.h occluder_fill.h; do
  [ ! -e "$prefix/include/aaf/core/$internal" ] || fail "internal header aaf/core/$internal is installed"
done
programs=$(cd "$prefix/bin" && ls)
[ "$programs" = "aaf" ] || fail "bin/ should hold only aaf, holds: $programs"
libraries=$(find "$(dirname "$aaf_dir")/.." -maxdepth 1 -type f -printf '%f\n' | sort | tr '\n' ' ')
[ "$libraries" = "libaaf_core.a libaaf_formats.so libaaf_io.a libaaf_trace.a " ] || fail "unexpected libraries: $libraries"
scene="$prefix/share/aaf/scenes/grids.json"
[ -f "$scene" ] || fail "the scenes are not installed ($scene)"

# configure_build NAME [CMAKE ARGS...]
configure_build() {
  local name="$1"
  shift
  "$cmake" -S "$here/$name" -B "$work/$name" -G "$generator" -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_CXX_COMPILER="$cxx" -Daaf_DIR="$aaf_dir" -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF --no-warn-unused-cli "$@"
  "$cmake" --build "$work/$name" --parallel 2
}

trace_packages=(-DCMAKE_DISABLE_FIND_PACKAGE_embree=ON -DCMAKE_DISABLE_FIND_PACKAGE_nlohmann_json=ON
                -DCMAKE_DISABLE_FIND_PACKAGE_tinyobjloader=ON)
io_packages=(-DCMAKE_DISABLE_FIND_PACKAGE_OpenImageIO=ON -DCMAKE_DISABLE_FIND_PACKAGE_OpenEXR=ON
             -DCMAKE_DISABLE_FIND_PACKAGE_Imath=ON -DCMAKE_DISABLE_FIND_PACKAGE_OpenColorIO=ON
             -DCMAKE_DISABLE_FIND_PACKAGE_PkgConfig=ON)

echo "== core consumer (only oneTBB and Highway findable)"
configure_build core "${io_packages[@]}" "${trace_packages[@]}"
"$work/core/core_consumer"

echo "== io consumer (the tracer's packages not findable)"
configure_build io "${trace_packages[@]}"
"$work/io/io_consumer" "$work/io/roundtrip.exr"

echo "== all components, installed headers one by one"
configure_build all
"$work/all/all_consumer" "$scene"
echo "== the installed tree moved elsewhere: aaf finds its own scenes; the installed Python module imports"
moved="$work/moved"
mv "$prefix" "$moved"
# The render records the scene file it read: the moved tree's, not the
# source tree's (a compiled-in fallback) nor the old prefix's (gone).
env -u AAF_SCENE_PATH "$moved/bin/aaf" render grids -o "$work/moved.exr" --width 8 --height 6 --spp 1
recorded=$(/usr/bin/python3 -c 'import OpenImageIO as oiio, sys; print(oiio.ImageInput.open(sys.argv[1]).spec().getattribute("aaf:scene_file"))' "$work/moved.exr")
[ "$recorded" = "$moved/share/aaf/scenes/grids.json" ] || fail "the moved aaf rendered $recorded, not its own scene"
module=$(find "$moved" -name 'aaf.cpython-*.so' -print -quit)
if [ -n "$module" ]; then
  PYTHONPATH="$(dirname "$module")" /usr/bin/python3 -c 'import aaf; assert "aaf" in [m["name"] for m in aaf.methods()]' \
    || fail "the installed Python module does not import"
fi
echo "consumer_test: ok"
