#!/usr/bin/env bash
# Installs the Debian packages the project needs; skips apt when all are present.
set -euo pipefail
packages=(
  cmake ninja-build g++ pkg-config
  clang-format-14        # tests/format/check_format.sh: every C++ file formatted by .clang-format
  libopenimageio-dev openimageio-tools libopenexr-dev libimath-dev
  libopencv-dev          # OpenImageIO's CMake target names /usr/include/opencv4; bench_aaf_filter's GaussianBlur yardstick
  libopencolorio-dev libcli11-dev catch2 libembree-dev libtbb-dev
  libtinyobjloader-dev nlohmann-json3-dev libbenchmark-dev
  libhwy-dev             # Google Highway: the core's SIMD gather with runtime dispatch (a private dependency)
  python3-openimageio python3-numpy   # scripts/make_bad_corpus.py (run with /usr/bin/python3)
  python3-dev python3-pybind11         # the Python module aaf (libaaf/python), built for /usr/bin/python3
  python3-matplotlib                   # the studies' plots (scripts/plot_*.py, ratio_study.py)
  python3-yaml                         # tests/farm/openjd_template_test.py reads the OpenJD template
  slurm-wlm munge                      # the farm tests' one-node Slurm cluster (tests/farm/slurm_cluster.sh)
  slurmdbd mariadb-server              # its accounting (slurmdbd on a private MariaDB), read with sacct
)
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
