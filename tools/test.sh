#!/usr/bin/env bash
# Installs what is missing, builds, and runs the whole test suite on lavapipe with the Vulkan
# validation layers on (a validation message fails the test). Extra arguments go to ctest,
# e.g. tools/test.sh -R Scene. Long runs carry the CTest label "long" and are excluded here.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$root/tools/deps.sh"
source "$root/tools/build.sh"
cd "$root/build"
ctest --output-on-failure -j "$(nproc)" --timeout 600 -LE long "$@"
