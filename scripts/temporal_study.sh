#!/usr/bin/env bash
# The temporal window study (scripts/temporal_study/RESULTS.md): each method
# filtered frame by frame and with --temporal-window K (K = 1, 2, 3; the
# other temporal options at their defaults) on
#   static: grids, still camera, 64x48, 16 frames of per-frame noise at 9 spp,
#           one 1024 spp reference for every frame;
#   studio: the studio scene's camera move and moving light, 96x72, frames
#           1-8 at 9 spp, a 256 spp reference per frame;
#   crossing: testdata/sequences/crossing.json, a box sliding through a
#           shelf's shadow on a still camera, 96x72, frames 1-12 at 9 spp,
#           a 256 spp reference per frame;
# per-frame RMSE (mean, and the largest change of any frame against its
# filtering alone) and the temporal error (the RMSE of the frame-to-frame
# change of test minus reference, aaf compare's temporal_rmse) against the
# references. Writes a Markdown table to stdout and to
# scripts/temporal_study/RESULTS.md (TEMPORAL_STUDY_OUT picks another folder).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
aaf="${AAF:-$root/build/cli/aaf}"
[ -x "$aaf" ] || "$root/scripts/build.sh" --tool
out="${TEMPORAL_STUDY_OUT:-$root/scripts/temporal_study}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"

# errors TEST REFERENCE FRAMES: "mean_rmse temporal_mean rmse1,rmse2,..."
errors() {
    "$aaf" compare "$1" "$2" --frames "$3" --json | /usr/bin/python3 -c '
import json, sys
d = json.load(sys.stdin)
print(d["summary"]["rmse"]["mean"], d["summary"]["temporal_rmse"]["mean"],
      ",".join(str(p["rmse"]) for p in d["pairs"]))'
}

# row SEQUENCE METHOD FRAMES: one table row per K against the frame-by-frame filter
row() {
    local seq="$1" method="$2" frames="$3" dir="$work/$1"
    "$aaf" filter "$method" "$dir/in.####.exr" -o "$dir/$method.k0.####.exr" --frames "$frames" \
        --progress none 2>/dev/null
    read -r rmse0 temporal0 frames0 < <(errors "$dir/$method.k0.####.exr" "$dir/ref.####.exr" "$frames")
    printf '| %s | %s | 0 | %.5f | - | %.5f | 1 |\n' "$seq" "$method" "$rmse0" "$temporal0"
    for k in 1 2 3; do
        "$aaf" filter "$method" "$dir/in.####.exr" -o "$dir/$method.k$k.####.exr" --frames "$frames" \
            --temporal-window "$k" --progress none 2>/dev/null
        read -r rmse temporal perframe < <(errors "$dir/$method.k$k.####.exr" "$dir/ref.####.exr" "$frames")
        worst=$(/usr/bin/python3 -c "
a = [float(v) for v in '$frames0'.split(',')]; b = [float(v) for v in '$perframe'.split(',')]
print('%+.1f %%' % (100 * max((y - x) / x for x, y in zip(a, b))))")
        printf '| %s | %s | %d | %.5f | %s | %.5f | %.2f |\n' "$seq" "$method" "$k" "$rmse" "$worst" "$temporal" \
            "$(echo "$temporal0 / $temporal" | bc -l)"
    done
}

mkdir -p "$work/static" "$work/studio" "$work/crossing"
"$aaf" render grids --width 64 --height 48 --spp 9 --frames 1-16 --aovs aaf,ratio,maaf6,motion \
    --progress none -o "$work/static/in.####.exr" >/dev/null
"$aaf" render grids --width 64 --height 48 --spp 1024 --aovs aaf,ratio,maaf6 --progress none \
    -o "$work/static/reference.exr" >/dev/null
for f in $(seq 1 16); do cp "$work/static/reference.exr" "$work/static/ref.$(printf %04d "$f").exr"; done
"$aaf" render studio --width 96 --height 72 --spp 9 --frames 1-8 --aovs aaf,motion --progress none \
    -o "$work/studio/in.####.exr" >/dev/null
"$aaf" render studio --width 96 --height 72 --spp 256 --frames 1-8 --aovs aaf --progress none \
    -o "$work/studio/ref.####.exr" >/dev/null
crossing="$root/testdata/sequences/crossing.json"
"$aaf" render "$crossing" --width 96 --height 72 --spp 9 --frames 1-12 --aovs aaf,ratio,maaf6,motion \
    --progress none -o "$work/crossing/in.####.exr" >/dev/null
"$aaf" render "$crossing" --width 96 --height 72 --spp 256 --frames 1-12 --aovs aaf,ratio,maaf6 --progress none \
    -o "$work/crossing/ref.####.exr" >/dev/null

{
    echo "# Temporal window study, $(date -u +%F)"
    echo
    echo "Machine: $("$root/scripts/machine.sh"). Produced by \`scripts/temporal_study.sh\`."
    echo
    echo "RMSE and temporal error (aaf compare's temporal_rmse) against the references, each method's"
    echo "CLI defaults and --temporal-window K with the other temporal options at their defaults;"
    echo "K = 0 is the frame-by-frame filter. 'worst frame' is the largest change of one frame's RMSE"
    echo "against its filtering alone (negative: every frame better)."
    echo
    echo "| sequence | method | K | mean RMSE | worst frame | temporal error | flicker reduction |"
    echo "| --- | --- | --- | --- | --- | --- | --- |"
    for method in aaf ratio maaf6; do row static "$method" 1-16; done
    row studio aaf 1-8
    for method in aaf ratio maaf6; do row crossing "$method" 1-12; done
} | tee "$out/RESULTS.md"
