// SHA-256 (FIPS 180-4) through OpenSSL's EVP interface, as lowercase hex. Used for cell keys and image-file digests.
#pragma once

#include <string>

namespace blocklab {

std::string sha256_hex(const std::string& bytes);
// Streams the file; throws Error("<path>: ...") when it cannot be read.
std::string sha256_file_hex(const std::string& path);

}  // namespace blocklab
