// The first two steps every received LCM buffer goes through (lcm_runtime.hpp, and the fuzz
// targets of tests/fuzz/): decode as the channel's type without letting the generated code throw,
// then validate(). The clock check and delivery stay in ServiceContext.
#pragma once

#include <cstdint>
#include <exception>
#include <string>

#include "mmh/common/message_validation.hpp"

namespace mmh {

enum class DecodeOutcome {
  kOk,           // decoded and valid
  kUndecodable,  // wrong type (fingerprint), truncated, or lengths beyond the buffer
  kInvalid,      // decoded, but validate() refused it (reason in *why)
};

template <class Msg>
DecodeOutcome decodeChecked(const void* data, uint32_t size, Msg& msg, std::string* why) {
  if (size > static_cast<uint32_t>(INT32_MAX)) return DecodeOutcome::kUndecodable;
  int status = -1;
  try {
    status = msg.decode(data, 0, static_cast<int>(size));
  } catch (const std::exception&) {
    status = -1;  // e.g. std::bad_alloc; lengths are bounded by the buffer (guard_decode.cmake)
  }
  if (status < 0) return DecodeOutcome::kUndecodable;
  if (!validate(msg, why)) return DecodeOutcome::kInvalid;
  return DecodeOutcome::kOk;
}

}  // namespace mmh
