"""The distributions of a dispersion (:class:`Uniform`, :class:`Normal`, :class:`LogUniform`)
and the members' random streams: member i draws from
``default_rng(SeedSequence(seed, spawn_key=(i,)))``, a chunk's streams computed together."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


# ------------------------------------------------------------------------------------ distributions
def _number(value, what: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)) \
            or not math.isfinite(value):
        raise ValueError(f"{what} = {value!r} must be a finite number")
    return float(value)


def _documented_draw(cls):
    """Gives ``cls.draw`` its docstring, the same for every distribution (with its own example)."""
    example = {"Uniform": "Uniform(0.5, 1.5)", "Normal": "Normal(1.0, 0.1)", "LogUniform": "LogUniform(1e-3, 1e-1)"}
    cls.draw.__doc__ = f"""One value drawn from the distribution.

        Parameters
        ----------
        rng : numpy.random.Generator
            The generator (a sweep gives member i ``SeedSequence(seed, spawn_key=(i,))``).

        Examples
        --------
        >>> import numpy as np
        >>> import gyrostat
        >>> value = gyrostat.{example[cls.__name__]}.draw(np.random.default_rng(7))
        >>> value == gyrostat.{example[cls.__name__]}.draw(np.random.default_rng(7))
        True
        """
    return cls


@_documented_draw
@dataclass(frozen=True)
class Uniform:
    """Uniform on [low, high): a distribution of a dispersed scene entry.

    Parameters
    ----------
    low, high : float
        The bounds, in the unit of the entry it disperses.

    Examples
    --------
    >>> import numpy as np
    >>> import gyrostat
    >>> round(gyrostat.Uniform(0.5, 1.5).draw(np.random.default_rng(1)), 6)
    1.011822
    """

    low: float
    high: float

    def __post_init__(self):
        if not _number(self.low, "Uniform low") < _number(self.high, "Uniform high"):
            raise ValueError(f"Uniform({self.low!r}, {self.high!r}): low must be below high")
        object.__setattr__(self, "_affine", (float(self.low), float(self.high) - float(self.low)))

    def draw(self, rng: np.random.Generator) -> float:
        # rng.uniform(low, high) bit for bit (NumPy computes low + (high - low)·u in doubles), ~3x faster
        low, width = self._affine
        return low + width * rng.random()


@_documented_draw
@dataclass(frozen=True)
class Normal:
    """Normal with the given mean and standard deviation.

    Parameters
    ----------
    mean, std : float
        In the unit of the entry it disperses; std > 0.

    Examples
    --------
    >>> import numpy as np
    >>> import gyrostat
    >>> round(gyrostat.Normal(1.0, 0.1).draw(np.random.default_rng(1)), 6)
    1.034558
    """

    mean: float
    std: float

    def __post_init__(self):
        _number(self.mean, "Normal mean")
        if not _number(self.std, "Normal std") > 0:
            raise ValueError(f"Normal({self.mean!r}, {self.std!r}): std must be positive")

    def draw(self, rng: np.random.Generator) -> float:
        # rng.normal(mean, std) bit for bit (NumPy computes mean + std·z in doubles)
        return float(self.mean) + float(self.std) * rng.standard_normal()


@_documented_draw
@dataclass(frozen=True)
class LogUniform:
    """log(value) uniform on [log low, log high): every decade equally likely.

    Parameters
    ----------
    low, high : float
        The bounds, 0 < low < high, in the unit of the entry it disperses.

    Examples
    --------
    >>> import numpy as np
    >>> import gyrostat
    >>> round(gyrostat.LogUniform(1e-3, 1e-1).draw(np.random.default_rng(1)), 6)
    0.010559
    """

    low: float
    high: float

    def __post_init__(self):
        low, high = _number(self.low, "LogUniform low"), _number(self.high, "LogUniform high")
        if not 0 < low < high:
            raise ValueError(f"LogUniform({self.low!r}, {self.high!r}): needs 0 < low < high")
        object.__setattr__(self, "_affine", (math.log(low), math.log(high) - math.log(low)))

    def draw(self, rng: np.random.Generator) -> float:
        # exp(rng.uniform(log low, log high)) bit for bit, the logarithms taken once
        low, width = self._affine
        return math.exp(low + width * rng.random())


DISTRIBUTIONS = {"uniform": Uniform, "normal": Normal, "loguniform": LogUniform}
Distribution = Uniform | Normal | LogUniform


# ------------------------------------------------------------------------------------ members' streams
# Member i of a dispersion draws from default_rng(SeedSequence(seed, spawn_key=(i,))). Made one by
# one, that generator costs ~25 us (NumPy's SeedSequence hashing and PCG64 seeding in Python); a
# chunk's streams are computed here together, NumPy's algorithms word for word on arrays (the
# SeedSequence of NumPy's bit_generator.pyx, PCG64's pcg_setseq_128_srandom_r), and set into one
# PCG64 member by member: the same numbers (tests/test_sweeps.py compares them with default_rng).
_INIT_A, _MULT_A, _INIT_B, _MULT_B = 0x43B0D7E5, 0x931E8875, 0x8B51F9DD, 0x58F38DED
_MIX_L, _MIX_R = 0xCA01F9DD, 0x4973F715
_PCG_MULT = 0x2360ED051FC65DA44385DF649FCCF645
_MASK32, _MASK128 = 0xFFFFFFFF, (1 << 128) - 1


def _words(n: int) -> list[int]:
    """A non-negative integer as 32-bit words, least significant first (0: one word)."""
    out = [n & _MASK32]
    while n > _MASK32:
        n >>= 32
        out.append(n & _MASK32)
    return out


def _pcg64_states(seed: int, members: np.ndarray) -> list[tuple[int, int]]:
    """(state, inc) of PCG64(SeedSequence(seed, spawn_key=(i,))) for each member i < 2**32."""
    u32 = np.uint32
    run = _words(seed)
    run += [0] * (4 - len(run))  # a spawned sequence pads its entropy to the pool size
    count = len(members)
    entropy = [np.full(count, w, u32) for w in run] + [members.astype(u32)]
    hash_a = [_INIT_A]

    def hashmix(value):
        value = value ^ u32(hash_a[0])
        hash_a[0] = (hash_a[0] * _MULT_A) & _MASK32
        value = value * u32(hash_a[0])
        return value ^ (value >> u32(16))

    def mix(x, y):
        result = u32(_MIX_L) * x - u32(_MIX_R) * y
        return result ^ (result >> u32(16))

    with np.errstate(over="ignore"):  # arithmetic modulo 2**32, as in NumPy's C
        pool = [hashmix(entropy[i]) for i in range(4)]
        for source in range(4):
            for target in range(4):
                if source != target:
                    pool[target] = mix(pool[target], hashmix(pool[source]))
        for source in range(4, len(entropy)):
            for target in range(4):
                pool[target] = mix(pool[target], hashmix(entropy[source]))
        hash_b, state = _INIT_B, []
        for k in range(8):  # generate_state(4, uint64): 8 words, pairs (low, high)
            value = pool[k % 4] ^ u32(hash_b)
            hash_b = (hash_b * _MULT_B) & _MASK32
            value = value * u32(hash_b)
            state.append((value ^ (value >> u32(16))).tolist())
    out = []
    for m in range(count):
        seed_high, seed_low, inc_high, inc_low = (state[2 * j][m] | (state[2 * j + 1][m] << 32) for j in range(4))
        inc = ((((inc_high << 64) | inc_low) << 1) | 1) & _MASK128
        current = (((inc + ((seed_high << 64) | seed_low)) & _MASK128) * _PCG_MULT + inc) & _MASK128
        out.append((current, inc))
    return out


def _member_generators(seed: int, start: int, stop: int):
    """Each member's generator in turn, for members start … stop − 1 (one Generator, reseeded)."""
    if stop > 2**32 or stop - start < 8:  # beyond 2**32 a spawn key has two words; a few members: NumPy's own way
        for i in range(start, stop):
            yield np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(i,)))
        return
    bits = np.random.PCG64(0)
    generator = np.random.Generator(bits)
    for current, inc in _pcg64_states(seed, np.arange(start, stop, dtype=np.uint64)):
        bits.state = {"bit_generator": "PCG64", "state": {"state": current, "inc": inc}, "has_uint32": 0,
                      "uinteger": 0}
        yield generator
