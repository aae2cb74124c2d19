#pragma once

#include <cstdint>

namespace aaf::trace {

/// SplitMix64 finaliser: a bijective 64-bit mix with good avalanche.
inline std::uint64_t mix64(std::uint64_t z) {
    z += 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

/// Counter-based random numbers for one pixel and pass: every value depends
/// only on (seed, pixel index, pass, draw index), never on thread scheduling.
/// Any 32-bit pass number gives its own stream (progressive references use
/// one pass per round of samples).
class PixelRng {
  public:
    PixelRng(std::uint64_t seed, std::uint64_t pixel_index, std::uint32_t pass)
        : state_(mix64(seed ^ mix64(pixel_index ^ mix64(pass)))) {}

    std::uint64_t next_u64() { return mix64(state_ += 0x632be59bd9b4e019ull); }
    std::uint32_t next_u32() { return std::uint32_t(next_u64() >> 32); }
    /// Uniform in [0, 1) with 24 bits, so it is exactly representable as float.
    float next_float() { return float(next_u64() >> 40) * 0x1p-24f; }
    /// Two independent uniforms in [0, 1) of 24 bits each from one 64-bit draw
    /// (half the cost of two next_float calls, for 2D samples).
    void next_float2(float &u1, float &u2) {
        const std::uint64_t bits = next_u64();
        u1 = float(bits >> 40) * 0x1p-24f;
        u2 = float((bits >> 16) & 0xffffffu) * 0x1p-24f;
    }

  private:
    std::uint64_t state_;
};

/// The image of `index` under a pseudo-random permutation of [0, count)
/// selected by `key`: a bijection on the enclosing power-of-two range (odd
/// multiplies, xor-shifts and adds on the masked bits), cycle-walked into range.
inline std::uint32_t permute_index(std::uint32_t index, std::uint32_t count, std::uint32_t key) {
    std::uint32_t mask = count - 1;
    mask |= mask >> 1;
    mask |= mask >> 2;
    mask |= mask >> 4;
    mask |= mask >> 8;
    mask |= mask >> 16;
    do {
        index = (index ^ key) & mask;
        index = (index * 0x9e3779b1u) & mask;
        index ^= index >> 3;
        index = (index + (key >> 8)) & mask;
        index = (index * 0x85ebca6bu) & mask;
        index ^= index >> 5;
        index = (index * (0x27d4eb2du | 1u)) & mask;
        index ^= index >> 7;
    } while (index >= count);
    return index;
}

}  // namespace aaf::trace
