#include "mmh/viewer/bind_address.hpp"

namespace mmh::viewer {

bool parseBindAddress(const std::string& text, std::string* address, uint16_t* port) {
  const size_t colon = text.rfind(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == text.size()) return false;
  std::string host = text.substr(0, colon);
  if (host.front() == '[') {
    if (host.back() != ']') return false;
    host = host.substr(1, host.size() - 2);
  }
  const std::string port_text = text.substr(colon + 1);
  if (port_text.find_first_not_of("0123456789") != std::string::npos || port_text.size() > 5)
    return false;
  const unsigned long value = std::stoul(port_text);
  if (value > 65535) return false;
  *address = host;
  *port = static_cast<uint16_t>(value);
  return true;
}

}  // namespace mmh::viewer
