#!/usr/bin/env python3
"""Writes the small pictures scenes/textured.rib reads (scenes/textures/*.png).

Standard library only: each picture is a function of the pixel centre, stored as 8-bit RGB PNG.
Run from the repository root: python3 tools/make_scene_textures.py
"""
import math
import struct
import zlib
from pathlib import Path


def write_png(path, w, h, pixel):
    rows = b""
    for y in range(h):
        row = bytearray([0])  # filter: none
        for x in range(w):
            r, g, b = pixel((x + 0.5) / w, (y + 0.5) / h)
            row += bytes(max(0, min(255, round(c * 255))) for c in (r, g, b))
        rows += bytes(row)

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b"")
    path.write_bytes(png)


def mix(a, b, f):
    return tuple(x + (y - x) * f for x, y in zip(a, b))


def tile(s, t):
    """Seamless soft tiles: terracotta squares in cream grout (periodic in s and t)."""
    edge = min(math.sin(math.pi * s), math.sin(math.pi * t))
    f = min(1.0, max(0.0, (edge - 0.12) / 0.18))
    return mix((0.93, 0.88, 0.78), (0.75, 0.36, 0.22), f)


def globe(s, t):
    """Latitude bands coloured by longitude."""
    band = 0.5 + 0.5 * math.cos(6 * math.pi * t)
    hue = mix((0.2, 0.45, 0.85), (0.25, 0.75, 0.35), 0.5 + 0.5 * math.sin(2 * math.pi * s))
    return mix((0.95, 0.95, 0.9), hue, band)


def sky(s, t):
    """A lat-long sky (z up, as RenderMan's lat-long maps are): blue above, warm ground below."""
    if t < 0.5:
        return mix((0.35, 0.55, 0.95), (0.85, 0.9, 1.0), t / 0.5)
    return mix((0.55, 0.45, 0.3), (0.3, 0.25, 0.2), (t - 0.5) / 0.5)


if __name__ == "__main__":
    out = Path(__file__).resolve().parent.parent / "scenes" / "textures"
    out.mkdir(parents=True, exist_ok=True)
    write_png(out / "tile.png", 64, 64, tile)
    write_png(out / "globe.png", 64, 32, globe)
    write_png(out / "sky.png", 64, 32, sky)
