/* rng.h — the runtime's deterministic random numbers (an internal header,
 * not part of sinew.h): xoshiro256** (Blackman & Vigna, "Scrambled linear
 * pseudorandom number generators", ACM TOMS 47(4), 2021) seeded from one
 * 64-bit seed through splitmix64, as its authors recommend.
 *
 * Everything here is integer arithmetic except sw_rng_normal, which takes
 * log and sqrt from libm (see rng.c); a stream is therefore the same on
 * every machine and build for the integers and the uniforms, and the same
 * on one machine (one libm) for the normals.  No state is global: each user
 * owns its swRng, so a study, its CMA-ES and its Latin hypercube never draw
 * from one another's streams. */
#ifndef SINEW_RNG_H
#define SINEW_RNG_H
#include <stdint.h>

typedef struct {
  uint64_t s[4];      /* xoshiro256** state, never all zero               */
  double spare;       /* the second normal of the last polar pair         */
  int has_spare;      /* 1: `spare` is the next sw_rng_normal             */
} swRng;

/* Seeds r from `seed` (any value, 0 included): the four state words are
 * four successive outputs of splitmix64 started at `seed`. */
void sw_rng_seed(swRng *r, uint64_t seed);
/* The next 64 random bits. */
uint64_t sw_rng_next(swRng *r);
/* Uniform on [0, 1): the top 53 bits of sw_rng_next times 2^-53, so every
 * value is a multiple of 2^-53 and 1 is never returned. */
double sw_rng_uniform(swRng *r);
/* Standard normal by Marsaglia's polar method (see rng.c). */
double sw_rng_normal(swRng *r);
/* Advances r by 2^128 draws of sw_rng_next (the xoshiro256** jump): 2^128
 * non-overlapping subsequences, one per stream.  Drops a spare normal. */
void sw_rng_jump(swRng *r);
/* Stream k of seed: seeded from `seed`, then jumped k times.  Streams of
 * one seed never overlap (each is 2^128 long); use one per purpose, e.g.
 * stream 0 for CMA-ES and stream 1 for a Latin hypercube. */
void sw_rng_stream(swRng *r, uint64_t seed, unsigned k);
#endif
