#!/usr/bin/env python3
"""Joins lgh-bench motion --images frames (the reference | the tested-history image) into an animated GIF.

Usage: bench/scripts/motion_gif.py FOLDER out.gif [scale] [ms_per_frame]
Needs Pillow (Debian: python3-pil). docs/measurements.md, "Under motion", has the command behind the GIF.
"""
import pathlib
import sys

from PIL import Image


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    frames = sorted(pathlib.Path(sys.argv[1]).glob("frame_*.png"))
    if not frames:
        sys.exit(f"{sys.argv[1]}: no frame_*.png")
    scale = int(sys.argv[3]) if len(sys.argv) > 3 else 3
    duration = int(sys.argv[4]) if len(sys.argv) > 4 else 62
    images = []
    for f in frames:
        image = Image.open(f).convert("RGB")
        images.append(image.resize((image.width * scale, image.height * scale), Image.NEAREST))
    images[0].save(sys.argv[2], save_all=True, append_images=images[1:], duration=duration, loop=0, optimize=True)
    print(f"wrote {sys.argv[2]}: {len(images)} frames of {images[0].width} x {images[0].height}")


if __name__ == "__main__":
    main()
