#!/usr/bin/env python3
"""Finds a valid RASTERIZER_DESC whose 64-bit FNV-1a key hash (rhi/src/states,
fields hashed one by one, little-endian) equals a given hash, by a lattice
search: the test tests/gpu/free_threading_test.cpp uses one that collides with
the default SAMPLER_DESC's hash, the case where the device's old single state
cache returned a rasterizer state as a sampler.

FNV-1a steps h' = (h ^ b) * P, and h ^ b = h + d with d = (l ^ b) - l for the
low byte l of h, so after the 12 free bytes of DepthBias, DepthBiasClamp and
SlopeScaledDepthBias the state is h12 * P^12 + sum(d_i * P^(12-i)) (mod 2^64).
LLL finds small d_i hitting the state the fixed tail bytes need (the tail
steps are inverted from the target); a d_i is realisable when l + d_i is a
byte. Prints the desc as C++ field values.

usage: tools/find_rasterizer_hash_collision.py TARGET_HASH_HEX
"""
import itertools
import struct
import sys

from fractions import Fraction

P = 0x100000001B3
OFFSET = 0xCBF29CE484222325
MASK = (1 << 64) - 1
P_INV = pow(P, -1, 1 << 64)
FREE = 12  # DepthBias, DepthBiasClamp, SlopeScaledDepthBias


def step(h, byte):
    return ((h ^ byte) * P) & MASK


def words_bytes(words):
    return b"".join(struct.pack("<I", w & 0xFFFFFFFF) for w in words)


def lll(basis, delta=Fraction(3, 4)):
    """Textbook LLL over exact rationals (small dimension: plain Gram-Schmidt per swap)."""
    b = [list(r) for r in basis]
    n = len(b)

    def dot(u, v):
        return sum(x * y for x, y in zip(u, v))

    def gram_schmidt():
        star, mu = [], [[Fraction(0)] * n for _ in range(n)]
        for i in range(n):
            v = [Fraction(x) for x in b[i]]
            for j in range(i):
                mu[i][j] = dot(b[i], star[j]) / dot(star[j], star[j])
                v = [x - mu[i][j] * y for x, y in zip(v, star[j])]
            star.append(v)
        return star, mu

    star, mu = gram_schmidt()
    k = 1
    while k < n:
        for j in range(k - 1, -1, -1):
            q = round(mu[k][j])
            if q:
                b[k] = [x - q * y for x, y in zip(b[k], b[j])]
                star, mu = gram_schmidt()
        if dot(star[k], star[k]) >= (delta - mu[k][k - 1] ** 2) * dot(star[k - 1], star[k - 1]):
            k += 1
        else:
            b[k], b[k - 1] = b[k - 1], b[k]
            star, mu = gram_schmidt()
            k = max(k - 1, 1)
    return b


def short_solutions(target_sum):
    """Short vectors d with sum(d_i * P^(FREE-i)) == target_sum (mod 2^64)."""
    n, k, m = FREE, 1 << 40, 1 << 5
    rows = []
    for i in range(n):
        row = [0] * (n + 2)
        row[i] = 1
        row[n] = k * pow(P, FREE - i, 1 << 64)
        rows.append(row)
    rows.append([0] * n + [k << 64, 0])
    rows.append([0] * n + [-k * target_sum, m])
    basis = lll(rows)
    with_target = [r for r in basis if r[n] == 0 and abs(r[n + 1]) == m]
    homogeneous = [r for r in basis if r[n] == 0 and r[n + 1] == 0]
    for base in with_target:
        sign = 1 if base[n + 1] == m else -1
        for coeffs in itertools.product((-1, 0, 1), repeat=min(4, len(homogeneous))):
            v = [sign * base[i] + sum(c * h[i] for c, h in zip(coeffs, homogeneous)) for i in range(n)]
            yield v


def realise(h, deltas):
    out = []
    for d in deltas:
        low = h & 0xFF
        if not 0 <= low + d <= 255:
            return None
        byte = low ^ (low + d)
        out.append(byte)
        h = step(h, byte)
    return bytes(out)


def finite(f32_bytes):
    return (struct.unpack("<I", f32_bytes)[0] >> 23) & 0xFF != 0xFF


def main():
    target = int(sys.argv[1], 16)
    # FillMode, CullMode, FrontCounterClockwise | free | DepthClip, Scissor, Multisample, AntialiasedLine
    for fill, cull, ccw, clip, scissor, ms, aa in itertools.product((3, 2), (1, 2, 3), (0, 1), (1, 0), (0, 1),
                                                                    (0, 1), (0, 1)):
        h = OFFSET
        for b in words_bytes([fill, cull, ccw]):
            h = step(h, b)
        need = target  # invert the tail: h_i = (h_{i+1} * P^-1) ^ b_i
        for b in reversed(words_bytes([clip, scissor, ms, aa])):
            need = ((need * P_INV) & MASK) ^ b
        target_sum = (need - h * pow(P, FREE, 1 << 64)) & MASK
        for deltas in short_solutions(target_sum):
            free = realise(h, deltas)
            if free is None or not finite(free[4:8]) or not finite(free[8:12]):
                continue
            bias = struct.unpack("<i", free[0:4])[0]
            clamp, slope = (struct.unpack("<I", free[i:i + 4])[0] for i in (4, 8))
            print(f"FillMode={fill} CullMode={cull} FrontCounterClockwise={ccw} DepthBias={bias} "
                  f"DepthBiasClamp=0x{clamp:08X} SlopeScaledDepthBias=0x{slope:08X} DepthClipEnable={clip} "
                  f"ScissorEnable={scissor} MultisampleEnable={ms} AntialiasedLineEnable={aa}")
            return 0
    print("no solution found", file=sys.stderr)
    return 1


if __name__ == "__main__":
    sys.exit(main())
