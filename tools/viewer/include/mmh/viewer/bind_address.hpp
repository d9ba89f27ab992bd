// The --bind option of mmh-viewer: "127.0.0.1:8765", "[::1]:8765" or "0.0.0.0:8765".
#pragma once

#include <cstdint>
#include <string>

namespace mmh::viewer {

// Splits into address and port; false if malformed (no port, port beyond 65535, "[" unclosed).
bool parseBindAddress(const std::string& text, std::string* address, uint16_t* port);

}  // namespace mmh::viewer
