// SHA-256 (FIPS 180-4, computed by OpenSSL) of a byte string, as 64 lowercase
// hexadecimal digits:
// the digest the model cache keeps beside each compiled object and checks
// before the object is loaded (oscillators/model_file/compile_cache.hpp).
#pragma once

#include <string>
#include <string_view>

namespace impactlab {

std::string sha256_hex(std::string_view bytes);

}  // namespace impactlab
