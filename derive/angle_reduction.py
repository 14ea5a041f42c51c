"""Constants of the runtimes' exact angle reduction (wrap to [-pi, pi]), computed from pi at high precision.

remainder(q, 6.283185307179586) is exact for the double it is given, but that double is not 2 pi: the reduced
angle drifts by |q| x 3.9e-17 (2 pi - fl(2 pi) = 2.45e-16 per turn), 2e-8 rad at q = 1e9 and every digit at 1e16.
The runtimes reduce against 2 pi itself, as libm's sin does (Payne-Hanek):
- C: the fraction of q / (2 pi) from the bits of 1 / (2 pi), 32 per word (`inv_two_pi_words`), enough words for
  the largest double's exponent plus a 256-bit window; that fraction times 2 pi in double-double.
- Python: exact integer arithmetic against floor(2 pi 2^TWO_PI_FIX_BITS) (`two_pi_fix`).
- Both: |q| <= fl(pi) (< pi) is returned as it is, and |q| up to ONE_TURN_MAX (< 3 pi, one turn) is
  (|q| - fl(2 pi)) - (2 pi - fl(2 pi)), whose first difference is exact (Sterbenz).
The closest a double comes to a multiple of pi / 2 is 4.7e-19 (6381956970095103 x 2^797), so the reduced angle
is at least 2^-62 and a window of 128 fraction bits leaves 66 significant ones."""

import mpmath

INV_TWO_PI_WINDOW_WORDS = 8  # the C window: 256 bits of 1 / (2 pi) past the integer bits of q / (2 pi)
INV_TWO_PI_WORDS = (1024 - 53) // 32 + INV_TWO_PI_WINDOW_WORDS  # first word index of the largest double + window
TWO_PI_FIX_BITS = 1024 + 256  # Python: 2 pi to 256 bits beyond the largest double's integer part
ONE_TURN_MAX = 9.4  # < 3 pi = 9.42477...: |q| / (2 pi) < 1.5, one turn from the reduced angle


def runtime_context() -> dict:
    """The runtimes' angle-reduction constants as their sources write them (bit-exact hex / repr): runtime/c and
    runtime/python hold them literally, tests/test_runtime_sources.py holds them equal to these."""
    with mpmath.workprec(TWO_PI_FIX_BITS + 64):
        two_pi = 2 * mpmath.pi
        hi = float(two_pi)  # fl(2 pi), rounded to nearest
        lo = float(two_pi - mpmath.mpf(hi))
        inv = int(mpmath.floor(mpmath.ldexp(1 / two_pi, 32 * INV_TWO_PI_WORDS)))
        fix = int(mpmath.floor(mpmath.ldexp(two_pi, TWO_PI_FIX_BITS)))
    hx = f"{fix:x}"
    words = [(inv >> (32 * (INV_TWO_PI_WORDS - 1 - i))) & 0xFFFFFFFF for i in range(INV_TWO_PI_WORDS)]
    return {"angle_reduction": {
        "two_pi_hi": hi.hex(), "two_pi_lo": lo.hex(), "two_pi_hi_repr": repr(hi), "two_pi_lo_repr": repr(lo),
        "inv_two_pi_words": [f"0x{w:08x}u" for w in words], "window_words": INV_TWO_PI_WINDOW_WORDS,
        "two_pi_fix_hex": [hx[i:i + 96] for i in range(0, len(hx), 96)],
        "two_pi_fix_bits": TWO_PI_FIX_BITS, "one_turn_max": repr(ONE_TURN_MAX)}}
