#!/usr/bin/env bash
# The README's picture and looping animation of the default scene (docs/images/showcase.png and .gif):
# renders assets/scenes/showcase.json as tools/run.sh does (64 frames after a 90-frame warm-up, the shipped
# all-orders network), then takes frame 24 (the key light still on the camera's side) as the picture and the
# 64 frames, 256 pixels wide, 15 per second, as a looping GIF with one 128-colour palette (ffmpeg's
# palettegen/paletteuse).
#   tools/readme_media.sh [RENDER_DIR]      (default out/showcase; rendered unless it holds 64 frames)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$root/tools/deps.sh"
source "$root/tools/build.sh"
frames="${1:-$root/out/showcase}"
if [ ! -f "$frames/frame_0063.png" ]; then
  "$root/build/src/app/sixway" render --scene "$root/assets/scenes/showcase.json" --frames 64 --out "$frames" --force
fi
images="$root/docs/images"
cp "$frames/frame_0024.png" "$images/showcase.png"
ffmpeg -loglevel error -y -framerate 15 -i "$frames/frame_%04d.png" \
  -vf "scale=256:-1:flags=lanczos,split[a][b];[a]palettegen=max_colors=128[p];[b][p]paletteuse=dither=bayer" \
  -loop 0 "$images/showcase.gif"
echo "sixway: wrote $images/showcase.png and $images/showcase.gif"
