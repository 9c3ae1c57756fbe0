#!/usr/bin/env python3
"""Writes the seeds of tests/fuzz/texture_corpus/ (docs/FUZZING.md): small valid DDS files
(legacy and DX10 headers, BC1/BC3/BC7, arrays, a cube map, a mip chain, 1D, 3D),
PNG/TGA/BMP images, and broken variants. Run from anywhere; rewrites the seed_*/broken_* files."""
import os, struct, zlib

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "texture_corpus")

def fourcc(s): return struct.unpack("<I", s.encode())[0]

def dds(width, height, mips=1, pf=(0x4, fourcc("DXT1"), 0, 0, 0, 0, 0), caps2=0, depth=0, dx10=None, data=b""):
    flags = 0x1 | 0x2 | 0x4 | 0x1000 | (0x20000 if mips > 1 else 0) | (0x800000 if depth else 0)
    header = struct.pack("<7I", 124, flags, height, width, 0, depth, mips) + b"\0" * 44
    header += struct.pack("<8I", 32, *pf)
    header += struct.pack("<5I", 0x1000, caps2, 0, 0, 0)
    ext = struct.pack("<5I", *dx10, 0) if dx10 else b""
    return b"DDS " + header + ext + data

DX10 = (0x4, fourcc("DX10"), 0, 0, 0, 0, 0)
RGBA8 = (0x41, 0, 32, 0xff, 0xff00, 0xff0000, 0xff000000)
BGRX8 = (0x40, 0, 32, 0xff0000, 0xff00, 0xff, 0)
LUM8 = (0x20000, 0, 8, 0xff, 0, 0, 0)
bc1 = struct.pack("<HHI", 0xF800, 0x001F, 0xFFAA5500)

def png(width, height, rgba):
    def chunk(kind, body): return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))
    rows = b"".join(b"\0" + rgba[y * width * 4:(y + 1) * width * 4] for y in range(height))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))

def tga(width, height, bgra):
    return struct.pack("<BBBHHBHHHHBB", 0, 0, 2, 0, 0, 0, 0, 0, width, height, 32, 8) + bgra

def bmp(width, height, bgr):
    row = (width * 3 + 3) & ~3
    pixels = b"".join(bgr[y * width * 3:(y + 1) * width * 3].ljust(row, b"\0") for y in range(height))
    info = struct.pack("<IiiHHIIiiII", 40, width, height, 1, 24, 0, len(pixels), 2835, 2835, 0, 0)
    return b"BM" + struct.pack("<IHHI", 14 + 40 + len(pixels), 0, 0, 54) + info + pixels

seeds = {
    "seed_bc1_legacy.dds": dds(4, 4, data=bc1),
    "seed_bc1_mips_8x8.dds": dds(8, 8, mips=4, data=bc1 * 7),
    "seed_dxt5_legacy.dds": dds(4, 4, pf=(0x4, fourcc("DXT5"), 0, 0, 0, 0, 0), data=b"\xff\x00" + b"\0" * 6 + bc1),
    "seed_bc7_dx10_array.dds": dds(4, 4, pf=DX10, dx10=(98, 3, 0, 2), data=bytes(range(32))),
    "seed_rgba8_cube.dds": dds(2, 2, pf=RGBA8, caps2=0xFE00, data=bytes(6 * 16)),
    "seed_bgrx8_legacy.dds": dds(3, 2, pf=BGRX8, data=bytes(range(24))),
    "seed_luminance8.dds": dds(5, 3, pf=LUM8, data=bytes(15)),
    "seed_r32f_1d_dx10.dds": dds(4, 1, pf=DX10, dx10=(41, 2, 0, 1), data=bytes(16)),
    "seed_rgba8_volume.dds": dds(2, 2, pf=RGBA8, caps2=0x200200, depth=2, data=bytes(2 * 16)),
    "seed_rgba16f_dx10_cube.dds": dds(1, 1, pf=DX10, dx10=(10, 3, 0x4, 1), data=bytes(6 * 8)),
    # Volumes with mip chains: each level's depth halves (4x4x4, 2x2x2, 1x1x1).
    "seed_rgba8_volume_mips.dds": dds(4, 4, mips=3, pf=RGBA8, caps2=0x200200, depth=4,
                                      data=bytes(range(256)) + bytes(32) + bytes(4)),
    "seed_bc1_dx10_volume_mips.dds": dds(8, 4, mips=2, pf=DX10, dx10=(71, 4, 0, 1), depth=2, data=bc1 * 5),
    "seed_rgba_2x2.png": png(2, 2, bytes([255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 128])),
    "seed_bgra_2x2.tga": tga(2, 2, bytes(range(16))),
    "seed_bgr_3x2.bmp": bmp(3, 2, bytes(range(18))),
    "broken_truncated_bc1.dds": dds(8, 8, mips=4, data=bc1 * 3),
    "broken_truncated_volume.dds": dds(4, 4, mips=3, pf=RGBA8, caps2=0x200200, depth=4, data=bytes(256 + 32 + 3)),
    "broken_dx10_volume_array.dds": dds(4, 4, pf=DX10, dx10=(71, 4, 0, 2), depth=2, data=bc1 * 4),
    "broken_magic.dds": b"DDX " + dds(4, 4, data=bc1)[4:],
    "broken_overflow.dds": dds(0xFFFFFFF0, 0xFFFFFFF0, mips=32, data=bc1),
    "broken_dx10_format.dds": dds(4, 4, pf=DX10, dx10=(255, 3, 0, 1), data=bc1),
    "broken_png_crc.png": png(2, 2, bytes(16))[:-5] + b"\0\0\0\0\0",
}
os.makedirs(OUT, exist_ok=True)
for name, data in seeds.items():
    with open(os.path.join(OUT, name), "wb") as f:
        f.write(data)
print(f"wrote {len(seeds)} files to {OUT}")
