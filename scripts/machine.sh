#!/usr/bin/env bash
# Prints the machine a figure is measured on, in one line: the CPU, its
# threads, the widest instruction set aaf's --isa can use on it, and the one
# in force (--isa / AAF_ISA, native by default). Renders are the same bytes
# under every instruction set; the filters' last bits and all times are not.
set -euo pipefail
cpu=$(awk -F': ' '/^model name/ {print $2; exit}' /proc/cpuinfo)
widest=sse4.2
grep -qw avx2 /proc/cpuinfo && grep -qw fma /proc/cpuinfo && widest=avx2
grep -qw avx512f /proc/cpuinfo && grep -qw avx512vl /proc/cpuinfo && widest=avx512
echo "${cpu:-unknown CPU}, $(nproc) threads, widest instruction set $widest, --isa ${AAF_ISA:-native}"
