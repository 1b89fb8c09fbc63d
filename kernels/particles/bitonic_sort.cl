// Bitonic sort (Batcher 1968, "Sorting networks and their applications", AFIPS SJCC 32) of
// (uint key, uint value) pairs, packed into one ulong as (key << 32) | value so that comparing two
// packed words compares the pairs lexicographically: by key, then by value. The sorted sequence of
// pairs is therefore unique (ties between equal keys are broken by the value, e.g. the particle
// index) and equals std::sort of the pairs on the host.
//
// The network works on N = 2^p elements; the host pads the input with the largest ulong (key and
// value 0xFFFFFFFF), which sorts after every real pair, so the first n outputs are the sorted input.
//
// Structure of the network. For every block size k = 2, 4, ..., N and then every stride
// j = k/2, k/4, ..., 1, each element i with (i & j) == 0 is compared with element i + j and the
// two are put in order: ascending when (i & k) == 0, descending otherwise. After all strides of one
// k every aligned block of k elements is sorted, alternately up and down, so each pair of
// neighbouring blocks forms a bitonic sequence that the strides of the next k merge. At k = N all
// of the array lies in the ascending half, so the result is ascending.
//
// Strides j and j/2 of one block size connect the four elements lo, lo + j/2, lo + j, lo + 3j/2 (lo
// with bits j and j/2 clear) only among themselves, so one work-item can do two strides at once on
// four elements in registers: the kernels take the strides two at a time, which halves the passes
// over memory and the barriers.
//
// A work-group of L work-items owns an aligned tile of 4L elements in local memory; every stride
// j < 4L stays inside the tile. bitonic_sort_local does all strides of all block sizes k <= 4L,
// bitonic_merge_local the strides j <= 2L of one larger block size. Only the strides j >= 4L of the
// larger blocks need passes over global memory (bitonic_merge_global_2 for two strides, and
// bitonic_merge_global for a single one left over). L must be a power of two and 4L <= N (the host
// ensures both; N = 2 is one bitonic_merge_global pass).
#ifndef TALUS_BITONIC_SORT_CL
#define TALUS_BITONIC_SORT_CL

/// Index of the lower element of compare-exchange number t at stride j (a power of two): t with a
/// zero bit inserted at position log2(j), i.e. the t-th index whose bit j is clear.
inline uint bitonic_lower(uint t, uint j) { return (t << 1) - (t & (j - 1u)); }

/// Puts a[lo] and a[lo + j] in ascending (or descending) order, in local memory.
inline void bitonic_order_local(__local ulong* a, uint lo, uint j, bool ascending) {
  const ulong u = a[lo], v = a[lo + j];
  if ((u > v) == ascending && u != v) {
    a[lo] = v;
    a[lo + j] = u;
  }
}

/// Puts a and b in ascending (or descending) order, in registers.
inline void bitonic_order_private(ulong* a, ulong* b, bool ascending) {
  const ulong u = *a, v = *b;
  if ((u > v) == ascending && u != v) {
    *a = v;
    *b = u;
  }
}

/// Packs (keys[i], i) for i < n, and the padding sentinel for n <= i < N, into `packed`.
__kernel void sort_pack_with_index(__global const uint* keys, const uint n, const uint padded,
                                   __global ulong* packed) {
  const uint i = get_global_id(0);
  if (i >= padded) return;
  packed[i] = i < n ? (((ulong)keys[i]) << 32) | (ulong)i : ~(ulong)0;
}

/// Packs (keys[i], values[i]) for i < n, and the padding sentinel for n <= i < N, into `packed`.
__kernel void sort_pack_pairs(__global const uint* keys, __global const uint* values, const uint n,
                              const uint padded, __global ulong* packed) {
  const uint i = get_global_id(0);
  if (i >= padded) return;
  packed[i] = i < n ? (((ulong)keys[i]) << 32) | (ulong)values[i] : ~(ulong)0;
}

/// Splits the first n packed pairs into keys and values.
__kernel void sort_unpack(__global const ulong* packed, const uint n, __global uint* keys,
                          __global uint* values) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const ulong p = packed[i];
  keys[i] = (uint)(p >> 32);
  values[i] = (uint)p;
}

/// The strides j, j/2, ..., 1 of block size k on a tile of 4L elements in local memory (L = local
/// size), two strides per step and a barrier after each step; `base` is the tile's first index.
inline void bitonic_tile_strides(__local ulong* tile, uint base, uint k, uint j) {
  const uint lid = get_local_id(0), L = get_local_size(0);
  for (; j >= 2u; j >>= 2) {
    const uint h = j >> 1;
    const uint lo = bitonic_lower(bitonic_lower(lid, h), j);
    const bool ascending = ((base + lo) & k) == 0u;
    ulong a = tile[lo], b = tile[lo + h], c = tile[lo + j], d = tile[lo + j + h];
    bitonic_order_private(&a, &c, ascending);
    bitonic_order_private(&b, &d, ascending);
    bitonic_order_private(&a, &b, ascending);
    bitonic_order_private(&c, &d, ascending);
    tile[lo] = a;
    tile[lo + h] = b;
    tile[lo + j] = c;
    tile[lo + j + h] = d;
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (j == 1u) {  // one stride left: two neighbouring pairs per work-item
    for (uint p = lid; p < 2u * L; p += L) {
      const uint lo = 2u * p;
      bitonic_order_local(tile, lo, 1u, ((base + lo) & k) == 0u);
    }
    barrier(CLK_LOCAL_MEM_FENCE);
  }
}

inline void bitonic_load_tile(__global const ulong* data, __local ulong* tile, uint base) {
  const uint lid = get_local_id(0), L = get_local_size(0);
  for (uint m = 0u; m < 4u; ++m) tile[lid + m * L] = data[base + lid + m * L];
  barrier(CLK_LOCAL_MEM_FENCE);
}

inline void bitonic_store_tile(__global ulong* data, __local const ulong* tile, uint base) {
  const uint lid = get_local_id(0), L = get_local_size(0);
  for (uint m = 0u; m < 4u; ++m) data[base + lid + m * L] = tile[lid + m * L];
}

/// All strides of all block sizes k = 2 .. 4L inside each tile of 4L elements (L = local size).
/// Afterwards every tile is sorted, ascending or descending by the parity of its position.
__kernel void bitonic_sort_local(__global ulong* data, __local ulong* tile) {
  const uint L = get_local_size(0), base = get_group_id(0) * 4u * L;
  bitonic_load_tile(data, tile, base);
  for (uint k = 2u; k <= 4u * L; k <<= 1) bitonic_tile_strides(tile, base, k, k >> 1);
  bitonic_store_tile(data, tile, base);
}

/// The strides j = 2L, L, ..., 1 of block size k (k >= 8L) inside each tile of 4L elements.
__kernel void bitonic_merge_local(__global ulong* data, const uint k, __local ulong* tile) {
  const uint L = get_local_size(0), base = get_group_id(0) * 4u * L;
  bitonic_load_tile(data, tile, base);
  bitonic_tile_strides(tile, base, k, 2u * L);
  bitonic_store_tile(data, tile, base);
}

/// One stride j of block size k over the whole array, one compare-exchange per work-item
/// (global size N/2).
__kernel void bitonic_merge_global(__global ulong* data, const uint k, const uint j, const uint pairs) {
  const uint t = get_global_id(0);
  if (t >= pairs) return;
  const uint lo = bitonic_lower(t, j);
  const ulong u = data[lo], v = data[lo + j];
  if ((u > v) == ((lo & k) == 0u) && u != v) {
    data[lo] = v;
    data[lo + j] = u;
  }
}

/// Strides j and j/2 of block size k over the whole array in one pass (global size N/4). The two
/// strides connect the elements lo, lo + j/2, lo + j, lo + 3j/2 (lo with bits j and j/2 clear) only
/// among themselves, so one work-item orders these four: first at stride j, then at stride j/2.
__kernel void bitonic_merge_global_2(__global ulong* data, const uint k, const uint j, const uint quads) {
  const uint t = get_global_id(0);
  if (t >= quads) return;
  const uint h = j >> 1;
  const uint lo = bitonic_lower(bitonic_lower(t, h), j);
  const bool ascending = (lo & k) == 0u;
  ulong a = data[lo], b = data[lo + h], c = data[lo + j], d = data[lo + j + h];
  bitonic_order_private(&a, &c, ascending);
  bitonic_order_private(&b, &d, ascending);
  bitonic_order_private(&a, &b, ascending);
  bitonic_order_private(&c, &d, ascending);
  data[lo] = a;
  data[lo + h] = b;
  data[lo + j] = c;
  data[lo + j + h] = d;
}

#endif
