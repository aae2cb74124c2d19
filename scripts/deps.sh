#!/usr/bin/env bash
# Installs the Debian packages the project needs; skips apt when all are present.
#   scripts/deps.sh        everything: the tool, the tests, the benchmarks, the
#                          Python module, the studies' plots and the farm tests
#   scripts/deps.sh tool   only what building the `aaf` tool needs (scripts/demo.sh)
set -euo pipefail
set_name="${1:-all}"
# The `aaf` tool: the libraries it links and the compilers that build it.
tool=(
  cmake ninja-build g++ pkg-config
  libopenexr-dev libimath-dev
  libopenimageio-dev     # the formats module (PNG/JPEG pictures, other formats) and file sequences
  libopencolorio-dev libcli11-dev libembree-dev libtbb-dev
  libtinyobjloader-dev nlohmann-json3-dev
  libhwy-dev             # Google Highway: the core's SIMD kernels with runtime dispatch (a private dependency)
)
# What the tests, benchmarks, studies and bindings add.
rest=(
  clang-format-14        # tests/format/check_format.sh: every C++ file formatted by .clang-format
  openimageio-tools      # oiiotool: the tests' and benchmarks' independent reader and I/O yardstick
  libopencv-dev          # the tests' OpenImageIO CMake target names /usr/include/opencv4; the benchmarks' yardsticks
  catch2 libbenchmark-dev
  python3-openimageio python3-numpy   # scripts/make_bad_corpus.py (run with /usr/bin/python3)
  python3-dev python3-pybind11         # the Python module aaf (libaaf/python), built for /usr/bin/python3
  python3-matplotlib                   # the studies' plots (scripts/plot_*.py, ratio_study.py)
  python3-yaml                         # tests/farm/openjd_template_test.py reads the OpenJD template
  slurm-wlm munge                      # the farm tests' one-node Slurm cluster (tests/farm/slurm_cluster.sh)
  slurmdbd mariadb-server              # its accounting (slurmdbd on a private MariaDB), read with sacct
)
case "$set_name" in
  tool) packages=("${tool[@]}") ;;
  all) packages=("${tool[@]}" "${rest[@]}") ;;
  *) echo "deps.sh: unknown set '$set_name' (expected tool or all)" >&2; exit 2 ;;
esac
missing=()
for p in "${packages[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "deps: installing ${missing[*]}" >&2
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
$sudo apt-get update -q
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
