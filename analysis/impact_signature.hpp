// The walls an orbit hits, in order: its impact signature
// (OrbitEvaluation::signature, "+1 +1 -1", "+1 c+1") without its contact
// phases ("c+1"), which may appear or end along a branch or a curve without
// stopping it, and with the impacts on a wall just before a contact phase
// on it written once: a chatter ending in contact, whose count of resolved
// impacts before the accumulation is taken changes from orbit to orbit
// while the map stays smooth. A change of it is a grazing.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace impactlab {

inline std::string walls_hit(const std::string& signature) {
  std::vector<std::string> walls;
  std::size_t begin = 0;
  while (begin < signature.size()) {
    std::size_t end = signature.find(' ', begin);
    if (end == std::string::npos) end = signature.size();
    if (end > begin) {
      std::string token = signature.substr(begin, end - begin);
      if (token.front() != 'c') {
        walls.push_back(std::move(token));
      } else {
        // the chatter landing in this contact phase: one token
        const std::string wall = token.substr(1);
        std::size_t run = 0;
        while (run < walls.size() && walls[walls.size() - 1 - run] == wall) ++run;
        if (run > 1) walls.resize(walls.size() - run + 1);
      }
    }
    begin = end + 1;
  }
  std::string joined;
  for (const std::string& wall : walls) joined += (joined.empty() ? "" : " ") + wall;
  return joined;
}

}  // namespace impactlab
