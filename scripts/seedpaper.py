"""The seed paper's Tables 1 and 2 (the brick with Coulomb friction) and the benchmark's goals, for the
brick scripts (bench-brick.py, goals-brick.py)."""

PAPER = {  # n: (m, {F: (Iter, n_A, time in s)})
    900: (180, {0.1: (5, 102, 1), 0.3: (7, 140, 2)}),
    2646: (378, {0.1: (5, 180, 11), 0.3: (7, 186, 12)}),
    5832: (648, {0.1: (5, 156, 34), 0.3: (7, 169, 38)}),
    10890: (990, {0.1: (5, 112, 67), 0.3: (7, 153, 94)}),
    18252: (1404, {0.1: (5, 155, 221), 0.3: (7, 176, 254)}),
}

ITER_GOAL = {0.1: 5, 0.3: 7}  # issue 5: Iter <= 5 (F = 0.1) and <= 7 (F = 0.3)
GROWTH_GOAL = 1.3  # n_A(largest) / n_A(900)
TIME_GOAL = 1.0  # seconds for n = 18252 on one core


def brick_n(k):
    """The brick's n for k cells per cube edge: the undecomposed mesh's unknowns without the clamped face."""
    return 9 * k * (k + 1) ** 2
