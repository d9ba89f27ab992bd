// libFuzzer target for one LCM message type, MMH_FUZZ_TYPE (e.g. local_map_t, set per target by
// tests/fuzz/CMakeLists.txt): the bytes go through the receive path of every service
// (decodeChecked: decode + validate), and an accepted message through consume().
#include <cstddef>
#include <cstdint>
#include <string>

#include "consume.hpp"
#include "mmh/common/checked_decode.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > (size_t{1} << 24)) return 0;
  mmh::MMH_FUZZ_TYPE msg;
  std::string why;
  if (mmh::decodeChecked(data, static_cast<uint32_t>(size), msg, &why) == mmh::DecodeOutcome::kOk)
    mmh::fuzz::consume(msg);
  return 0;
}
