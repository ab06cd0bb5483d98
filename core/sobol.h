// Owen-scrambled 2D Sobol points, deterministic per (seed, stream): the first two Sobol dimensions
// (van der Corput, and the Pascal-matrix dimension), each Owen-scrambled with the hash-based
// permutation of Burley, "Practical Hash-based Owen Scrambling" (JCGT 2020). Any aligned block of
// 2^k consecutive indices is a (0,k,2)-net, so the 16-sample batches of the area-light sampler are
// each stratified, and so is every power-of-two prefix.
#pragma once

#include <cstdint>

namespace so {

inline uint32_t reverseBits32(uint32_t x) {
    x = (x << 16) | (x >> 16);
    x = ((x & 0x00ff00ffu) << 8) | ((x & 0xff00ff00u) >> 8);
    x = ((x & 0x0f0f0f0fu) << 4) | ((x & 0xf0f0f0f0u) >> 4);
    x = ((x & 0x33333333u) << 2) | ((x & 0xccccccccu) >> 2);
    x = ((x & 0x55555555u) << 1) | ((x & 0xaaaaaaaau) >> 1);
    return x;
}

// A good 32-bit integer hash (Wellons' lowbias32), for seeds.
inline uint32_t hash32(uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

inline uint32_t hashCombine(uint32_t a, uint32_t b) {
    return hash32(a ^ (hash32(b) + 0x9e3779b9u + (a << 6) + (a >> 2)));
}

// Burley's improved Laine-Karras permutation: an Owen scramble of the bit-reversed value.
inline uint32_t laineKarras(uint32_t x, uint32_t seed) {
    x ^= x * 0x3d20adeau;
    x += seed;
    x *= (seed >> 16) | 1u;
    x ^= x * 0x05526c56u;
    x ^= x * 0x53a22864u;
    return x;
}

inline uint32_t owenScramble(uint32_t x, uint32_t seed) {
    return reverseBits32(laineKarras(reverseBits32(x), seed));
}

// Sobol dimension 0 (van der Corput) and 1 (generator v_1 = 2^31, v_k = v_{k-1} ^ (v_{k-1} >> 1)).
inline uint32_t sobol0(uint32_t i) {
    return reverseBits32(i);
}
inline uint32_t sobol1(uint32_t i) {
    uint32_t r = 0;
    for (uint32_t v = 1u << 31; i; i >>= 1, v ^= v >> 1)
        if (i & 1u) r ^= v;
    return r;
}

// The scramble seeds of a sequence's two dimensions.
inline uint32_t sobolScrambleU(uint32_t seed) {
    return hash32(seed);
}
inline uint32_t sobolScrambleV(uint32_t seed) {
    return hash32(seed ^ 0x68bc21ebu);
}
// 24 bits so the float is exact and strictly below 1.
inline float sobolFloat(uint32_t x) {
    return float(x >> 8) * 0x1p-24f;
}

// Point `index` of the scrambled sequence for `seed`, in [0, 1)^2.
inline void sobol2D(uint32_t index, uint32_t seed, float& u, float& v) {
    u = sobolFloat(owenScramble(sobol0(index), sobolScrambleU(seed)));
    v = sobolFloat(owenScramble(sobol1(index), sobolScrambleV(seed)));
}

// The unscrambled values of points 0..15 of each dimension: Sobol dimensions are linear over GF(2)
// in the index bits, so in an aligned block starting at `first` (a multiple of the block's size)
// point first + k is sobolN(first) ^ table[k].
inline constexpr uint32_t kSobolBlock0[16] = {0x00000000u, 0x80000000u, 0x40000000u, 0xc0000000u,
                                              0x20000000u, 0xa0000000u, 0x60000000u, 0xe0000000u,
                                              0x10000000u, 0x90000000u, 0x50000000u, 0xd0000000u,
                                              0x30000000u, 0xb0000000u, 0x70000000u, 0xf0000000u};
inline constexpr uint32_t kSobolBlock1[16] = {0x00000000u, 0x80000000u, 0xc0000000u, 0x40000000u,
                                              0xa0000000u, 0x20000000u, 0x60000000u, 0xe0000000u,
                                              0xf0000000u, 0x70000000u, 0x30000000u, 0xb0000000u,
                                              0x50000000u, 0xd0000000u, 0x90000000u, 0x10000000u};

// The `count` points (a power of two, at most 16) of the aligned block starting at `first` (a
// multiple of `count`): the same values as sobol2D, much cheaper.
inline void sobol2DBlock(uint32_t first, int count, uint32_t seed, float* u, float* v) {
    const uint32_t b0 = sobol0(first), b1 = sobol1(first);
    const uint32_t s0 = sobolScrambleU(seed), s1 = sobolScrambleV(seed);
    for (int k = 0; k < count; ++k) {
        u[k] = sobolFloat(owenScramble(b0 ^ kSobolBlock0[k], s0));
        v[k] = sobolFloat(owenScramble(b1 ^ kSobolBlock1[k], s1));
    }
}

inline void sobol2DBlock16(uint32_t first, uint32_t seed, float* u, float* v) {
    sobol2DBlock(first, 16, seed, u, v);
}

}  // namespace so
