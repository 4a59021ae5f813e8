#pragma once
// A 64-bit checksum of a byte array, for detecting damaged checkpoint data (a flipped bit, a
// zeroed block). Each 8-byte word w updates h <- rotl(h ^ mix(w), 27) * K with K odd and mix a
// bijection (the splitmix64 finaliser; Steele, Lea & Flood, OOPSLA 2014): every step is a
// bijection of h for a fixed word and of the word for a fixed h, so two arrays of the same length
// that differ in one word always give different sums, and random damage is missed with
// probability 2^-64. Not cryptographic: it guards against accidents, not against an adversary.
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace ballista {

inline std::uint64_t checksum64(const void* data, std::size_t bytes) {
  auto mix = [](std::uint64_t z) {
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  };
  auto step = [&](std::uint64_t h, std::uint64_t w) {
    h ^= mix(w);
    return ((h << 27) | (h >> 37)) * 0x9E3779B97F4A7C15ULL;
  };
  const auto* p = static_cast<const unsigned char*>(data);
  std::uint64_t h = mix(bytes + 0x2545F4914F6CDD1DULL);
  std::size_t k = 0;
  for (; k + 8 <= bytes; k += 8) {
    std::uint64_t w;
    std::memcpy(&w, p + k, 8);
    h = step(h, w);
  }
  if (k < bytes) {
    std::uint64_t w = 0;
    std::memcpy(&w, p + k, bytes - k);
    h = step(h, w);
  }
  return mix(h);
}

}  // namespace ballista
