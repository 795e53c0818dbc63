#include "streams.h"

namespace taebp::streams {

std::uint64_t StreamSeed(std::uint64_t seed, std::uint64_t salt) {
  std::uint64_t x = seed ^ (salt * 0x9E3779B97F4A7C15ULL);
  for (int i = 0; i < 2; ++i) {
    x += 0x9E3779B97F4A7C15ULL;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
    x ^= x >> 31;
  }
  return x;
}

double IdUniform(std::uint64_t seed, const std::string& id, std::uint64_t salt) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (const unsigned char c : id) h = (h ^ c) * 0x100000001b3ULL;
  return static_cast<double>(StreamSeed(seed ^ h, salt) >> 11) * 0x1.0p-53;
}

}  // namespace taebp::streams
