// Small SSE2 helpers for the per-lane bookkeeping of 16-ray packets (hard_shadow.cpp,
// area_shadow.cpp). Every x86-64 has SSE2, and the oracle already assumes x86-64 (its samplers are
// target_clones); the compiler leaves these loops over mixed integer, byte and float lanes lane by
// lane, where they cost a third of the oracle's own time per packet.
#pragma once

#include <cstdint>

#include <emmintrin.h>

namespace so {

// The set bits of a 4-bit mask (_mm_movemask_ps). x86-64 before x86-64-v2 has no popcount
// instruction, and GCC calls a library function for __builtin_popcount there.
inline int setBits4(int m) {
    return (m & 1) + (m >> 1 & 1) + (m >> 2 & 1) + (m >> 3 & 1);
}

// The set bits of a 16-bit mask (a packet's lanes), as setBits4 four at a time.
inline int setBits16(uint32_t m) {
    return setBits4(int(m & 15u)) + setBits4(int(m >> 4 & 15u)) + setBits4(int(m >> 8 & 15u)) +
           setBits4(int(m >> 12 & 15u));
}

// Lanes g .. g + 3 of an int mask array (-1 or 0) as a float mask.
inline __m128 laneMask4(const int* lanes, int g) {
    return _mm_castsi128_ps(_mm_loadu_si128(reinterpret_cast<const __m128i*>(lanes + g)));
}

// The smallest of four floats (NaN lanes may be dropped: test them apart).
inline float horizontalMin(__m128 v) {
    v = _mm_min_ps(v, _mm_shuffle_ps(v, v, _MM_SHUFFLE(1, 0, 3, 2)));
    v = _mm_min_ps(v, _mm_shuffle_ps(v, v, _MM_SHUFFLE(2, 3, 0, 1)));
    return _mm_cvtss_f32(v);
}

}  // namespace so
