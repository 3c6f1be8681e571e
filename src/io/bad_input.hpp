// Bad input: a scene, key or value the program cannot accept. The command line
// reports it as one line naming the key and the value, with exit status 2; the
// value is shown escaped and, when long, shortened (io/message_text.hpp).
#pragma once

#include <stdexcept>
#include <string>

#include <impactlab/io/message_text.hpp>

namespace impactlab {

class BadInput : public std::runtime_error {
 public:
  BadInput(std::string key, std::string value, const std::string& reason)
      : std::runtime_error(elide_value(key) + " = " + elide_value(value) + ": " + reason),
        key_(std::move(key)),
        value_(std::move(value)) {}

  [[nodiscard]] const std::string& key() const { return key_; }
  [[nodiscard]] const std::string& value() const { return value_; }

 private:
  std::string key_;
  std::string value_;
};

}  // namespace impactlab
