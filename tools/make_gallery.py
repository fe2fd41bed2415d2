#!/usr/bin/python3
"""Renders one still of the built-in default scene and of every scene in examples/ with
build/coinroll and tiles them into docs/gallery.png (the README's gallery), in that order.
Run from the repository root after building:

    /usr/bin/python3 tools/make_gallery.py [--time 3] [--columns 4] [--coinroll build/coinroll]
                                           [--output docs/gallery.png] [SCENE ...]

SCENE ...: tile these scene files instead of the built-in default and examples/*.json.
"""
import argparse
import json
import pathlib
import subprocess
import sys
import tempfile

from PIL import Image  # Debian's python3-pil, which python3-matplotlib installs

ROOT = pathlib.Path(__file__).resolve().parent.parent


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--time", type=float, default=3.0, help="simulated time of each still, s (clamped to the scene)")
    parser.add_argument("--columns", type=int, default=6)
    parser.add_argument("--output", default=str(ROOT / "docs" / "gallery.png"))
    parser.add_argument("--coinroll", default=str(ROOT / "build" / "coinroll"), help="the program (default: build/coinroll)")
    parser.add_argument("scenes", nargs="*", type=pathlib.Path, help="scene files (default: the built-in one and examples/)")
    args = parser.parse_args()

    # None: the built-in default scene
    scenes = args.scenes or [None] + sorted((ROOT / "examples").glob("*.json"))
    tiles = []
    with tempfile.TemporaryDirectory() as tmp:
        for scene in scenes:
            name = scene.stem if scene else "default"
            duration = json.loads(scene.read_text())["duration"] if scene else args.time
            still = pathlib.Path(tmp) / (name + ".png")
            subprocess.run([args.coinroll, "still", *([str(scene)] if scene else []),
                            "--time", str(min(args.time, duration)), "-o", str(still),
                            "--set", "render.width=320", "--set", "render.height=180", "--set", "render.hud=false"],
                           check=True, stderr=subprocess.DEVNULL)
            tiles.append(Image.open(still).convert("RGB"))
    width, height = tiles[0].size
    rows = (len(tiles) + args.columns - 1) // args.columns
    sheet = Image.new("RGB", (width * args.columns, height * rows), "white")
    for i, tile in enumerate(tiles):
        sheet.paste(tile, ((i % args.columns) * width, (i // args.columns) * height))
    sheet.save(args.output, optimize=True)
    print(f"wrote {args.output}: {', '.join(s.stem if s else 'default' for s in scenes)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
