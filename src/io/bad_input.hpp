// Bad input: a scene, key or value the program cannot accept. The command line
// reports it as one line naming the key and the value, with exit status 2.
#pragma once

#include <stdexcept>
#include <string>

namespace impactlab {

class BadInput : public std::runtime_error {
 public:
  BadInput(std::string key, std::string value, const std::string& reason)
      : std::runtime_error(key + " = " + value + ": " + reason),
        key_(std::move(key)),
        value_(std::move(value)) {}

  [[nodiscard]] const std::string& key() const { return key_; }
  [[nodiscard]] const std::string& value() const { return value_; }

 private:
  std::string key_;
  std::string value_;
};

}  // namespace impactlab
