/* rng.c — xoshiro256** with splitmix64 seeding, uniforms and normals.
 *
 * Design.  A study must be reproducible: the same seed gives the same
 * candidates on any number of MPI ranks and after a resume, so the
 * generator is ours, its state is a plain struct that the caller owns, and
 * no draw depends on anything but that state.  xoshiro256** (Blackman and
 * Vigna 2021) is small, fast, passes BigCrush and has a jump function that
 * splits one seed into 2^128 non-overlapping streams of 2^128 draws each.
 * Its state must not be all zero; seeding it with four outputs of
 * splitmix64 (Steele, Lea and Flood, "Fast splittable pseudorandom number
 * generators", OOPSLA 2014) turns any 64-bit seed, 0 included, into a
 * well-mixed nonzero state.
 *
 * Uniforms take the top 53 bits (the low bits of xoshiro256** are its
 * weakest) as a multiple of 2^-53 on [0, 1).  Normals use Marsaglia's polar
 * method (Marsaglia and Bray, SIAM Review 6(3), 1964): draw u, v uniform on
 * [-1, 1) until 0 < s = u^2 + v^2 < 1, then u sqrt(-2 ln s / s) and
 * v sqrt(-2 ln s / s) are two independent standard normals; the second is
 * kept for the next call.  It needs no sin or cos, only sqrt (exact in IEEE
 * 754) and log, so a stream of normals is bitwise the same on one machine
 * with one libm; the code is compiled with -std=c11, under which GCC does
 * not contract a*b+c into fused multiply-adds, so the optimised and the
 * sanitizer builds draw the same numbers too. */
#include <math.h>

#include "rng.h"

static uint64_t splitmix64(uint64_t *x) {
  uint64_t z = (*x += UINT64_C(0x9e3779b97f4a7c15));
  z = (z ^ (z >> 30)) * UINT64_C(0xbf58476d1ce4e5b9);
  z = (z ^ (z >> 27)) * UINT64_C(0x94d049bb133111eb);
  return z ^ (z >> 31);
}

static inline uint64_t rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

void sw_rng_seed(swRng *r, uint64_t seed) {
  uint64_t x = seed;
  for (int i = 0; i < 4; i++) r->s[i] = splitmix64(&x);
  r->has_spare = 0;
  r->spare = 0.0;
}

uint64_t sw_rng_next(swRng *r) {
  uint64_t *s = r->s;
  const uint64_t out = rotl(s[1] * 5, 7) * 9;
  const uint64_t t = s[1] << 17;
  s[2] ^= s[0];
  s[3] ^= s[1];
  s[1] ^= s[2];
  s[0] ^= s[3];
  s[2] ^= t;
  s[3] = rotl(s[3], 45);
  return out;
}

double sw_rng_uniform(swRng *r) {
  return (double)(sw_rng_next(r) >> 11) * 0x1.0p-53;
}

double sw_rng_normal(swRng *r) {
  if (r->has_spare) {
    r->has_spare = 0;
    return r->spare;
  }
  double u, v, s;
  do {
    u = 2.0 * sw_rng_uniform(r) - 1.0;
    v = 2.0 * sw_rng_uniform(r) - 1.0;
    s = u * u + v * v;
  } while (s >= 1.0 || s == 0.0);
  const double f = sqrt(-2.0 * log(s) / s);
  r->spare = v * f;
  r->has_spare = 1;
  return u * f;
}

/* The jump polynomial of xoshiro256** for 2^128 steps (Blackman and Vigna's
 * published constants): the state after the jump is the sum (xor) of the
 * states visited at the polynomial's nonzero coefficients. */
void sw_rng_jump(swRng *r) {
  static const uint64_t JUMP[4] = {UINT64_C(0x180ec6d33cfd0aba), UINT64_C(0xd5a61266f0c9392c),
                                   UINT64_C(0xa9582618e03fc9aa), UINT64_C(0x39abdc4529b1661c)};
  uint64_t t[4] = {0, 0, 0, 0};
  for (int i = 0; i < 4; i++)
    for (int b = 0; b < 64; b++) {
      if (JUMP[i] & (UINT64_C(1) << b))
        for (int k = 0; k < 4; k++) t[k] ^= r->s[k];
      sw_rng_next(r);
    }
  for (int k = 0; k < 4; k++) r->s[k] = t[k];
  r->has_spare = 0;
}

void sw_rng_stream(swRng *r, uint64_t seed, unsigned k) {
  sw_rng_seed(r, seed);
  for (unsigned i = 0; i < k; i++) sw_rng_jump(r);
}
