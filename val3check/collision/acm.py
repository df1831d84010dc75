"""The allowed-collision matrix of an arm, computed as MoveIt's setup assistant does.

A pair of links is not checked against each other when it is
  * adjacent: joined by one joint, or through links that have no collision geometry;
  * default: in collision at the default position (every joint at 0, or mid-range when 0 is
    outside its limits);
  * always: in collision in more than 95 % of 200 random positions (repeated until a round
    disables nothing new);
  * never: never in collision over `trials` random positions (10,000 by default).
Random positions are uniform within the joint limits, drawn from `random.Random(seed)` (the
Mersenne Twister of the standard library, whose sequence does not change between Python
versions), so the matrix is the same on every machine. "In collision" is fcl's `collide` on the
links' collision solids, without tolerance.

A URDF may name pairs itself, inside `<val3check>`, as a MoveIt SRDF does:
`<disable_collisions link1=".." link2=".." reason="user"/>`. Those are added to the computed ones
(the catalogue's URDFs name two: robots/README.md). With `<acm trials=".." seed=".."/>` as well, the
URDF's list is the whole matrix and nothing is computed (a matrix copied from a MoveIt SRDF).

The catalogue's URDFs store the matrix computed here (robots/generate.py writes it): their `<acm>`
also has `inputs`, a digest of everything the computation reads (`acm_inputs`: the link tree, the
solids, the joint limits, the user's pairs, trials, seed and this module's constants). It is used
only while that digest is the arm's: an arm whose solids, limits or pairs differ from the stored
ones gets its matrix computed (about 0.1 s, once per URDF in a process).
"""

from __future__ import annotations

import hashlib
import random

import fcl
import numpy as np

from ..light_dataclass import dataclass, field
from .bodies import Body

REASONS = ("adjacent", "default", "always", "never")
TRIALS = 10_000
SEED = 0
ALWAYS_ROUND = 200
ALWAYS_FRACTION = 0.95


@dataclass(frozen=True)
class ACM:
    """Link pairs that are not checked, with the reason; pairs are (a, b) with a < b."""

    disabled: dict[tuple[str, str], str] = field(default_factory=dict)
    trials: int = TRIALS
    seed: int = SEED
    source: str = "computed"  # "urdf": read from the URDF; "computed": at load; "stored": computed by
    # robots/generate.py and stored in the URDF, for the same inputs (`acm_inputs`)

    def allowed(self, a: str, b: str) -> bool:
        return a == b or ((a, b) if a < b else (b, a)) in self.disabled

    def xml(self, indent: str = "    ") -> list[str]:
        """The `<val3check>` children that store it in a URDF."""
        out = [f'{indent}<acm trials="{self.trials}" seed="{self.seed}"/>']
        for (a, b), why in sorted(self.disabled.items()):
            out.append(f'{indent}<disable_collisions link1="{a}" link2="{b}" reason="{why}"/>')
        return out


def compute_acm(links, bodies: dict[str, list[Body]], limits, trials: int = TRIALS, seed: int = SEED,
                user: dict[tuple[str, str], str] | None = None) -> ACM:
    """The matrix for an `ArmLinks` whose links carry `bodies` ({link: [Body]}), joint `limits`
    ((lo, hi) per joint value, degrees or mm); `user`: pairs disabled beforehand, with their reason."""
    names = sorted(n for n, b in bodies.items() if b)
    disabled: dict[tuple[str, str], str] = dict(user or {})
    for p in sorted(links.adjacent_pairs(set(names))):
        disabled.setdefault(p, "adjacent")
    pairs = [(a, b) for i, a in enumerate(names) for b in names[i + 1:]]

    def enabled() -> list[tuple[str, str]]:
        return [p for p in pairs if p not in disabled]

    default = [0.0 if lo <= 0.0 <= hi else 0.5 * (lo + hi) for lo, hi in limits]
    for p, n in _collisions(links, bodies, np.array([default]), enabled()).items():
        if n:
            disabled[p] = "default"
    rng = random.Random(seed)

    lo = np.array([float(a) for a, _ in limits])
    span = np.array([float(b) for _, b in limits]) - lo

    def sample(n: int) -> np.ndarray:
        # rng.uniform(lo, hi) per value, row by row, all at once: lo + (hi - lo) * random(), the same
        # operations in the same order (numpy rounds each one as Python does)
        r = np.array([rng.random() for _ in range(n * len(lo))]).reshape(n, len(lo))
        return lo + span * r

    seen: set[tuple[str, str]] = set()
    while True:
        counts = _collisions(links, bodies, sample(ALWAYS_ROUND), enabled())
        seen.update(p for p, n in counts.items() if n)
        found = [p for p, n in counts.items() if n > int(ALWAYS_ROUND * ALWAYS_FRACTION)]
        for p in found:
            disabled[p] = "always"
        if not found:
            break
    todo = [p for p in enabled() if p not in seen]
    chunk = 2000
    done = 0
    while done < trials and todo:
        n = min(chunk, trials - done)
        counts = _collisions(links, bodies, sample(n), todo)
        seen.update(p for p, c in counts.items() if c)
        todo = [p for p in todo if p not in seen]
        done += n
    for p in enabled():
        if p not in seen:
            disabled[p] = "never"
    return ACM(dict(sorted(disabled.items())), trials, seed, "computed")


def _collisions(links, bodies: dict[str, list[Body]], Q: np.ndarray, pairs) -> dict[tuple[str, str], int]:
    """For each link pair: in how many of the positions Q its solids collide. Boxes around the
    solids, computed for all positions at once, leave fcl only the positions where they overlap."""
    poses = links.poses_many(Q)
    world: dict[int, np.ndarray] = {}
    boxes: dict[int, tuple[np.ndarray, np.ndarray]] = {}
    for link in {x for p in pairs for x in p}:
        for b in bodies[link]:
            T = poses[link] @ b.local
            world[id(b)] = T
            R = T[:, :3, :3]
            c = np.einsum("nij,j->ni", R, b.center) + T[:, :3, 3]
            h = np.einsum("nij,j->ni", np.abs(R), b.half)
            boxes[id(b)] = (c, h)
    req = fcl.CollisionRequest()
    out: dict[tuple[str, str], int] = {}
    for a, b in pairs:
        hit = np.zeros(len(Q), dtype=bool)
        for ba in bodies[a]:
            for bb in bodies[b]:
                ca, ha = boxes[id(ba)]
                cb, hb = boxes[id(bb)]
                near = np.nonzero(np.all(np.abs(ca - cb) <= ha + hb, axis=1) & ~hit)[0]
                Ta, Tb = world[id(ba)], world[id(bb)]
                oa = ba.exact if ba.exact is not None else ba.obj  # the triangles of a mesh, not its hull
                ob = bb.exact if bb.exact is not None else bb.obj
                for k in near:
                    oa.setRotation(Ta[k, :3, :3])
                    oa.setTranslation(Ta[k, :3, 3])
                    ob.setRotation(Tb[k, :3, :3])
                    ob.setTranslation(Tb[k, :3, 3])
                    if fcl.collide(oa, ob, req, fcl.CollisionResult()):
                        hit[k] = True
        out[(a, b)] = int(hit.sum())
    return out


def acm_inputs(links, bodies: dict[str, list[Body]], limits, user: dict[tuple[str, str], str], trials: int,
               seed: int) -> str:
    """A digest of everything `compute_acm` reads: the link tree (each joint's parent, kind, index,
    origin and axis), each link's solids (shape, size, pose in the link, points, triangles), the
    joint limits (numbers to 1e-9: `_bits`), the user's pairs, trials, seed and the rules' constants."""
    h = hashlib.sha256()

    def put(*items) -> None:
        for x in items:
            h.update(x if isinstance(x, bytes) else repr(x).encode())
            h.update(b"|")

    put("acm 1", REASONS, ALWAYS_ROUND, ALWAYS_FRACTION, int(trials), int(seed), links.root,
        _bits(links.root_in_world))
    for n in links.links[1:]:
        e = links.edges[n]
        put(n, e.parent, e.kind, e.index, _bits(e.origin), _bits(e.axis))
    for link in sorted(bodies):
        for b in bodies[link]:
            put(link, b.geometry, _bits(b.size), _bits(b.radius), _bits(b.local), _bits(b.points))
            tri = getattr(b.triangle_shape, "triangles", None)  # a mesh's own triangles (what fcl collides)
            put(None if tri is None else _bits(tri), b.exact is None)
    put(_bits(limits), sorted(user.items()))
    return h.hexdigest()[:32]


def _bits(values) -> bytes:
    """Numbers rounded to 1e-9 (mm, degrees): a digest the same on every machine, whose sin, cos
    and inverse may differ in the last bit, and that any real change of the arm changes."""
    return (np.round(np.asarray(values, dtype=float), 9) + 0.0).tobytes()


def read_acm(urdf_path: str) -> tuple[dict[tuple[str, str], str], tuple | None]:
    """The pairs a URDF's `<val3check>` element disables ({(a, b): reason}), and (trials, seed,
    inputs) when it also has `<acm>` (then the list is the whole matrix; `inputs`: the digest it
    was computed for, or None)."""
    from defusedxml import ElementTree as ET

    try:
        root = ET.parse(urdf_path).getroot()
    except (OSError, ET.ParseError):
        return {}, None
    meta = root.find("val3check")
    if meta is None:
        return {}, None
    disabled: dict[tuple[str, str], str] = {}
    for r in meta.findall("disable_collisions"):
        a, b = r.get("link1", ""), r.get("link2", "")
        if a and b and a != b:
            disabled[(min(a, b), max(a, b))] = (r.get("reason") or "user").lower()
    head = meta.find("acm")
    if head is None:
        return dict(sorted(disabled.items())), None
    return dict(sorted(disabled.items())), (_int(head.get("trials"), 0), _int(head.get("seed"), 0), head.get("inputs"))


def arm_acm(links, bodies: dict[str, list[Body]], limits, urdf_path: str) -> ACM:
    """The matrix of an arm: the URDF's when it has a whole one (a stored one only for the inputs
    it was computed for), else computed plus the URDF's own pairs."""
    declared, head = read_acm(urdf_path)
    if head is None:
        return compute_acm(links, bodies, limits, user=declared)
    trials, seed, inputs = head
    if inputs is None:
        return ACM(declared, trials, seed, "urdf")
    user = {p: why for p, why in declared.items() if why == "user"}
    if inputs == acm_inputs(links, bodies, limits, user, trials, seed):
        return ACM(declared, trials, seed, "stored")
    return compute_acm(links, bodies, limits, trials, seed, user=user)


def stored_lines(acm: ACM, inputs: str, indent: str = "    ") -> list[str]:
    """The `<val3check>` children that store a computed matrix in a URDF (robots/generate.py): its
    `<acm>` with the digest of its inputs, and the pairs it disables besides the user's."""
    out = [f'{indent}<acm trials="{acm.trials}" seed="{acm.seed}" inputs="{inputs}" '
           'computed_by="val3check/collision/acm.py (robots/generate.py)"/>']
    for (a, b), why in sorted(acm.disabled.items()):
        if why != "user":
            out.append(f'{indent}<disable_collisions link1="{a}" link2="{b}" reason="{why}"/>')
    return out


def _int(text, default: int) -> int:
    try:
        return int(text)
    except (TypeError, ValueError):
        return default
