#!/usr/bin/env python3
"""Prints size and colour statistics of a PNG (8-bit RGB/RGBA, no libraries
needed) and exits non-zero when the image is blank (a single colour) or its
3D area holds no shaded object. Used by scripts/smoke-viewer.sh."""
import struct
import sys
import zlib


def read_png(path):
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise SystemExit(f"{path}: not a PNG")
    pos, idat, w = 8, b"", None
    while pos < len(data):
        (n,) = struct.unpack(">I", data[pos:pos + 4])
        kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + n]
        pos += 12 + n
        if kind == b"IHDR":
            w, h, depth, ctype = struct.unpack(">IIBB", body[:10])
            if depth != 8 or ctype not in (2, 6):
                raise SystemExit(f"{path}: unsupported PNG (depth {depth}, colour type {ctype})")
            bpp = 3 if ctype == 2 else 4
        elif kind == b"IDAT":
            idat += body
    raw = zlib.decompress(idat)
    stride = w * bpp
    rows, prev = [], bytearray(stride)
    for y in range(h):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b = prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        prev = line
    return w, h, bpp, rows


def main():
    path = sys.argv[1]
    w, h, bpp, rows = read_png(path)
    colours = set()
    for y in range(0, h, 4):
        r = rows[y]
        for x in range(0, w, 4):
            colours.add(r[x * bpp:x * bpp + 3])
    # The 3D area is right of the panel: sample its centre region.
    cx0, cx1 = int(w * 0.45), int(w * 0.85)
    cy0, cy1 = int(h * 0.3), int(h * 0.7)
    centre = set()
    for y in range(cy0, cy1, 3):
        r = rows[y]
        for x in range(cx0, cx1, 3):
            centre.add(r[x * bpp:x * bpp + 3])
    print(f"{path}: {w}x{h}, {len(colours)} colours sampled, {len(centre)} in the 3D area")
    if len(colours) < 8:
        raise SystemExit(f"{path}: the image is blank")
    if len(centre) < 8:
        raise SystemExit(f"{path}: the 3D area shows no shaded object")


main()
