#!/usr/bin/env bash
# Rewrites the generated tables of libaaf/AOV_CONTRACT.md from the code (roles,
# methods, synonyms, tracer groups), through the test that checks them.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/build.sh"
AAF_UPDATE_CONTRACT_DOC=1 "$root/build/tests/test_trace" "AOV_CONTRACT.md holds the contract as the code declares it"
echo "updated $root/libaaf/AOV_CONTRACT.md"
