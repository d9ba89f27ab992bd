// decodeChecked() and the length guards of the generated decoders (lcmtypes/guard_decode.cmake):
// a length field larger than the bytes received, or a string length below 1, makes decoding fail
// without allocating for the claimed size.
#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <vector>

#include "mmh/common/checked_decode.hpp"

namespace {

mmh::pointcloud_t smallCloud() {
  mmh::pointcloud_t m{};
  m.header.utime = 5;
  m.header.source = "test";
  m.sensor_kind = mmh::pointcloud_t::SENSOR_DEPTH;
  m.sensor_orientation[0] = 1.0;
  m.max_range_m = 4.5f;
  m.xyz = std::vector<float>(6, 1.f);
  m.num_coords = 6;
  return m;
}

std::vector<uint8_t> encode(const mmh::pointcloud_t& m) {
  std::vector<uint8_t> buf(m.getEncodedSize());
  EXPECT_EQ(m.encode(buf.data(), 0, static_cast<int>(buf.size())), static_cast<int>(buf.size()));
  return buf;
}

// Offset of num_coords: everything after it is the xyz array (4 bytes per float).
size_t numCoordsOffset(const mmh::pointcloud_t& m, const std::vector<uint8_t>& buf) {
  return buf.size() - 4 * m.xyz.size() - 4;
}

void putBigEndian32(std::vector<uint8_t>& buf, size_t at, int32_t v) {
  const auto u = static_cast<uint32_t>(v);
  for (int i = 0; i < 4; ++i) buf[at + i] = static_cast<uint8_t>(u >> (24 - 8 * i));
}

TEST(CheckedDecode, ValidMessageDecodes) {
  const auto m = smallCloud();
  const auto buf = encode(m);
  mmh::pointcloud_t out;
  std::string why;
  EXPECT_EQ(mmh::decodeChecked(buf.data(), static_cast<uint32_t>(buf.size()), out, &why),
            mmh::DecodeOutcome::kOk)
      << why;
  EXPECT_EQ(out.xyz, m.xyz);
}

TEST(CheckedDecode, HugeArrayLengthIsUndecodableWithoutAllocating) {
  const auto m = smallCloud();
  auto buf = encode(m);
  const size_t at = numCoordsOffset(m, buf);
  for (int32_t claimed :
       {std::numeric_limits<int32_t>::max(), 1 << 28, 7, -1, std::numeric_limits<int32_t>::min()}) {
    putBigEndian32(buf, at, claimed);
    mmh::pointcloud_t out;
    EXPECT_EQ(mmh::decodeChecked(buf.data(), static_cast<uint32_t>(buf.size()), out, nullptr),
              mmh::DecodeOutcome::kUndecodable)
        << claimed;
    EXPECT_LE(out.xyz.capacity(), buf.size()) << claimed;
  }
}

TEST(CheckedDecode, StringLengthBelowOneIsUndecodable) {
  const auto m = smallCloud();
  auto buf = encode(m);
  // header: 8 bytes fingerprint, utime, seq, then the source length.
  const size_t at = 8 + 8 + 8;
  for (int32_t claimed : {0, -1, std::numeric_limits<int32_t>::min()}) {
    putBigEndian32(buf, at, claimed);
    mmh::pointcloud_t out;
    EXPECT_EQ(mmh::decodeChecked(buf.data(), static_cast<uint32_t>(buf.size()), out, nullptr),
              mmh::DecodeOutcome::kUndecodable)
        << claimed;
  }
}

TEST(CheckedDecode, WrongTypeAndInvalidContent) {
  const auto buf = encode(smallCloud());
  mmh::odometry_t odom;
  EXPECT_EQ(mmh::decodeChecked(buf.data(), static_cast<uint32_t>(buf.size()), odom, nullptr),
            mmh::DecodeOutcome::kUndecodable);
  auto bad = smallCloud();
  bad.max_range_m = std::numeric_limits<float>::quiet_NaN();
  const auto bad_buf = encode(bad);
  mmh::pointcloud_t out;
  std::string why;
  EXPECT_EQ(mmh::decodeChecked(bad_buf.data(), static_cast<uint32_t>(bad_buf.size()), out, &why),
            mmh::DecodeOutcome::kInvalid);
  EXPECT_FALSE(why.empty());
}

// A NUL inside an LCM string encodes shorter than getEncodedSize() says: refused, as are control
// characters in identifiers.
TEST(CheckedDecode, StringsWithNulOrControlCharactersAreInvalid) {
  auto m = smallCloud();
  m.header.source = std::string("mmh-sim\0xx", 10);
  std::string why;
  EXPECT_FALSE(mmh::validate(m.header, &why));
  m.header.source = "mmh-sim\x1b[2J";
  EXPECT_FALSE(mmh::validate(m.header, &why));
  mmh::heartbeat_t hb{};
  hb.service = "mmh-fpm";
  hb.host = "vm";
  hb.state_detail = std::string("ok\0", 3);
  EXPECT_FALSE(mmh::validate(hb, &why));
  hb.state_detail = "ok";
  EXPECT_TRUE(mmh::validate(hb, &why)) << why;
}

}  // namespace
