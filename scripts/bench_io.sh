#!/usr/bin/env bash
# `aaf filter` end to end against the I/O floor, and the adaptive frame.
#
# For each size (default 640x480 1920x1080 3840x2160) it renders the grids
# scene once (9 spp, the CLI's default AOVs) and then times, alternately in
# the same loop so that load on a shared machine hits all alike:
#   oiiotool      oiiotool in.exr -o out.exr   (read and write the same file:
#                 the floor any filter that reads and writes it pays; it keeps
#                 the input's compression name, "zip", which OpenEXR writes at
#                 its default deflate level 4)
#   oiiotool_zip1 oiiotool in.exr --compression zip:1 -o out.exr (the same
#                 compression as aaf filter's default, zip:1: like for like)
#   aaf_filter    aaf filter aaf in.exr -o out.exr   (CLI defaults)
#   each method   aaf filter METHOD (maaf needs the maaf AOVs: left out here)
# and, at 640x480 only, the adaptive frame (aaf render grids --adaptive, then
# aaf filter aaf, written; and the same in one process, aaf render grids
# --adaptive --filter aaf, alternately). Peak memory (maximum RSS, /usr/bin/time -v) of one
# aaf filter run, of `aaf --version` (the mapped libraries alone: the
# baseline) and of the oiiotool copy; the frame's AOV bytes are width x height
# x the bytes of its channels as stored, and the peak is given over them both
# including and excluding the baseline. Prints a Markdown table of medians
# (REPS, default 5).
#
# First, the OpenEXR floor: for each size, alternately in the same loop,
#   floor         exr_copy_floor in.exr out.exr N (scripts/bench: OpenEXR alone
#                 reads every channel of every part as float and writes them
#                 back as zip:1 on N threads, Imf::setGlobalThreadCount)
#   aaf_filter    aaf filter aaf in.exr -o out.exr --threads N
# for N = 2 and 1, with the medians and their ratio; then `aaf --version`
# (median of 20 runs: the start-up alone), `aaf info in.exr` (the header)
# and `aaf info --stats in.exr` (every pixel). With
# FLOOR_ONLY=1 only this part runs.
# Usage: scripts/bench_io.sh [WIDTHxHEIGHT ...]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
aaf="${AAF:-$root/build/cli/aaf}"
reps="${REPS:-5}"
dir="${AAF_BENCH_DIR:-/tmp/aaf_bench_io}"
mkdir -p "$dir"
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(640x480 1920x1080 3840x2160)

now() { date +%s.%N; }
median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }

echo "Machine: $(nproc) CPUs, load average $(cut -d' ' -f1-3 /proc/loadavg) at the start, $(date -u +%FT%TZ); REPS=$reps; aaf $("$aaf" --version 2>/dev/null | head -n1)"
echo
# Maximum resident set size of a command, KiB.
peak_rss_kb() {
    /usr/bin/time -v "$@" 2>&1 >/dev/null | awk -F: '/Maximum resident set size/ {gsub(/ /, "", $2); print $2}'
}

floor="${EXR_COPY_FLOOR:-$root/build/scripts/bench/exr_copy_floor}"
render_input() {  # render_input WIDTHxHEIGHT: the grids frame of that size, rendered once
    local w="${1%x*}" h="${1#*x}" in="$dir/grids_$1.exr"
    [ -f "$in" ] || "$aaf" render grids --width "$w" --height "$h" --aovs aaf,isg,depth -o "$in" --progress none >/dev/null
    echo "$in"
}
elapsed_ms() {  # elapsed_ms COMMAND...: wall time of one run, ms
    local t
    t=$(now)
    "$@" >/dev/null
    echo "($(now) - $t) * 1000" | bc -l
}
echo "| size | threads | OpenEXR floor ms | aaf filter aaf ms | aaf / floor |"
echo "| --- | --- | --- | --- | --- |"
for size in "${sizes[@]}"; do
    in=$(render_input "$size")
    for n in 2 1; do
        floor_ms=()
        aaf_ms=()
        for ((r = 0; r < reps; ++r)); do
            floor_ms+=("$(elapsed_ms "$floor" "$in" "$dir/floor.exr" "$n")")
            aaf_ms+=("$(elapsed_ms "$aaf" filter aaf "$in" -o "$dir/out.exr" --threads "$n")")
        done
        f=$(printf '%s\n' "${floor_ms[@]}" | median)
        a=$(printf '%s\n' "${aaf_ms[@]}" | median)
        awk -v s="$size" -v n="$n" -v f="$f" -v a="$a" 'BEGIN { printf "| %s | %d | %.0f | %.0f | %.2f |\n", s, n, f, a, a / f }'
    done
done
version_ms=()
info_ms=()
stats_ms=()
in=$(render_input "${sizes[0]}")
for ((r = 0; r < 20; ++r)); do
    version_ms+=("$(elapsed_ms "$aaf" --version)")
    info_ms+=("$(elapsed_ms "$aaf" info "$in")")
    stats_ms+=("$(elapsed_ms "$aaf" info --stats "$in")")
done
m() { printf '%s\n' "$@" | median | xargs printf '%.1f'; }
echo
echo "aaf --version: median of 20 runs $(m "${version_ms[@]}") ms; ${sizes[0]} frame: aaf info (the header) $(m "${info_ms[@]}") ms, aaf info --stats (every pixel) $(m "${stats_ms[@]}") ms"
echo
[ "${FLOOR_ONLY:-0}" = 1 ] && exit 0

echo "| size | oiiotool copy ms | oiiotool zip:1 copy ms | aaf filter aaf ms | aaf / oiiotool | aaf / oiiotool zip:1 | gaussian ms | isg-shadow ms | ms per Mpixel (aaf) | peak RSS MiB | aaf --version RSS MiB | oiiotool copy RSS MiB | AOV bytes MiB | RSS / AOV bytes | (RSS - baseline) / AOV bytes |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"
for size in "${sizes[@]}"; do
    w="${size%x*}"
    h="${size#*x}"
    in="$dir/grids_${size}.exr"
    [ -f "$in" ] || "$aaf" render grids --width "$w" --height "$h" --aovs aaf,isg,depth -o "$in" --progress none >/dev/null
    declare -A times=()
    for ((r = 0; r < reps; ++r)); do
        for what in oiiotool oiiotool_zip1 aaf gaussian isg-shadow; do
            t=$(now)
            case "$what" in
                oiiotool) oiiotool "$in" -o "$dir/copy.exr" ;;
                oiiotool_zip1) oiiotool "$in" --compression zip:1 -o "$dir/copy.exr" ;;
                *) "$aaf" filter "$what" "$in" -o "$dir/out.exr" >/dev/null ;;
            esac
            times[$what]+="$(echo "($(now) - $t) * 1000" | bc -l) "
        done
    done
    declare -A med=()
    for what in oiiotool oiiotool_zip1 aaf gaussian isg-shadow; do
        med[$what]=$(echo "${times[$what]}" | tr ' ' '\n' | grep . | median)
    done
    rss_kb=$(peak_rss_kb "$aaf" filter aaf "$in" -o "$dir/out.exr")
    base_kb=$(peak_rss_kb "$aaf" --version)
    copy_kb=$(peak_rss_kb oiiotool "$in" -o "$dir/copy.exr")
    # Bytes of the input's channels as stored (half 2, float 4) times the pixels.
    aov_bytes=$(oiiotool --info -v "$in" | awk -v px=$((w * h)) '
        /channel list:/ {
            n = split($0, parts, ",")
            for (i = 1; i <= n; ++i) bytes += (parts[i] ~ /\(half\)/) ? 2 : 4
        }
        END { print bytes * px }')
    awk -v s="$size" -v o="${med[oiiotool]}" -v z="${med[oiiotool_zip1]}" -v a="${med[aaf]}" \
        -v g="${med[gaussian]}" -v i="${med[isg-shadow]}" -v mp="$(echo "$w * $h / 1000000" | bc -l)" \
        -v rss="$rss_kb" -v base="$base_kb" -v copy="$copy_kb" -v bytes="$aov_bytes" 'BEGIN {
        printf "| %s | %.0f | %.0f | %.0f | %.2f | %.2f | %.0f | %.0f | %.0f | %.0f | %.0f | %.0f | %.1f | %.2f | %.2f |\n",
            s, o, z, a, a / o, a / z, g, i, a / mp, rss / 1024, base / 1024, copy / 1024, bytes / 1048576,
            rss * 1024 / bytes, (rss - base) * 1024 / bytes }'
    unset times med
done

# The adaptive frame at 640x480: render (9 spp first pass, the CLI defaults) + filter + write.
frame=()
one=()
for ((r = 0; r < reps; ++r)); do
    t=$(now)
    "$aaf" render grids --adaptive -o "$dir/adaptive.exr" --progress none >/dev/null
    "$aaf" filter aaf "$dir/adaptive.exr" -o "$dir/adaptive_filtered.exr" >/dev/null
    frame+=("$(echo "($(now) - $t) * 1000" | bc -l)")
    t=$(now)
    "$aaf" render grids --adaptive --filter aaf -o "$dir/adaptive_one.exr" --progress none >/dev/null
    one+=("$(echo "($(now) - $t) * 1000" | bc -l)")
done
echo
echo "Adaptive 640x480 grids frame (aaf render grids --adaptive; aaf filter aaf): median $(printf '%s\n' "${frame[@]}" | median | xargs printf '%.0f') ms"
echo "The same in one process (aaf render grids --adaptive --filter aaf): median $(printf '%s\n' "${one[@]}" | median | xargs printf '%.0f') ms"
