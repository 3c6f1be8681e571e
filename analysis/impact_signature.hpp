// Whether two orbits hit the same walls in the same order: the comparison of
// impact signatures (OrbitEvaluation::signature, "+1 +1 -1", "+1 c+1") that
// a branch or a curve makes from point to point. A contact phase ("c+1") may
// appear or end along it without stopping it, and a chatter ending in
// contact may resolve more or fewer impacts before its accumulation is taken
// (the count changes from orbit to orbit while the map stays smooth); any
// other change is a grazing.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace impactlab {

namespace detail {

// The signature's tokens, in order.
inline std::vector<std::string> signature_tokens(const std::string& signature) {
  std::vector<std::string> tokens;
  std::size_t begin = 0;
  while (begin < signature.size()) {
    std::size_t end = signature.find(' ', begin);
    if (end == std::string::npos) end = signature.size();
    if (end > begin) tokens.push_back(signature.substr(begin, end - begin));
    begin = end + 1;
  }
  return tokens;
}

inline std::string joined(const std::vector<std::string>& tokens) {
  std::string text;
  for (const std::string& token : tokens) text += (text.empty() ? "" : " ") + token;
  return text;
}

}  // namespace detail

// The walls an orbit hits, in order: the signature without its contact phases.
inline std::string walls_hit(const std::string& signature) {
  std::vector<std::string> walls;
  for (std::string& token : detail::signature_tokens(signature))
    if (token.front() != 'c') walls.push_back(std::move(token));
  return detail::joined(walls);
}

// The signature with a chatter landing in a contact phase written as one
// token: three or more impacts on a wall just before a contact phase on it
// ("+1 +1 +1 c+1" → "+1… c+1"). Shorter runs are kept as they are: an impact
// that leaves the wall before a plastic landing on it ("-1 -1 c-1") comes
// and goes by a graze.
inline std::string chatter_collapsed(const std::string& signature) {
  std::vector<std::string> kept;
  for (std::string& token : detail::signature_tokens(signature)) {
    if (token.front() == 'c') {
      const std::string wall = token.substr(1);
      std::size_t run = 0;
      while (run < kept.size() && kept[kept.size() - 1 - run] == wall) ++run;
      if (run >= 3) {
        kept.resize(kept.size() - run);
        kept.push_back(wall + "…");
      }
    }
    kept.push_back(std::move(token));
  }
  return detail::joined(kept);
}

// The same walls in the same order, but for contact phases appearing or
// ending, or a chatter's count (three or more) of resolved impacts before
// its contact phase.
inline bool same_walls_hit(const std::string& a, const std::string& b) {
  return walls_hit(a) == walls_hit(b) || chatter_collapsed(a) == chatter_collapsed(b);
}

}  // namespace impactlab
