#include <gtest/gtest.h>

#include "gpu/address_space.h"

namespace sixway::gpu {
namespace {

constexpr uint64_t MiB = uint64_t(1) << 20;

TEST(AddressSpace, EnoughBesideTheMappedSpaceIsNoShortfall) {
  EXPECT_FALSE(addressSpaceShortfall(670 * MiB + kAddressSpaceHeadroomBytes, 670 * MiB).has_value());
  EXPECT_FALSE(addressSpaceShortfall(uint64_t(1) << 40, 670 * MiB).has_value());
}

TEST(AddressSpace, TooLittleNamesTheLimitAndWhatItNeeds) {
  const auto shortfall = addressSpaceShortfall(900 * MiB, 670 * MiB);
  ASSERT_TRUE(shortfall.has_value());
  EXPECT_NE(shortfall->find("ulimit -v) of 900 MiB leaves 230 MiB"), std::string::npos) << *shortfall;
  EXPECT_NE(shortfall->find("at least " + std::to_string(670 + (kAddressSpaceHeadroomBytes >> 20)) + " MiB"),
            std::string::npos)
      << *shortfall;
  // A limit below what is mapped already (a limit lowered after start) leaves nothing, without wrapping.
  EXPECT_NE(addressSpaceShortfall(500 * MiB, 670 * MiB)->find("leaves 0 MiB"), std::string::npos);
  // One byte short of the headroom is short.
  EXPECT_TRUE(addressSpaceShortfall(670 * MiB + kAddressSpaceHeadroomBytes - 1, 670 * MiB).has_value());
}

}  // namespace
}  // namespace sixway::gpu
