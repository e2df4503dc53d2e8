#pragma once
// For tests and benchmarks of the library's internal layers (collision,
// time of impact), which take the internal Body: copies of a world's bodies,
// made from what the public API shows of them (BodyView). A World hands out
// no Body of its own.
//
// The copies share their descriptions with one another across update(), as
// long as the world keeps the same bodies: a CollisionDetector keeps its
// per-body caches by description, so detection on updated copies runs as it
// does inside the world's step.

#include <cstddef>
#include <memory>
#include <span>
#include <stdexcept>
#include <vector>

#include "physics/body/body.h"
#include "rbsim/physics/world.h"

namespace rbsim::testing {

// A copy of one body: description, dynamics, state (bit for bit), serial,
// sleep and freeze.
inline Body bodyCopy(const BodyView& view, std::shared_ptr<const BodyDescription> description) {
  Body body(std::move(description), view.dynamics(), view.state());
  body.moveTo(view.state());  // as it is: the constructor normalises the quaternion
  body.setSerial(view.serial());
  body.setSleeping(view.isSleeping());
  body.setFreezeReason(view.freezeReason());
  return body;
}

inline Body bodyCopy(const World& world, BodyId id) {
  const BodyView view = world.body(id);  // throws for an id of no body of the world
  return bodyCopy(view, std::make_shared<const BodyDescription>(view.description()));
}

// Every body of a world, in dense order.
class BodyCopies {
 public:
  explicit BodyCopies(const World& world) { update(world); }

  // The copies brought to the world's current state; new copies (and new
  // descriptions) when the world's bodies changed.
  void update(const World& world) {
    bool same = m_bodies.size() == static_cast<std::size_t>(world.bodyCount());
    for (std::size_t i = 0; same && i < m_bodies.size(); ++i)
      same = m_bodies[i].serial() == world.bodyAt(static_cast<int>(i)).serial();
    if (!same) {
      m_bodies.clear();
      for (const BodyView view : world.bodies())
        m_bodies.push_back(bodyCopy(view, std::make_shared<const BodyDescription>(view.description())));
      return;
    }
    for (std::size_t i = 0; i < m_bodies.size(); ++i) {
      const BodyView view = world.bodyAt(static_cast<int>(i));
      m_bodies[i] = bodyCopy(view, m_bodies[i].sharedDescription());
    }
  }

  std::span<const Body> bodies() const { return m_bodies; }

 private:
  std::vector<Body> m_bodies;
};

}  // namespace rbsim::testing
