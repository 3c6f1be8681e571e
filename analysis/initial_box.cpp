#include <impactlab/analysis/initial_box.hpp>

namespace impactlab {

namespace {

// splitmix64's output function (Steele, Lea, Flood 2014): a bijection of
// 64-bit words whose outputs for consecutive inputs look independent
std::uint64_t mix(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

}  // namespace

double box_uniform(std::uint64_t seed, int point, int sample, int key) {
  std::uint64_t state = mix(seed);
  for (const int counter : {point, sample, key})
    state = mix(state ^ static_cast<std::uint64_t>(static_cast<std::uint32_t>(counter)));
  // the top 53 bits as a fraction of 2^53
  return static_cast<double>(state >> 11) * 0x1.0p-53;
}

double box_value(const BoxRange& range, std::uint64_t seed, int point, int sample, int key) {
  return range.from + (range.to - range.from) * box_uniform(seed, point, sample, key);
}

}  // namespace impactlab
