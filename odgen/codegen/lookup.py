"""`--lookup hash`: a perfect hash from index to entry position, found at generation time.

Hash and displace, as runtime/odg.c's hash_slot computes it: `h = index * mul` (32 bits); its top
`bucket_bits` bits choose a bucket whose displacement is xored into the `bits` bits below them,
giving the slot. The slot holds an entry position, and odg_find compares that entry's index with
the one asked for, so absent indices fall out. The search is seeded and bounded, so the same
dictionary always gets the same tables.
"""

from __future__ import annotations

from dataclasses import dataclass

TRIES = 300
BUCKET_SHIFT = 2  # buckets = slots / 4  # multipliers tried per table size
SEED = 0x9E3779B1  # the golden ratio in 32 bits: the first multiplier tried


@dataclass
class PerfectHash:
    mul: int
    bits: int  # slots = 1 << bits
    bucket_bits: int
    slots: list[int]
    disp: list[int]

    @property
    def ctype(self) -> str:
        """Both tables' element type, as odg_dict_t says: uint8_t up to 8 bits."""
        return "uint8_t" if self.bits <= 8 else "uint16_t"

    @property
    def table_bytes(self) -> int:
        return (1 if self.bits <= 8 else 2) * (len(self.slots) + len(self.disp))


def _multipliers() -> list[int]:
    out, x = [], SEED
    for _ in range(TRIES):
        out.append(x | 1)
        x = (x * 1103515245 + 12345) & 0xFFFFFFFF
        x ^= x >> 13
    return out


MULTIPLIERS = _multipliers()


def _displaced(indices: list[int], bits: int, bucket_bits: int) -> PerfectHash | None:
    size, mask = 1 << bits, (1 << bits) - 1
    for mul in MULTIPLIERS[:64]:
        buckets: dict[int, list[tuple[int, int]]] = {}
        for pos, k in enumerate(indices):
            h = k * mul & 0xFFFFFFFF
            buckets.setdefault(h >> (32 - bucket_bits), []).append((pos, (h >> (32 - bucket_bits - bits)) & mask))
        if any(len({b for _, b in items}) != len(items) for items in buckets.values()):
            continue  # two keys alike in every bit the hash uses: no displacement separates them
        slots, used = [0] * size, [False] * size
        disp = [0] * (1 << bucket_bits)
        ok = True
        for bucket, items in sorted(buckets.items(), key=lambda kv: (-len(kv[1]), kv[0])):
            d = next((d for d in range(size) if not any(used[b ^ d] for _, b in items)), None)
            if d is None:
                ok = False
                break
            disp[bucket] = d
            for pos, b in items:
                used[b ^ d] = True
                slots[b ^ d] = pos
        if ok:
            return PerfectHash(mul, bits, bucket_bits, slots, disp)
    return None


def perfect_hash(indices: list[int]) -> PerfectHash:
    """Tables for the sorted `indices`: slots a power of two, loaded to at most 80%, and a quarter
    as many buckets."""
    n = max(len(indices), 1)
    bits = max((n + n // 4 - 1).bit_length(), 1)  # a load of at most 80%: the search stays quick
    while True:
        found = _displaced(indices, bits, max(bits - BUCKET_SHIFT, 1))
        if found:
            return found
        bits += 1
