// An output that cannot be written: a folder that refuses new files, a full
// disk, a file size limit, a rename that fails. Not bad input (the same
// command can succeed once there is room or permission): the command line
// reports it as one line with an exit status of its own, 4.
#pragma once

#include <stdexcept>
#include <string>

namespace impactlab {

class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace impactlab
