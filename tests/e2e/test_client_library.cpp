// The C++ client library's own pieces: page reassembly (without a network),
// its defaults, and reassembly of a real multi-page state from the server.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <set>

#include "rbsim/client/client.h"
#include "rbsim/client/page_assembler.h"
#include "server_test.h"

namespace rbsim::e2e {
namespace {

// A step's state of `total` bodies cut into pages of `perPage`.
std::vector<rbsim::world_state_t> pagesOf(int64_t step, int32_t total, int32_t perPage) {
  std::vector<rbsim::world_state_t> pages;
  const int32_t count = (total + perPage - 1) / perPage;
  for (int32_t p = 0; p < count; ++p) {
    rbsim::world_state_t page{};
    page.utime = 1000 + step;
    page.step = step;
    page.world_revision = 1;
    page.page = p;
    page.num_pages = count;
    page.total_bodies = total;
    page.first_body_index = p * perPage;
    for (int32_t i = p * perPage; i < std::min(total, (p + 1) * perPage); ++i) {
      rbsim::body_state_t body{};
      body.id = i + 1;
      body.name = "b" + std::to_string(i);
      page.bodies.push_back(body);
    }
    page.num_bodies = static_cast<int32_t>(page.bodies.size());
    pages.push_back(page);
  }
  return pages;
}

TEST(PageAssembler, MergesPagesInAnyOrder) {
  client::PageAssembler<rbsim::world_state_t> assembler;
  auto pages = pagesOf(7, 10, 4);  // 4 + 4 + 2
  ASSERT_EQ(pages.size(), 3u);
  EXPECT_FALSE(assembler.add(pages[2]));
  EXPECT_FALSE(assembler.add(pages[0]));
  EXPECT_FALSE(assembler.add(pages[0])) << "a duplicate completes nothing";
  const auto whole = assembler.add(pages[1]);
  ASSERT_TRUE(whole.has_value());
  EXPECT_EQ(whole->step, 7);
  EXPECT_EQ(whole->page, 0);
  EXPECT_EQ(whole->num_pages, 1);
  EXPECT_EQ(whole->num_bodies, 10);
  ASSERT_EQ(whole->bodies.size(), 10u);
  for (int32_t i = 0; i < 10; ++i) EXPECT_EQ(whole->bodies[static_cast<std::size_t>(i)].id, i + 1);
}

TEST(PageAssembler, ALostPageLeavesItsStepIncompleteButNotTheNext) {
  client::PageAssembler<rbsim::world_state_t> assembler;
  const auto step7 = pagesOf(7, 10, 4);
  const auto step8 = pagesOf(8, 10, 4);
  EXPECT_FALSE(assembler.add(step7[0]));
  EXPECT_FALSE(assembler.add(step7[1]));  // step7[2] is lost
  EXPECT_FALSE(assembler.add(step8[0]));
  EXPECT_FALSE(assembler.add(step8[1]));
  const auto whole = assembler.add(step8[2]);
  ASSERT_TRUE(whole.has_value());
  EXPECT_EQ(whole->step, 8);
  EXPECT_EQ(whole->bodies.size(), 10u);
  // A republication of the same step (new utime, as while paused) is a new one.
  auto again = pagesOf(8, 10, 4);
  for (auto& page : again) page.utime += 5;
  EXPECT_FALSE(assembler.add(again[0]));
  EXPECT_FALSE(assembler.add(step8[1])) << "a page of the older publication restarts the assembly";
  EXPECT_FALSE(assembler.add(again[1]));
  EXPECT_FALSE(assembler.add(again[2])) << "so the mixed publication never completes";
}

TEST(PageAssembler, RejectsInconsistentPages) {
  client::PageAssembler<rbsim::world_state_t> assembler;
  auto single = pagesOf(1, 3, 10).front();
  EXPECT_TRUE(assembler.add(single).has_value());
  auto lying = single;
  lying.num_bodies = 5;  // more than it holds
  EXPECT_FALSE(assembler.add(lying));
  auto outOfRange = single;
  outOfRange.page = 1;
  EXPECT_FALSE(assembler.add(outOfRange));
  auto pages = pagesOf(2, 10, 4);
  pages[1].first_body_index = 5;  // a gap
  assembler.add(pages[0]);
  assembler.add(pages[1]);
  EXPECT_FALSE(assembler.add(pages[2])) << "bodies that do not add up are dropped";
}

TEST(ClientDefaults, UrlAndClientId) {
  ASSERT_EQ(unsetenv("LCM_DEFAULT_URL"), 0);
  EXPECT_EQ(client::resolveLcmUrl(""), client::kDefaultUrl);
  EXPECT_EQ(client::resolveLcmUrl("memq://"), "memq://");
  ASSERT_EQ(setenv("LCM_DEFAULT_URL", "udpm://239.255.76.67:7701?ttl=0", 1), 0);
  EXPECT_EQ(client::resolveLcmUrl(""), "udpm://239.255.76.67:7701?ttl=0");
  EXPECT_EQ(client::resolveLcmUrl("memq://"), "memq://") << "an explicit URL wins";
  ASSERT_EQ(setenv("LCM_DEFAULT_URL", "", 1), 0);
  EXPECT_EQ(client::resolveLcmUrl(""), client::kDefaultUrl)
      << "an empty variable means the default";
  unsetenv("LCM_DEFAULT_URL");

  // "cpp-<hostname>-<pid>", with "-N" for the N-th id of the process.
  char host[256] = {};
  gethostname(host, sizeof host - 1);
  const std::string base = "cpp-" + std::string(host) + "-" + std::to_string(getpid());
  const std::string first = client::makeDefaultClientId();
  const std::string second = client::makeDefaultClientId();
  EXPECT_EQ(first.rfind(base, 0), 0u) << first;
  EXPECT_EQ(second.rfind(base + "-", 0), 0u) << second;
  EXPECT_NE(first, second) << "two clients of one process must not share an id";

  client::Client local(client::ClientOptions{"memq://", "RBSIM_", ""});
  ASSERT_TRUE(local.good());
  EXPECT_EQ(local.clientId().rfind("cpp-" + std::string(host) + "-", 0), 0u) << local.clientId();
  EXPECT_EQ(local.waitForAck(local.pause(), std::chrono::milliseconds(10)), std::nullopt)
      << "nobody answers on memq://";
}

using ClientPaging = ServerTest;

// 1200 bodies do not fit one 60 kB page: the server sends several per step.
TEST_F(ClientPaging, ReassemblesAMultiPageStateFromTheServer) {
  const std::string world = scratchPath("many.yaml");
  {
    std::ofstream out(world);
    out << "world: {dt: 0.001, gravity: [0, 0, 0]}\nbodies:\n";
    for (int i = 0; i < 1200; ++i)
      out << "  - {name: s" << i << ", shape: {type: sphere, radius: 0.05}, mass: 1, position: ["
          << i << ", 0, 0], linear_velocity: [0, 0, 1]}\n";
  }
  startServer(world, {"--paused", "--state-rate", "0"});
  // Count the raw pages too, to be sure the state really was paged.
  struct PageCount {
    std::set<int32_t> pages;
  } count;
  client().lcm().subscribeFunction(
      client().channel("STATE"),
      +[](const lcm::ReceiveBuffer*, const std::string&, const rbsim::world_state_t* page,
          PageCount* c) { c->pages.insert(page->page); },
      &count);

  stepAndWait(3);
  const auto& state = history().at(3);
  EXPECT_GE(count.pages.size(), 2u) << "the state should have come in several pages";
  EXPECT_EQ(state.num_pages, 1);
  EXPECT_EQ(state.total_bodies, 1200);
  ASSERT_EQ(state.bodies.size(), 1200u);
  for (std::size_t i = 0; i < state.bodies.size(); ++i) {
    EXPECT_EQ(state.bodies[i].name, "s" + std::to_string(i));
    EXPECT_NEAR(state.bodies[i].position[2], 0.003, 1e-12);
  }
  ASSERT_TRUE(client().world().has_value());
  EXPECT_EQ(client().world()->bodies.size(), 1200u) << "the world description is reassembled too";
}

}  // namespace
}  // namespace rbsim::e2e
