"""Seeded drawing helpers shared by the random scene generators (scripts/fuzz-scenes.py, scripts/fuzz_meshes.py)."""


def num(v, digits=4):
    """A float rounded to a few significant digits; the scene and the oracle both use this value."""
    return float(f"{v:.{digits}g}")


def pick(rng, weighted):
    """One value of weighted, [(weight, value)], drawn with the random.Random rng."""
    total = sum(w for w, _ in weighted)
    r = rng.uniform(0, total)
    for w, v in weighted:
        r -= w
        if r <= 0:
            return v
    return weighted[-1][1]
