// RBSIM_CONTACTS against the mechanics: a box resting on the ground is held
// up by exactly its weight, and a dropped ball's contact impulse is exactly
// the momentum change the states show. The server runs paused and is
// stepped, with contacts published every step (worlds/contacts.yaml).

#include <gtest/gtest.h>
#include <lcm/lcm-cpp.hpp>

#include <cmath>
#include <map>
#include <rbsim/contacts_t.hpp>

#include "e2e_paths.h"
#include "rigid_body_math.h"
#include "server_test.h"

namespace rbsim::e2e {
namespace {

constexpr double kGravity = 9.81;  // m/s²

class Contacts : public ServerTest {
 protected:
  void SetUp() override {
    ServerTest::SetUp();
    m_lcm = std::make_unique<lcm::LCM>(kUrl);
    ASSERT_TRUE(m_lcm->good());
    // Every step's contacts are kept (LCM's default queue keeps 30 messages
    // while nobody handles them).
    m_lcm->subscribe("RBSIM_CONTACTS", &Contacts::onContacts, this)->setQueueCapacity(100000);
    startServer("contacts.yaml", {"--paused", "--state-rate", "0"});
  }

  // Steps n and waits until the contacts of the last of them have arrived.
  void stepAndCollect(int64_t n) {
    const rbsim::ack_t ack = stepAndWait(n);
    const int64_t last = ack.effective_step + n - 1;
    waitFor("the contacts of step " + std::to_string(last), [&] {
      while (m_lcm->handleTimeout(0) > 0) {
      }
      return m_contacts.count(last) > 0;
    });
  }

  // The points between two bodies at a step (every page of it).
  std::vector<rbsim::contact_t> between(int64_t step, int32_t a, int32_t b) const {
    std::vector<rbsim::contact_t> points;
    const auto found = m_contacts.find(step);
    if (found == m_contacts.end()) return points;
    for (const rbsim::contact_t& c : found->second)
      if (c.body_a == a && c.body_b == b) points.push_back(c);
    return points;
  }

  std::map<int64_t, std::vector<rbsim::contact_t>> m_contacts;  // by step

 private:
  void onContacts(const lcm::ReceiveBuffer*, const std::string&, const rbsim::contacts_t* page) {
    EXPECT_EQ(page->num_pages, 1) << "a few contacts fit one page";
    EXPECT_EQ(page->total_contacts, page->num_contacts);
    auto& points = m_contacts[page->step];
    points.insert(points.end(), page->contacts.begin(), page->contacts.end());
  }

  std::unique_ptr<lcm::LCM> m_lcm;
};

TEST_F(Contacts, ARestingBoxIsHeldUpByItsWeightAtItsFourCorners) {
  stepAndCollect(300);
  const int32_t ground = description("ground").id;
  const int32_t crate = description("crate").id;
  const double mass = description("crate").mass;
  const double dt = client().world()->dt;
  const int64_t step = currentStep();
  const std::vector<rbsim::contact_t> points = between(step, ground, crate);
  ASSERT_EQ(points.size(), 4u) << "a face on the ground: four corners";
  double total = 0.0;
  for (const rbsim::contact_t& c : points) {
    EXPECT_NEAR(c.normal[0], 0.0, 1e-12);
    EXPECT_NEAR(c.normal[1], 0.0, 1e-12);
    EXPECT_NEAR(c.normal[2], 1.0, 1e-12) << "from the ground (A) to the crate (B)";
    EXPECT_NEAR(std::abs(c.position[0]), 0.1, 1e-3) << "at a corner";
    EXPECT_NEAR(std::abs(c.position[1]), 0.1, 1e-3) << "at a corner";
    EXPECT_NEAR(c.position[2], 0.0, 1e-3);
    EXPECT_LT(c.depth, 1e-3);
    EXPECT_EQ(c.classification, rbsim::contact_t::RESTING);
    EXPECT_GT(c.normal_impulse, 0.0);
    total += c.normal_impulse;
  }
  // At rest the contact impulse over a step cancels gravity's m g dt.
  EXPECT_NEAR(total, mass * kGravity * dt, 1e-9 * mass * kGravity * dt);
  // And the corners share it evenly (the solver pushes a face as a block).
  for (const rbsim::contact_t& c : points) EXPECT_NEAR(c.normal_impulse, total / 4, 1e-9 * total);
}

TEST_F(Contacts, AFallingBallsImpulseIsItsMomentumChange) {
  stepAndCollect(400);  // 0.2 m of fall takes 0.2 s; the bounce comes well before
  const int32_t ground = description("ground").id;
  const int32_t ball = description("ball").id;
  const double mass = description("ball").mass;
  const double dt = client().world()->dt;
  // The first step with an impulse on the ball.
  int64_t impact = -1;
  for (const auto& [step, points] : m_contacts) {
    for (const rbsim::contact_t& c : between(step, ground, ball))
      if (c.normal_impulse > 0.0) impact = step;
    if (impact >= 0) break;
  }
  ASSERT_GT(impact, 0) << "the ball hits the ground";
  const std::vector<rbsim::contact_t> points = between(impact, ground, ball);
  ASSERT_EQ(points.size(), 1u) << "a sphere touches at one point";
  const rbsim::contact_t& c = points[0];
  EXPECT_EQ(c.classification, rbsim::contact_t::COLLIDING);
  EXPECT_LT(c.normal_velocity, -1.0) << "about sqrt(2 g h) = 2 m/s towards the ground";
  EXPECT_NEAR(c.position[0], 1.0, 1e-9);
  EXPECT_NEAR(c.position[2], 0.0, 1e-3);

  // Semi-implicit Euler: m v' = m v − m g dt + J, so J = m (v' − v) + m g dt.
  const double before = history().body(impact - 1, "ball").linear_velocity[2];
  const double after = history().body(impact, "ball").linear_velocity[2];
  const double impulse = mass * (after - before) + mass * kGravity * dt;
  EXPECT_NEAR(c.normal_impulse, impulse, 1e-9 * impulse);
  // Restitution 0.5 against the ground's 0 (the pair takes the larger): the
  // ball leaves at half its approach speed.
  EXPECT_NEAR(after, -0.5 * c.normal_velocity, 0.02 * std::abs(c.normal_velocity));
}

// The client library reassembles RBSIM_CONTACTS like the states: the
// contacts it holds for a step are those on the wire.
TEST_F(Contacts, TheClientLibraryHoldsTheLatestContacts) {
  stepAndCollect(300);
  const int64_t step = currentStep();
  waitFor("the client's contacts of step " + std::to_string(step), [&] {
    client().handle(std::chrono::milliseconds(10));
    return client().latestContacts() && client().latestContacts()->step == step;
  });
  const rbsim::contacts_t& held = *client().latestContacts();
  const auto& wire = m_contacts.at(step);
  ASSERT_EQ(held.contacts.size(), wire.size());
  EXPECT_EQ(held.num_pages, 1);
  EXPECT_EQ(held.total_contacts, static_cast<int32_t>(wire.size()));
  for (std::size_t i = 0; i < wire.size(); ++i) {
    EXPECT_EQ(held.contacts[i].body_a, wire[i].body_a);
    EXPECT_EQ(held.contacts[i].body_b, wire[i].body_b);
    EXPECT_EQ(held.contacts[i].normal_impulse, wire[i].normal_impulse);
  }
  EXPECT_GT(client().contactsCount(), 0u);
}

}  // namespace
}  // namespace rbsim::e2e
