#!/usr/bin/env python3
"""Checks that PNG files are valid, of the expected size and not blank.

Standard library only (zlib + struct), so it runs wherever the figure pipeline runs.
A PNG passes when:
  - the signature, the chunk CRCs, IHDR (8-bit grey/RGB/RGBA, no interlace) and IEND are valid
    and the pixel data decompress and unfilter to exactly height rows of width pixels;
  - width x height is the expected size;
  - it is not blank: at least kMinInkFraction of the pixels differ from the background colour
    (the most frequent one) and the grey-level standard deviation is at least kMinGreyStd.

usage: check_png.py FILE:WIDTHxHEIGHT [FILE:WIDTHxHEIGHT ...]     exit 0 if all pass, 1 if not
"""
import struct
import sys
import zlib
from collections import Counter

# A real plot puts ink (axes, text, curves) on a few percent of its pixels; a blank or
# background-only image has none. 0.5 % leaves margin for sparse line plots (ours: 4-20 %).
kMinInkFraction = 0.005
# Grey-level (0-255) standard deviation: black text and lines on white give > 20; a blank
# page gives 0. 5 accepts faint plots and still rejects uniform ones.
kMinGreyStd = 5.0

SIGNATURE = b"\x89PNG\r\n\x1a\n"
CHANNELS = {0: 1, 2: 3, 4: 2, 6: 4}  # colour type -> samples per pixel (8-bit only)


def read_chunks(data):
    if data[:8] != SIGNATURE:
        raise ValueError("not a PNG (bad signature)")
    pos = 8
    while pos < len(data):
        if pos + 8 > len(data):
            raise ValueError("truncated chunk header")
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if len(body) != length or pos + 12 + length > len(data):
            raise ValueError("truncated chunk %r" % kind)
        (crc,) = struct.unpack(">I", data[pos + 8 + length:pos + 12 + length])
        if zlib.crc32(kind + body) & 0xFFFFFFFF != crc:
            raise ValueError("CRC mismatch in chunk %r" % kind)
        yield kind, body
        pos += 12 + length


def unfilter(raw, width, height, bpp):
    """Undoes the per-row PNG filters; returns the rows as bytearrays."""
    stride = width * bpp
    if len(raw) != height * (stride + 1):
        raise ValueError("pixel data size %d != %d" % (len(raw), height * (stride + 1)))
    rows = []
    prev = bytearray(stride)
    for y in range(height):
        start = y * (stride + 1)
        ftype = raw[start]
        line = bytearray(raw[start + 1:start + 1 + stride])
        if ftype == 0:
            pass
        elif ftype == 1:  # Sub
            for i in range(bpp, stride):
                line[i] = (line[i] + line[i - bpp]) & 0xFF
        elif ftype == 2:  # Up
            line = bytearray((a + b) & 0xFF for a, b in zip(line, prev))
        elif ftype == 3:  # Average
            for i in range(stride):
                left = line[i - bpp] if i >= bpp else 0
                line[i] = (line[i] + ((left + prev[i]) >> 1)) & 0xFF
        elif ftype == 4:  # Paeth
            for i in range(stride):
                a = line[i - bpp] if i >= bpp else 0
                b = prev[i]
                c = prev[i - bpp] if i >= bpp else 0
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pred = a if (pa <= pb and pa <= pc) else (b if pb <= pc else c)
                line[i] = (line[i] + pred) & 0xFF
        else:
            raise ValueError("unknown filter type %d in row %d" % (ftype, y))
        rows.append(line)
        prev = line
    return rows


def check(path, expected):
    with open(path, "rb") as f:
        data = f.read()
    header = None
    idat = []
    seen_end = False
    for kind, body in read_chunks(data):
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat.append(body)
        elif kind == b"IEND":
            seen_end = True
    if header is None or not idat or not seen_end:
        raise ValueError("missing IHDR, IDAT or IEND")
    width, height, depth, ctype, _, _, interlace = header
    if (width, height) != expected:
        raise ValueError("size %dx%d, expected %dx%d" % (width, height, *expected))
    if depth != 8 or ctype not in CHANNELS or interlace != 0:
        raise ValueError("unsupported format: depth %d, colour type %d, interlace %d"
                         % (depth, ctype, interlace))
    bpp = CHANNELS[ctype]
    rows = unfilter(zlib.decompress(b"".join(idat)), width, height, bpp)

    # Grey level of every pixel (alpha composited on white; colour averaged).
    greys = []
    for line in rows:
        if ctype == 0:
            greys.extend(line)
            continue
        if ctype == 4:
            grey = line[0::2]
        else:
            grey = [(r + g + b) // 3 for r, g, b in zip(line[0::bpp], line[1::bpp], line[2::bpp])]
        if ctype in (4, 6):
            alpha = line[bpp - 1::bpp]
            grey = [(v * a + 255 * (255 - a)) // 255 for v, a in zip(grey, alpha)]
        greys.extend(grey)
    n = len(greys)
    background, count = Counter(greys).most_common(1)[0]
    ink = 1.0 - count / n
    mean = sum(greys) / n
    std = (sum((g - mean) ** 2 for g in greys) / n) ** 0.5
    if ink < kMinInkFraction or std < kMinGreyStd:
        raise ValueError("blank: ink fraction %.4f (min %.4f), grey std %.2f (min %.1f)"
                         % (ink, kMinInkFraction, std, kMinGreyStd))
    return "%dx%d, ink %.1f %%, grey std %.1f" % (width, height, 100 * ink, std)


def main(argv):
    if len(argv) < 2:
        print(__doc__, file=sys.stderr)
        return 2
    failures = 0
    for spec in argv[1:]:
        path, _, size = spec.rpartition(":")
        w, _, h = size.partition("x")
        try:
            print("ok    %s: %s" % (path, check(path, (int(w), int(h)))))
        except (OSError, ValueError, zlib.error) as e:
            print("FAIL  %s: %s" % (path, e))
            failures += 1
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
