#!/usr/bin/env python3
"""Writes the seed corpus of the `scene`, `paths_agree` and `damage` fuzz targets.

Each seed, `corpus/<target>/seed-<name>`, is a `SceneInput` (fuzz/src/lib.rs) encoded the way
`arbitrary` 1.x decodes it (the `seed-` prefix keeps it clear of the hex names libFuzzer gives
the inputs it finds, which git ignores): an enum variant is a little-endian u32 `v` selecting
variant `(v * count) >> 32`; integers are little-endian; a bool is a byte whose low bit is the
value; a `Vec` is a sequence of elements each preceded by a byte 1, ended by a byte 0. Numbers
are written as `Num::Bits` (exact f32) unless a seed is about the edge-value table. Run:

    python3 fuzz/seeds.py
"""
import os
import struct

NUM_VARIANTS = 5  # Small, Fraction, Power, Special, Bits
SPECIAL = 3
BITS = 4


def variant(i, count):
    return struct.pack("<I", ((2 * i + 1) << 32) // (2 * count))


def num(x):
    """An exact f32 (`Num::Bits`); already encoded numbers pass through."""
    if isinstance(x, bytes):
        return x
    return variant(BITS, NUM_VARIANTS) + struct.pack("<f", x)


def special(index):
    """An entry of the edge-value table (`Num::Special`)."""
    return variant(SPECIAL, NUM_VARIANTS) + bytes([index])


def v3(x, y, z):
    return b"".join(num(n) for n in (x, y, z))


MODELS = 5  # Phong, BlinnPhong, Lambert, NormalizedPhong, NormalizedBlinnPhong
SURFACES = 3  # Dielectric, Fresnel(ior), Metal(index)
PHONG = variant(0, MODELS)
BLINN_PHONG = variant(1, MODELS)
LAMBERT = variant(2, MODELS)


def lobe(weight=0.0, n=1.0):
    return num(weight) + num(n)


def dielectric():
    return variant(0, SURFACES)


def fresnel(ior):
    return variant(1, SURFACES) + num(ior)


def metal(index):
    """0 gold, 1 copper, 2 bronze."""
    return variant(2, SURFACES) + bytes([index])


def normalized(surface, lobes=(), blinn=False):
    """A normalized model (`ModelIn::NormalizedPhong` or `NormalizedBlinnPhong`) with lobes 1
    and 2 (`lobes` as (weight, n) pairs; missing ones have weight 0)."""
    more = list(lobes) + [(0.0, 1.0)] * (2 - len(lobes))
    return variant(4 if blinn else 3, MODELS) + surface + b"".join(lobe(w, n) for w, n in more)


def sphere(center, radius, albedo=(0.18, 0.18, 0.18), kd=0.8, ks=0.2, n=50.0, blinn=False, model=None):
    """`model`: encoded bytes of a model (PHONG, LAMBERT, normalized(...), ...); by default
    classic Phong, or classic Blinn-Phong if `blinn`."""
    if model is None:
        model = BLINN_PHONG if blinn else PHONG
    return b"\x01" + v3(*center) + num(radius) + v3(*albedo) + num(kd) + num(ks) + num(n) + model


def distant(direction, color=(1.0, 1.0, 1.0), intensity=2.0):
    return b"\x01" + variant(0, 2) + v3(*direction) + v3(*color) + num(intensity)


def point(position, color=(1.0, 1.0, 1.0), intensity=50.0):
    return b"\x01" + variant(1, 2) + v3(*position) + v3(*color) + num(intensity)


LINEAR, LINEAR_DITHERED, SRGB, SRGB_DITHERED = range(4)


def scene(camera, spheres, lights, width, height, rows=(0, 0), background=(0.1, 0.2, 0.3),
          encoding=LINEAR, radii=()):
    """`width` is the image width (1..=67), encoded as `width - 1`; `encoding` indexes
    `ENCODINGS` (linear, linear dithered, sRGB, sRGB dithered); `radii` are the point
    lights' radii, in order (the last field: a `Vec` that the end of the input ends, so a
    seed without radii ends before it and has only point lights)."""
    position, look_at, up, vfov = camera
    out = v3(*position) + v3(*look_at) + v3(*up) + num(vfov)
    out += v3(*background)
    out += b"".join(spheres) + b"\x00"
    out += b"".join(lights) + b"\x00"
    out += bytes([width - 1]) + struct.pack("<H", height) + struct.pack("<HH", *rows)
    out += bytes([encoding])
    out += b"".join(b"\x01" + num(r) for r in radii)
    return out


FRONT = ((0.0, 0.0, 5.0), (0.0, 0.0, 0.0), (0.0, 1.0, 0.0), 40.0)
UNIT = sphere((0.0, 0.0, 0.0), 1.0)

SEEDS = {
    # The shared exponent series: five spheres (the fifth exceeds the capacity of 4).
    "exponent-series": scene(
        ((0.0, 1.0, 12.0), (0.0, 1.0, 0.0), (0.0, 1.0, 0.0), 36.87),
        [sphere((x, 1.0, 0.0), 0.9, ks=ks, n=n) for x, ks, n in
         [(-4.0, 0.04, 2.0), (-2.0, 0.08, 10.0), (0.0, 0.1, 50.0), (2.0, 0.15, 250.0), (4.0, 0.2, 1250.0)]],
        [distant((-0.4347962, -0.8416416, 0.3202994), intensity=5.0)],
        67, 49, rows=(24, 20), background=(0.235294, 0.67451, 0.843137)),
    "point-and-distant-blinn": scene(
        FRONT,
        [sphere((0.0, 0.0, 0.0), 1.0, albedo=(0.5, 0.2, 0.1), n=80.0, blinn=True),
         sphere((1.5, 0.5, -1.0), 0.6)],
        [point((2.0, 2.0, 3.0), intensity=200.0), distant((1.0, -1.0, -1.0))],
        33, 21, rows=(10, 7)),
    "camera-inside-sphere": scene(
        FRONT, [sphere((0.0, 0.0, 5.0), 2.0), UNIT], [point((0.0, 0.5, 5.0))], 17, 11, rows=(5, 0)),
    "light-inside-sphere": scene(
        FRONT, [sphere((-1.2, 0.0, 0.0), 1.0), sphere((1.2, 0.0, 0.0), 1.0)],
        [point((1.2, 0.0, 0.0))], 31, 15, rows=(7, 3)),
    "point-light-at-hit-point": scene(
        FRONT, [UNIT], [point((0.0, 0.0, 1.0))], 9, 9, rows=(4, 3)),
    # Regression: a subnormal direction normalized to NaN.
    "subnormal-directions": scene(
        ((0.0, 0.0, 5.0), (0.0, 0.0, 0.0), (0.0, 1e-40, 0.0), 40.0), [UNIT],
        [distant((-1e-45, 0.0, -1e-45))], 9, 9, rows=(4, 2)),
    # Regression: kd*albedo*arriving overflowed to inf.
    "brightest-light-on-surface": scene(
        FRONT, [sphere((0.0, 0.0, 0.0), 1.0, albedo=(1e6, 1e6, 1e6), kd=1e6, ks=1e6, n=1.0)],
        [point((0.0, 0.0, 1.0000001), color=(1e6, 1e6, 1e6), intensity=1e12)] * 3, 9, 9, rows=(4, 4)),
    # Regression: a row tangent to a sphere lost its span.
    "tangent-row": scene(
        ((0.25, 4.25, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, -0.25), 6.25), [sphere((0.0, 0.0, 6.25), 6.25)],
        [], 1, 1, background=(6.25, 0.0, 0.0)),
    # Regression: a radius whose square underflows.
    "tiny-radius": scene(
        FRONT, [sphere((0.0, 0.0, 0.0), 1.1754944e-38), sphere((0.0, 0.0, 0.0), 1e-18)],
        [distant((0.0, 0.0, -1.0))], 9, 9, rows=(4, 4)),
    # Regression: a light within 1e-19 of the hit points (subnormal d²), black red channel.
    "tiny-fov-light-on-surface": scene(
        ((0.0, 0.0, 5.0), (0.0, 0.0, 0.0), (0.0, 1.0, 0.0), 1.6432439e-19), [UNIT],
        [point((0.0, 0.0, 1.0), color=(0.0, 40.0, 0.1), intensity=0.2)], 36, 58982, rows=(39322, 29491)),
    "extreme-fov": scene(
        ((0.0, 0.0, 5.0), (0.0, 0.0, 0.0), (0.0, 1.0, 0.0), special(19)), [UNIT], [distant((0.0, -1.0, -1.0))],
        65, 65, rows=(32, 31)),
    # Every model in one row, under a point light and a distant light, sRGB dithered.
    "every-model": scene(
        ((0.0, 0.0, 9.0), (0.0, 0.0, 0.0), (0.0, 1.0, 0.0), 40.0),
        [sphere((-3.0, 0.0, 0.0), 0.9, albedo=(0.8, 0.3, 0.2), kd=0.9, model=LAMBERT),
         sphere((-1.0, 0.0, 0.0), 0.9, kd=0.6, ks=0.4, n=200.0,
                model=normalized(fresnel(1.5), [(0.2, 20.0)])),
         sphere((1.0, 0.0, 0.0), 0.9, kd=0.0, ks=0.6, n=400.0,
                model=normalized(metal(0), [(0.3, 40.0)], blinn=True)),
         sphere((3.0, 0.0, 0.0), 0.9, kd=0.3, ks=0.4, n=1000.0,
                model=normalized(dielectric(), [(0.2, 100.0), (0.1, 1.0)], blinn=True))],
        [point((0.0, 4.0, 6.0), intensity=300.0), distant((-1.0, -1.0, -1.0))],
        67, 31, rows=(15, 12), encoding=SRGB_DITHERED),
    # A row of spheres under a sphere light above it: soft shadows and widened lobes.
    "row-sphere-light": scene(
        ((0.0, 0.0, 9.0), (0.0, 0.0, 0.0), (0.0, 1.0, 0.0), 40.0),
        [sphere((x, 0.0, 0.0), 0.9, ks=0.4, n=n) for x, n in
         [(-3.0, 5.0), (-1.0, 50.0), (1.0, 400.0), (3.0, 2000.0)]],
        [point((2.0, 3.0, 2.0), intensity=300.0)],
        67, 31, rows=(15, 8), radii=(0.8,)),
    # A sphere light almost touching a sphere, and a tiny one far away.
    "sphere-lights-near-and-tiny": scene(
        FRONT, [sphere((0.0, 0.0, 0.0), 1.0), sphere((1.5, 0.0, -1.0), 0.5)],
        [point((0.0, 0.0, 2.0000002), intensity=20.0), point((0.0, 900.0, 0.0), intensity=1e7)],
        31, 23, rows=(11, 5), radii=(1.0, 1e-6)),
    # Metals: copper and bronze, normalized Phong, linear dithered into every format.
    "metals": scene(
        FRONT,
        [sphere((-0.6, 0.0, 0.0), 0.5, ks=1.0, n=80.0, model=normalized(metal(1))),
         sphere((0.6, 0.0, 0.0), 0.5, ks=0.5, n=8.0, model=normalized(metal(2), [(0.5, 300.0)]))],
        [distant((0.0, -0.3, -1.0))], 41, 21, rows=(10, 9), encoding=LINEAR_DITHERED),
    # Options at the edges of validation: ior just above 1, the largest ior, a lobe with the
    # largest exponent, a lobe weight of 0 with any exponent; sRGB.
    "edge-options": scene(
        FRONT,
        [sphere((0.0, 0.0, 0.0), 1.0, ks=1.0, n=1e6,
                model=normalized(fresnel(1.0000001), [(1e6, 1e6), (0.0, 1.0)])),
         sphere((1.0, 1.0, -1.0), 0.5, n=0.001, model=normalized(fresnel(1e6), [(1.0, 0.001)], blinn=True))],
        [distant((0.0, 0.0, -1.0))], 9, 9, rows=(4, 4), encoding=SRGB),
    # Refused options: NaN ior, ior 1, a negative lobe weight, NaN lobe exponent.
    "bad-options": scene(
        FRONT,
        [sphere((0.0, 0.0, 0.0), 1.0, model=normalized(fresnel(special(0)))),
         sphere((0.0, 0.0, 0.0), 1.0, model=normalized(fresnel(1.0))),
         sphere((0.0, 0.0, 0.0), 1.0, model=normalized(dielectric(), [(-0.5, 10.0)])),
         sphere((0.0, 0.0, 0.0), 1.0, model=normalized(metal(2), [(0.5, special(0))], blinn=True)),
         UNIT],
        [distant((0.0, 0.0, -1.0))], 9, 9, rows=(4, 4), encoding=LINEAR),
    # Edge-value table entries in every field.
    "edge-values": scene(
        ((special(13), special(14), special(6)), (0.0, 0.0, 0.0), (special(5), 1.0, 0.0), special(21)),
        [sphere((special(13), 0.0, 0.0), special(30), albedo=(special(30),) * 3, kd=special(30),
                ks=special(30), n=special(30))],
        [distant((special(6), 0.0, special(7)), color=(special(30),) * 3, intensity=special(16)),
         point((special(0), 0.0, 0.0))],
        67, 65535, rows=(65534, 32767)),
}


def change(kind, index, amount):
    """A `damage` input's `ChangeIn`: its kind, index and three signed amounts (bytes)."""
    return bytes([kind, index]) + struct.pack("<3b", *amount)


# The `damage` target's seeds: a change, then a scene of `SEEDS`.
DAMAGE_SEEDS = {
    "moved-sphere-exponent-series": (change(0, 2, (8, -6, 4)), "exponent-series"),
    "turned-light-point-and-distant": (change(1, 0, (12, 0, 0)), "point-and-distant-blinn"),
    "moved-point-light": (change(1, 1, (-20, 10, 6)), "point-and-distant-blinn"),
    "recoloured-sphere-every-model": (change(2, 1, (100, -40, 7)), "every-model"),
    "moved-camera-tangent-row": (change(3, 0, (5, 5, -5)), "tangent-row"),
    "moved-and-recoloured-metals": (change(4, 0, (-16, 3, 9)), "metals"),
}


def main():
    root = os.path.dirname(os.path.abspath(__file__))
    for target in ("scene", "paths_agree"):
        directory = os.path.join(root, "corpus", target)
        os.makedirs(directory, exist_ok=True)
        for name, data in SEEDS.items():
            with open(os.path.join(directory, "seed-" + name), "wb") as f:
                f.write(data)
    directory = os.path.join(root, "corpus", "damage")
    os.makedirs(directory, exist_ok=True)
    for name, (head, scene_name) in DAMAGE_SEEDS.items():
        with open(os.path.join(directory, "seed-" + name), "wb") as f:
            f.write(head + SEEDS[scene_name])


if __name__ == "__main__":
    main()
