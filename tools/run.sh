#!/usr/bin/env bash
# Installs what is missing, builds, and runs sixway headless into out/.
# Until the renderer lands (issue #5) the most complete command is `sixway info`, which opens
# the Vulkan device with validation on and writes its description to out/info.json.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$root/tools/deps.sh"
source "$root/tools/build.sh"
mkdir -p "$root/out"
"$root/build/src/app/sixway" info --validate --report "$root/out/info.json" --force
echo "sixway: wrote $root/out/info.json"
