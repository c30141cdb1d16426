#!/usr/bin/env bash
# Renders the README's pictures again with this checkout's binaries (BUILD, default build/) and the
# reference scenes in ../shared/scenes:
#   docs/sponza_cornell.png          lgh-render: Sponza with the sun (camera atrium, 640 x 360, exposure 1)
#                                    beside the Cornell box (360 x 360), 8 accumulated frames each
#   bench/results/viewer_sponza.png  lgh-viewer under Xvfb: 960 x 540, two frames, the window with its panel
# Needs xvfb-run (package xvfb) and Debian's python3 with PIL (python3-pil, which python3-matplotlib pulls
# in). The PNGs keep 7 bits per channel: the renders' last bit is noise and a third of the file's size.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD:-build}
sponza=../shared/scenes/sponza_sun/sponza_sun.gltf
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

"$build/lgh-render" "$sponza" --camera atrium --width 640 --height 360 --exposure 1 --frames 8 -q -o "$tmp/sponza.png"
"$build/lgh-render" data/cornell_box.gltf --width 360 --height 360 --frames 8 -q -o "$tmp/cornell.png"
xvfb-run -a -s "-screen 0 1280x1024x24" "$build/lgh-viewer" "$sponza" --width 960 --height 540 --exposure 1 -q \
  --script "frames=2;window-screenshot=$tmp/viewer.png;quit"

/usr/bin/python3 - "$tmp" <<'EOF'
import sys
from PIL import Image

tmp = sys.argv[1]
def seven_bits(image):
    return image.convert("RGB").point(lambda v: min(255, (v + 1) // 2 * 2))

sponza, cornell = Image.open(f"{tmp}/sponza.png"), Image.open(f"{tmp}/cornell.png")
gap = 6
both = Image.new("RGB", (sponza.width + gap + cornell.width, sponza.height), "white")
both.paste(sponza, (0, 0))
both.paste(cornell, (sponza.width + gap, 0))
seven_bits(both).save("docs/sponza_cornell.png", optimize=True)
seven_bits(Image.open(f"{tmp}/viewer.png")).save("bench/results/viewer_sponza.png", optimize=True)
EOF
ls -l docs/sponza_cornell.png bench/results/viewer_sponza.png
