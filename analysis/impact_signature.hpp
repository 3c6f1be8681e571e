// The walls an orbit hits, in order: its impact signature
// (OrbitEvaluation::signature, "+1 +1 -1", "+1 c+1") without its contact
// phases ("c+1"), which may appear or end along a branch or a curve without
// stopping it. A change of it is a grazing.
#pragma once

#include <cstddef>
#include <string>

namespace impactlab {

inline std::string walls_hit(const std::string& signature) {
  std::string walls;
  std::size_t begin = 0;
  while (begin < signature.size()) {
    std::size_t end = signature.find(' ', begin);
    if (end == std::string::npos) end = signature.size();
    if (end > begin && signature[begin] != 'c') {
      if (!walls.empty()) walls += ' ';
      walls.append(signature, begin, end - begin);
    }
    begin = end + 1;
  }
  return walls;
}

}  // namespace impactlab
