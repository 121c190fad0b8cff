#!/usr/bin/env python3
"""An independent re-implementation of apps/study's randomness (shuffle.hpp) and
of the plan rules for a single-stage random-order study (plan.hpp), written from
their documentation and the published algorithms, for the C++ to be compared
against at test time:

  MT19937-64     Matsumoto & Nishimura's 64-bit Mersenne Twister (mt19937-64.c),
                 checked here against the C++ standard's required 10000th output
                 of a default-seeded std::mt19937_64, 9981545732273789042
  FNV-1a 64      offset basis 0xcbf29ce484222325, prime 0x100000001b3
  SplitMix64     Steele, Lea & Flood's finaliser (+ 0x9e3779b97f4a7c15 first)
  uniform_below  reject draws below 2**64 mod n, then x mod n
  Fisher-Yates   for i = n-1 … 1: swap a[i], a[uniform_below(i + 1)]

Usage:
  shuffle_reference.py shuffles STUDY_SEED CODE SIZE…
      "seed S", then "perm SIZE a b …" per SIZE, all from one engine stream
  shuffle_reference.py pointing STUDY_SEED CODE BLOCKS CONDITIONS
      "seed S", then per block "block B c1 c2 …" (listed-order condition
      indices) and "directions B ±1 …" (a random first direction per trial)
"""
import sys

MASK = (1 << 64) - 1


class MT19937_64:
    N, M = 312, 156
    MATRIX_A = 0xB5026F5AA96619E9
    UPPER, LOWER = 0xFFFFFFFF80000000, 0x7FFFFFFF

    def __init__(self, seed):
        self.mt = [0] * self.N
        self.mt[0] = seed & MASK
        for i in range(1, self.N):
            prev = self.mt[i - 1]
            self.mt[i] = (6364136223846793005 * (prev ^ (prev >> 62)) + i) & MASK
        self.index = self.N

    def _twist(self):
        mt = self.mt
        for i in range(self.N):
            x = (mt[i] & self.UPPER) | (mt[(i + 1) % self.N] & self.LOWER)
            xa = x >> 1
            if x & 1:
                xa ^= self.MATRIX_A
            mt[i] = mt[(i + self.M) % self.N] ^ xa
        self.index = 0

    def __call__(self):
        if self.index >= self.N:
            self._twist()
        x = self.mt[self.index]
        self.index += 1
        x ^= (x >> 29) & 0x5555555555555555
        x ^= (x << 17) & 0x71D67FFFEDA60000
        x ^= (x << 37) & 0xFFF7EEE000000000
        x ^= x >> 43
        return x & MASK


def fnv1a64(text):
    h = 0xCBF29CE484222325
    for byte in text.encode("utf-8"):
        h ^= byte
        h = (h * 0x100000001B3) & MASK
    return h


def splitmix64(x):
    x = (x + 0x9E3779B97F4A7C15) & MASK
    x = ((x ^ (x >> 30)) * 0xBF58476D1CE4E5B9) & MASK
    x = ((x ^ (x >> 27)) * 0x94D049BB133111EB) & MASK
    return x ^ (x >> 31)


def uniform_below(engine, n):
    threshold = (1 << 64) % n
    while True:
        x = engine()
        if x >= threshold:
            return x % n


def fisher_yates(items, engine):
    for i in range(len(items) - 1, 0, -1):
        j = uniform_below(engine, i + 1)
        items[i], items[j] = items[j], items[i]


def self_check():
    engine = MT19937_64(5489)  # std::mt19937_64's default seed
    for _ in range(9999):
        engine()
    if engine() != 9981545732273789042:
        sys.exit("MT19937-64 re-implementation disagrees with the C++ standard's check value")


def main(argv):
    self_check()
    mode, study_seed, code = argv[1], int(argv[2]), argv[3]
    seed = splitmix64(study_seed ^ fnv1a64(code))
    engine = MT19937_64(seed)
    print("seed", seed)
    if mode == "shuffles":
        for size in map(int, argv[4:]):
            items = list(range(size))
            fisher_yates(items, engine)
            print("perm", size, *items)
    elif mode == "pointing":
        blocks, conditions = int(argv[4]), int(argv[5])
        for block in range(1, blocks + 1):
            order = list(range(conditions))
            fisher_yates(order, engine)
            directions = [1 if uniform_below(engine, 2) == 0 else -1 for _ in order]
            print("block", block, *order)
            print("directions", block, *directions)
    else:
        sys.exit("unknown mode " + mode)


if __name__ == "__main__":
    main(sys.argv)
