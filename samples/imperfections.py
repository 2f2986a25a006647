"""CAD imperfections for generated scenes: what real exports do to clean geometry.

Standard library only. Used by ``generate_samples.py`` (every scene takes these options) so that
tests and users can make the imperfect twin of any clean scene and compare the two:

  --noise E        every vertex of every block moved by independent uniform noise in [-E, E]
                   along each axis (m). Blocks do not share vertices in the model JSON, so the
                   two copies of a corner that two blocks share move independently: joints open
                   and close by up to about 2E, and faces with four or more corners warp.
  --warp W         a smooth displacement field of amplitude W (m) applied to every point, the
                   same for every block, so faces that two blocks share stay shared but warp
                   (out of plane by up to about W), as offset or projected CAD surfaces do.
                   Only faces with the same corners stay shared: a long face that several
                   blocks rest on (the base slab's top) keeps its few corners, so the blocks'
                   faces move off it by up to W. At W = 5 mm the default 1920-block facade
                   still passes, but a 12 x 10 facade, the church, the dome and a 2 x 1 town
                   house overlap their base by 1.0-1.3 % of a block, which rbla refuses as more
                   than an imperfection: keep W to a few mm on small scenes.
  --joint-gap G    every free block moved rigidly by a random vector of length up to G (m):
                   joints with gaps and overlaps of up to about 2G between blocks.
  --split-faces P  each face with four or more corners is replaced, with probability P, by a
                   fan of triangles from a random corner (the two blocks on either side of a
                   joint then split it along different diagonals), as mesh exports do.
  --rotate DEG     the whole model (and the analysis directions) rotated about the vertical.
  --units U        the model written in m, cm or mm.
  --seed S         the random seed (the same seed gives the same file).

Order: warp, joint gaps, noise (all in metres), then split, rotate, change of units. Centroids
and volumes are recomputed from the imperfect faces, as a CAD would report them.
"""

import math
import random

LENGTH_FACTORS = {"m": 1.0, "cm": 100.0, "mm": 1000.0}


def add_arguments(parser):
    g = parser.add_argument_group("CAD imperfections (all off by default)")
    g.add_argument("--noise", type=float, default=0.0,
                   help="independent uniform noise on every vertex, +-E along each axis, m")
    g.add_argument("--warp", type=float, default=0.0,
                   help="amplitude of a smooth displacement field that warps shared faces, m")
    g.add_argument("--joint-gap", type=float, default=0.0,
                   help="each free block moved rigidly by up to G, m (joint gaps and overlaps)")
    g.add_argument("--split-faces", type=float, default=0.0, metavar="P",
                   help="probability that a face of 4+ corners is split into a fan of triangles")
    g.add_argument("--rotate", type=float, default=0.0, metavar="DEG",
                   help="rotate the model about the vertical axis, degrees")
    g.add_argument("--units", choices=sorted(LENGTH_FACTORS), default="m",
                   help="length unit of the written model")
    g.add_argument("--seed", type=int, default=1, help="random seed of the imperfections")


def requested(args):
    return bool(args.noise or args.warp or args.joint_gap or args.split_faces or args.rotate
                or args.units != "m")


def describe(args):
    parts = []
    if args.warp:
        parts.append("faces warped by a %g m field" % args.warp)
    if args.joint_gap:
        parts.append("blocks moved by up to %g m" % args.joint_gap)
    if args.noise:
        parts.append("vertex noise +-%g m" % args.noise)
    if args.split_faces:
        parts.append("%g of the faces split into triangles" % args.split_faces)
    if args.rotate:
        parts.append("rotated %g deg about z" % args.rotate)
    if args.units != "m":
        parts.append("written in %s" % args.units)
    return "; ".join(parts) + " (seed %d)" % args.seed


def _block_sizes(blocks):
    sizes = []
    for b in blocks:
        lo = [min(v[k] for v in b["vertices"]) for k in range(3)]
        hi = [max(v[k] for v in b["vertices"]) for k in range(3)]
        sizes.append(math.sqrt(sum((hi[k] - lo[k]) ** 2 for k in range(3))))
    return sizes


def _warp_field(rng, amplitude, wavelength):
    """d(p) = W (sin(k_i . p + phase_i))_i: smooth, bounded by W, a function of the point only."""
    waves = []
    for _ in range(3):
        u = [rng.gauss(0.0, 1.0) for _ in range(3)]
        n = math.sqrt(sum(c * c for c in u)) or 1.0
        waves.append(([2.0 * math.pi * c / (n * wavelength) for c in u], rng.uniform(0.0, 2.0 * math.pi)))

    def field(p):
        return [amplitude * math.sin(sum(k[j] * p[j] for j in range(3)) + phase) for k, phase in waves]
    return field


def _fan(face, start):
    f = face[start:] + face[:start]
    return [[f[0], f[k], f[k + 1]] for k in range(1, len(f) - 1)]


def _rotate_z(v, c, s):
    return [c * v[0] - s * v[1], s * v[0] + c * v[1], v[2]]


def apply(model, args, make_block):
    """Applies the imperfections of ``args`` to ``model`` in place. ``make_block(id, vertices,
    faces, role, label)`` rebuilds a block with its centroid and volume."""
    if not requested(args):
        return model
    rng = random.Random(args.seed)
    blocks = model["blocks"]
    sizes = sorted(_block_sizes(blocks))
    median = sizes[len(sizes) // 2] if sizes else 1.0
    # A wavelength incommensurate with the block grid, of the order of a block, so neighbouring
    # faces warp differently.
    field = _warp_field(rng, args.warp, 1.7 * median) if args.warp else None
    angle = math.radians(args.rotate)
    c, s = math.cos(angle), math.sin(angle)
    scale = LENGTH_FACTORS[args.units]
    out = []
    for b in blocks:
        vertices = [list(v) for v in b["vertices"]]
        if field:
            vertices = [[v[k] + d for k, d in enumerate(field(v))] for v in vertices]
        if args.joint_gap and b["role"] == "free":
            u = [rng.gauss(0.0, 1.0) for _ in range(3)]
            n = math.sqrt(sum(x * x for x in u)) or 1.0
            r = args.joint_gap * rng.random()
            vertices = [[v[k] + r * u[k] / n for k in range(3)] for v in vertices]
        if args.noise:
            vertices = [[x + rng.uniform(-args.noise, args.noise) for x in v] for v in vertices]
        faces = []
        for f in b["faces"]:
            if len(f) >= 4 and args.split_faces and rng.random() < args.split_faces:
                faces.extend(_fan(list(f), rng.randrange(len(f))))
            else:
                faces.append(list(f))
        vertices = [[round(x * scale, 10) + 0.0 for x in _rotate_z(v, c, s)] for v in vertices]
        out.append(make_block(b["id"], vertices, faces, b["role"], b.get("label")))
    model["blocks"] = out
    analysis = model.get("analysis") or {}
    seismic = analysis.get("seismic")
    if seismic and angle:
        seismic["direction"] = [round(x, 15) + 0.0 for x in _rotate_z(seismic["direction"], c, s)]
    if args.units != "m":
        model["units"]["length"] = args.units
    model["title"] = (model.get("title", "") + "; CAD imperfections: " + describe(args)).lstrip("; ")
    return model
