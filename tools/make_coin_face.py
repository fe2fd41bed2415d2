#!/usr/bin/python3
"""Draws assets/coin_face.png, the pattern both faces of the coin carry (the shader colours it:
brass with blue enamel on the obverse, silver with red on the reverse).

Red channel: relief shading of the metal (1 = plain; darker for the raised bead near the rim,
the twelve hour ticks and the engraved ring). Green channel: where the enamel goes (the bar
along body +X from the centre to 0.78 of the radius, and a dot at (-0.30, 0.48)). Texture
coordinates: u = (X / a + 1) / 2, v = (Y / a + 1) / 2, so image right is body +X and image up
(the PNG's first row is v = 1) is body +Y. Drawn at 4x and downsampled, so edges are smooth.

    /usr/bin/python3 tools/make_coin_face.py
"""
import math
import pathlib

from PIL import Image, ImageDraw

SIZE = 256
SUPER = 4
ROOT = pathlib.Path(__file__).resolve().parent.parent


def main() -> None:
    n = SIZE * SUPER
    relief = Image.new("L", (n, n), 255)
    enamel = Image.new("L", (n, n), 0)
    r, e = ImageDraw.Draw(relief), ImageDraw.Draw(enamel)

    def to_pixels(x: float, y: float) -> tuple[float, float]:  # body units of the radius -> image pixels
        return (x + 1) / 2 * n, (1 - y) / 2 * n

    def circle(draw: ImageDraw.ImageDraw, cx: float, cy: float, radius: float, fill: int) -> None:
        (x0, y0), (x1, y1) = to_pixels(cx - radius, cy + radius), to_pixels(cx + radius, cy - radius)
        draw.ellipse([x0, y0, x1, y1], fill=fill)

    circle(r, 0, 0, 0.92, 184)   # raised bead near the rim
    circle(r, 0, 0, 0.86, 255)
    circle(r, 0, 0, 0.70, 214)   # engraved ring inside the ticks
    circle(r, 0, 0, 0.68, 255)
    for hour in range(12):
        a = 2 * math.pi * hour / 12
        c, s = math.cos(a), math.sin(a)
        w = 0.022
        corners = [(0.74 * c - w * s, 0.74 * s + w * c), (0.82 * c - w * s, 0.82 * s + w * c),
                   (0.82 * c + w * s, 0.82 * s - w * c), (0.74 * c + w * s, 0.74 * s - w * c)]
        r.polygon([to_pixels(x, y) for x, y in corners], fill=170)
    (x0, y0), (x1, y1) = to_pixels(0.12, 0.075), to_pixels(0.78, -0.075)
    e.rectangle([x0, y0, x1, y1], fill=255)
    circle(e, -0.30, 0.48, 0.11, 255)

    blank = Image.new("L", (n, n), 0)
    face = Image.merge("RGB", (relief, enamel, blank)).resize((SIZE, SIZE), Image.LANCZOS)
    out = ROOT / "assets" / "coin_face.png"
    face.save(out, optimize=True)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
