#include <gtest/gtest.h>

#include "mmh/viewer/bind_address.hpp"

namespace mmh::viewer {
namespace {

TEST(BindAddress, ParsesIpv4Ipv6AndPort) {
  std::string address;
  uint16_t port = 0;
  ASSERT_TRUE(parseBindAddress("127.0.0.1:8765", &address, &port));
  EXPECT_EQ(address, "127.0.0.1");
  EXPECT_EQ(port, 8765);
  ASSERT_TRUE(parseBindAddress("[::1]:0", &address, &port));
  EXPECT_EQ(address, "::1");
  EXPECT_EQ(port, 0);
}

TEST(BindAddress, RefusesMalformed) {
  std::string address;
  uint16_t port = 0;
  for (const char* text : {"", "8765", "127.0.0.1", "127.0.0.1:", ":8765", "host:99999", "host:12a",
                           "[::1:8765", "host:1234567"})
    EXPECT_FALSE(parseBindAddress(text, &address, &port)) << text;
}

}  // namespace
}  // namespace mmh::viewer
