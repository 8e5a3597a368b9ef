#!/usr/bin/env python3
"""Draws the application icon (resources/icons/): the scalable SVG and PNGs at the hicolor
sizes, rasterised here with 4x4 supersampling (no imaging library needed).

The icon: a voxel cube on a dark rounded square, its three faces lit from deep blue
through orange to near white (a high dynamic range of one surface), with a bright spot.
Run from the repository root: python3 tools/make_icons.py
"""
import struct
import zlib

BG = (0x1d, 0x25, 0x30)
# Shapes in a 256-unit square: (colour, polygon) drawn in order.
TOP = ((0xff, 0xe9, 0xb8), [(128, 44), (210, 88), (128, 132), (46, 88)])
LEFT = ((0x2b, 0x4c, 0x8c), [(46, 88), (128, 132), (128, 222), (46, 178)])
RIGHT = ((0xf0, 0x8a, 0x24), [(128, 132), (210, 88), (210, 178), (128, 222)])
EDGE = (0x10, 0x14, 0x1a)
SHAPES = [TOP, LEFT, RIGHT]
SUN = ((0xff, 0xff, 0xff), (150, 84, 15))  # centre x, y, radius: the highlight on the top face
RADIUS = 44  # corner radius of the background square


def inside_poly(x, y, poly):
    c = False
    n = len(poly)
    for i in range(n):
        (x1, y1), (x2, y2) = poly[i], poly[(i + 1) % n]
        if (y1 > y) != (y2 > y) and x < (x2 - x1) * (y - y1) / (y2 - y1) + x1:
            c = not c
    return c


def near_edge(x, y, poly, width):
    n = len(poly)
    for i in range(n):
        (x1, y1), (x2, y2) = poly[i], poly[(i + 1) % n]
        dx, dy = x2 - x1, y2 - y1
        t = max(0.0, min(1.0, ((x - x1) * dx + (y - y1) * dy) / (dx * dx + dy * dy)))
        if (x - x1 - t * dx) ** 2 + (y - y1 - t * dy) ** 2 <= width * width:
            return True
    return False


def in_background(x, y):
    r = RADIUS
    cx = min(max(x, 8 + r), 248 - r)
    cy = min(max(y, 8 + r), 248 - r)
    return (x - cx) ** 2 + (y - cy) ** 2 <= r * r


def sample(x, y):
    """Colour and coverage (0 or 1) at a point of the 256-unit square."""
    if not in_background(x, y):
        return (0, 0, 0), 0
    colour = BG
    for c, poly in SHAPES:
        if inside_poly(x, y, poly):
            colour = c
    if any(near_edge(x, y, poly, 2.5) for _, poly in SHAPES) and any(inside_poly(x, y, p) for _, p in SHAPES):
        colour = EDGE
    (sx, sy, sr) = SUN[1]
    d2 = (x - sx) ** 2 + (y - sy) ** 2
    if d2 <= sr * sr:
        k = 1 - d2 / (sr * sr)
        colour = tuple(int(a + (b - a) * k) for a, b in zip(colour, SUN[0]))
    return colour, 1


def png(size):
    ss = 4
    rows = []
    for py in range(size):
        row = bytearray([0])
        for px in range(size):
            acc = [0, 0, 0]
            cov = 0
            for j in range(ss):
                for i in range(ss):
                    x = (px + (i + 0.5) / ss) * 256 / size
                    y = (py + (j + 0.5) / ss) * 256 / size
                    c, a = sample(x, y)
                    if a:
                        cov += 1
                        for k in range(3):
                            acc[k] += c[k]
            n = ss * ss
            if cov:
                row += bytes(int(acc[k] / cov + 0.5) for k in range(3))
            else:
                row += b"\0\0\0"
            row.append(int(255 * cov / n + 0.5))
        rows.append(bytes(row))
    raw = b"".join(rows)

    def chunk(tag, data):
        return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF)

    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", size, size, 8, 6, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def svg():
    def pts(poly):
        return " ".join(f"{x},{y}" for x, y in poly)

    def hexc(c):
        return "#%02x%02x%02x" % c

    faces = "\n".join(
        f'  <polygon points="{pts(p)}" fill="{hexc(c)}" stroke="{hexc(EDGE)}" stroke-width="5" stroke-linejoin="round"/>'
        for c, p in SHAPES)
    (sx, sy, sr) = SUN[1]
    return f'''<?xml version="1.0" encoding="UTF-8"?>
<svg xmlns="http://www.w3.org/2000/svg" width="256" height="256" viewBox="0 0 256 256">
  <defs>
    <radialGradient id="sun">
      <stop offset="0" stop-color="#ffffff" stop-opacity="1"/>
      <stop offset="1" stop-color="#ffffff" stop-opacity="0"/>
    </radialGradient>
  </defs>
  <rect x="8" y="8" width="240" height="240" rx="{RADIUS}" fill="{hexc(BG)}"/>
{faces}
  <circle cx="{sx}" cy="{sy}" r="{sr}" fill="url(#sun)"/>
</svg>
'''


if __name__ == "__main__":
    for s in (16, 24, 32, 48, 64, 128, 256, 512):
        with open(f"resources/icons/hdrfusion-studio-{s}.png", "wb") as f:
            f.write(png(s))
    with open("resources/icons/hdrfusion-studio.svg", "w") as f:
        f.write(svg())
