#!/usr/bin/env python3
"""Writes the procedural textures of lesson 33 into lessons/textures/ (standard library only).

bricks.png            albedo, sRGB: running-bond bricks with a per-brick tint, grey mortar
bricks_roughness.png  roughness, linear grey: mortar 0.9, bricks 0.35-0.55
bricks_normal.png     tangent-space normal map, linear: n = 2c - 1 from the height field
                      (bricks raised, bevelled edges, mortar grooves), +x right, +y up (OpenGL)
bricks_ao.png         ambient occlusion, linear grey: 1 on the brick faces, down to 0.3 at the
                      bottom of the mortar grooves (the share of the sky a groove sees)
plate.png             base colour, sRGB: red paint, scratched through to bare steel
plate_metallic.png    metallic, linear grey: 0 on the paint, 1 in the scratches

Deterministic: the tints come from an integer hash, so running it again gives the same bytes.
Usage: python3 tools/make_textures.py [out_dir]
"""
import math
import struct
import sys
import zlib
from pathlib import Path

N = 128  # texels per side
BRICKS_X, BRICKS_Y = 4, 8  # bricks per row, rows
MORTAR = 0.06  # mortar half-width, in brick heights


def png(path, rows, channels):
    """A PNG of 8-bit rows (lists of ints), grey (1) or RGB (3)."""
    colour = {1: 0, 3: 2}[channels]
    raw = b"".join(b"\x00" + bytes(r) for r in rows)
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    data = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", N, N, 8, colour, 0, 0, 0))
    data += chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
    path.write_bytes(data)


def hash01(i, j):
    h = (i * 73856093) ^ (j * 19349663) ^ 0x5BD1E995
    h = (h * 2654435761) & 0xFFFFFFFF
    h ^= h >> 15
    return (h & 0xFFFF) / 65535.0


def brick(u, v):
    """(brick id, distance to the nearest mortar line in brick heights) at uv in [0, 1)."""
    y = v * BRICKS_Y
    row = int(math.floor(y))
    x = u * BRICKS_X + (0.5 if row % 2 else 0.0)
    col = int(math.floor(x)) % BRICKS_X
    fy, fx = y - row, x - math.floor(x)
    # Bricks are 2:1 in uv units of rows, so x distances count double.
    d = min(fy, 1 - fy, (min(fx, 1 - fx)) * BRICKS_Y / BRICKS_X)
    return (row, col), d


def height(u, v):
    _, d = brick(u % 1.0, v % 1.0)
    # Mortar at 0, a bevel up to the brick face at 1.
    return max(0.0, min(1.0, (d - MORTAR) / 0.08))


def srgb_encode(c):
    c = max(0.0, min(1.0, c))
    return 12.92 * c if c <= 0.0031308 else 1.055 * c ** (1 / 2.4) - 0.055


def main(out):
    out.mkdir(parents=True, exist_ok=True)
    albedo, rough, normal, ao = [], [], [], []
    for j in range(N):
        a_row, r_row, n_row, o_row = [], [], [], []
        v = 1.0 - (j + 0.5) / N  # row 0 is the top, v = 1
        for i in range(N):
            u = (i + 0.5) / N
            (row, col), d = brick(u, v)
            t = hash01(row, col)
            if d < MORTAR:
                lin, r = (0.35, 0.34, 0.32), 0.9
            else:
                lin = (0.45 + 0.2 * t, 0.16 + 0.06 * t, 0.10 + 0.03 * t)
                r = 0.35 + 0.2 * hash01(col + 17, row + 5)
            a_row += [round(255 * srgb_encode(c)) for c in lin]
            r_row.append(round(255 * r))
            # Central differences of the height field, one texel apart; strength 2.
            e = 1.0 / N
            dhdu = (height(u + e, v) - height(u - e, v)) / 2
            dhdv = (height(u, v + e) - height(u, v - e)) / 2
            nx, ny, nz = -2.0 * dhdu, -2.0 * dhdv, 1.0
            ln = math.sqrt(nx * nx + ny * ny + nz * nz)
            n_row += [round(255 * (c / ln * 0.5 + 0.5)) for c in (nx, ny, nz)]
            o_row.append(round(255 * (0.3 + 0.7 * height(u, v))))
        albedo.append(a_row)
        rough.append(r_row)
        normal.append(n_row)
        ao.append(o_row)
    png(out / "bricks.png", albedo, 3)
    png(out / "bricks_roughness.png", rough, 1)
    png(out / "bricks_normal.png", normal, 3)
    png(out / "bricks_ao.png", ao, 1)
    plate(out)


def scratch_distance(u, v, segments):
    """Distance in uv from (u, v) to the nearest scratch segment."""
    best = 1.0
    for (ax, ay), (bx, by) in segments:
        dx, dy = bx - ax, by - ay
        t = max(0.0, min(1.0, ((u - ax) * dx + (v - ay) * dy) / (dx * dx + dy * dy)))
        best = min(best, math.hypot(u - ax - t * dx, v - ay - t * dy))
    return best


def plate(out):
    """Red paint over steel, with scratches through the paint (base colour and metallic)."""
    segments = []
    for k in range(14):
        ax, ay = 0.08 + 0.84 * hash01(k, 1), 0.08 + 0.84 * hash01(k, 2)
        angle = math.pi * hash01(k, 3)
        length = 0.12 + 0.3 * hash01(k, 4)
        segments.append(((ax, ay), (ax + length * math.cos(angle), ay + length * math.sin(angle))))
    colour, metal = [], []
    for j in range(N):
        c_row, m_row = [], []
        v = 1.0 - (j + 0.5) / N
        for i in range(N):
            u = (i + 0.5) / N
            # Scratches 1.5 texels wide, antialiased over one texel.
            m = max(0.0, min(1.0, (1.5 / N - scratch_distance(u, v, segments)) * N + 0.5))
            paint, steel = (0.55, 0.04, 0.03), (0.56, 0.57, 0.58)
            lin = [p + (s_ - p) * m for p, s_ in zip(paint, steel)]
            c_row += [round(255 * srgb_encode(c)) for c in lin]
            m_row.append(round(255 * m))
        colour.append(c_row)
        metal.append(m_row)
    png(out / "plate.png", colour, 3)
    png(out / "plate_metallic.png", metal, 1)


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent / "lessons" / "textures")
