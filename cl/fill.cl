// clmesh — filling device arrays with a value, in parallel (support for
// the resident data of thesis §3.6.1: the free slots and marks start
// filled). A queue's fill command runs on one thread on PoCL's CPU device,
// and the first write to fresh memory costs its page faults there; a kernel
// spreads both over every core. The value is a pattern of 1, 2 or 4 words
// (4-, 8- and 16-byte elements), aligned on the array's start.

__kernel void fill_words(__global uint *words, const uint4 pattern, const uint period,
                         const ulong first, const ulong count) {
  const ulong i = get_global_id(0);
  if (i >= count)
    return;
  const ulong w = first + i;
  const uint phase = (uint)(w & (period - 1));
  words[w] = phase == 0 ? pattern.x : phase == 1 ? pattern.y : phase == 2 ? pattern.z : pattern.w;
}
