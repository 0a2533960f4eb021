/* clmesh — deterministic pseudo-random priorities, shared by the device and the host.
 *
 * A bijection of 32-bit integers that scatters consecutive values: conflict-free rounds keyed
 * by it do not degrade on sorted input (points given in order, segments listed along chains),
 * and the result stays independent of scheduling. Plain C, valid in OpenCL C and C++. */
#ifndef CLMESH_PRIORITY_H
#define CLMESH_PRIORITY_H

static inline unsigned int clm_priority_of(unsigned int x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

/* The same for the integers below 2^bits (1 <= bits <= 32): a bijection of
 * them (odd multipliers and right xor-shifts, each invertible on `bits`
 * bits). */
static inline unsigned int clm_priority_within(unsigned int x, int bits) {
  if (bits >= 32)
    return clm_priority_of(x);
  const unsigned int mask = (1u << bits) - 1u;
  const int shift = (bits + 1) / 2;
  x = (x * 0x7feb352du) & mask;
  x ^= x >> shift;
  x = (x * 0x846ca68bu) & mask;
  x ^= x >> shift;
  return x;
}

#endif
