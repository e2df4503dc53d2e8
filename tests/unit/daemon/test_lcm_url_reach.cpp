// rbserver warns at start when its LCM traffic leaves the host.
#include <gtest/gtest.h>

#include <cstdlib>

#include "config/server_settings.h"
#include "daemon/lcm_url_reach.h"

namespace rbsim {
namespace {

TEST(LcmUrlReach, TtlIsReadFromUdpmUrls) {
  EXPECT_EQ(multicastTtl("udpm://239.255.76.67:7667?ttl=0"), 0);
  EXPECT_EQ(multicastTtl("udpm://239.255.76.67:7667?recv_buf_size=2097152&ttl=1"), 1);
  EXPECT_EQ(multicastTtl("udpm://239.255.76.67:7667?ttl=32&recv_buf_size=4096"), 32);
  EXPECT_EQ(multicastTtl("udpm://239.255.76.67:7667"), 0);  // LCM's default
  EXPECT_EQ(multicastTtl("udpm://239.255.76.67:7667?recv_buf_size=1"), 0);
  EXPECT_EQ(multicastTtl("memq://"), std::nullopt);
  EXPECT_EQ(multicastTtl("udpm://239.255.76.67:7667?ttl=one"), std::nullopt);
}

TEST(LcmUrlReach, TheDefaultsStayOnTheHostAndOthersAreWarnedAbout) {
  EXPECT_EQ(reachWarning(ServerSettings{}.lcmUrl), "");
  const std::string warning = reachWarning("udpm://239.255.76.67:7667?ttl=1");
  EXPECT_NE(warning.find("ttl=1"), std::string::npos) << warning;
  EXPECT_NE(warning.find("no authentication"), std::string::npos) << warning;
  EXPECT_NE(reachWarning("udpm://239.255.76.67:7667?ttl=x"), "");

  // An empty URL is $LCM_DEFAULT_URL, as for lcm_create.
  ASSERT_EQ(setenv("LCM_DEFAULT_URL", "udpm://239.255.76.67:7667?ttl=1", 1), 0);
  EXPECT_EQ(multicastTtl(""), 1);
  ASSERT_EQ(unsetenv("LCM_DEFAULT_URL"), 0);
  EXPECT_EQ(multicastTtl(""), 0);
}

}  // namespace
}  // namespace rbsim
