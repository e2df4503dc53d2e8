#include "session/wrench_scheduler.h"

#include <algorithm>
#include <cassert>

namespace rbsim {

void WrenchScheduler::add(const WrenchRequest& request) { m_pending.push_back(request); }

int WrenchScheduler::start(const WrenchRequest& request) {
  const auto sameClientAndBody = [&](const WrenchRequest& active) {
    return active.client == request.client && (request.body.empty() || active.body == request.body);
  };
  if (isClear(request.mode)) {
    const bool everyClient = request.mode == WrenchMode::ClearAllClients;
    return static_cast<int>(std::erase_if(m_active, [&](const WrenchRequest& active) {
      const bool owned = everyClient ? (request.body.empty() || active.body == request.body)
                                     : sameClientAndBody(active);
      return owned && active.mode != WrenchMode::OneStep;
    }));
  }
  if (request.mode == WrenchMode::Persistent) {
    std::erase_if(m_active, [&](const WrenchRequest& active) {
      return sameClientAndBody(active) && active.mode == WrenchMode::Persistent;
    });
  }
  m_active.push_back(request);
  return 0;
}

int WrenchScheduler::countClearedBy(const WrenchRequest& clear) const {
  // A copy steps through the steps at which pending requests start, up to the
  // clear's: before each, what finishStep would have retired by then goes
  // (finishStep(s - 1) retires every wrench that ends before step s), then
  // the requests due start in acceptance order, as applyForStep does.
  WrenchScheduler preview = *this;
  preview.m_pending.push_back(clear);
  std::vector<int64_t> steps;
  for (const WrenchRequest& request : preview.m_pending)
    if (request.firstStep <= clear.firstStep) steps.push_back(request.firstStep);
  std::sort(steps.begin(), steps.end());
  steps.erase(std::unique(steps.begin(), steps.end()), steps.end());
  for (const int64_t step : steps) {
    preview.finishStep(step - 1);
    std::vector<WrenchRequest> stillPending;
    for (std::size_t i = 0; i < preview.m_pending.size(); ++i) {
      const WrenchRequest& request = preview.m_pending[i];
      if (request.firstStep > step) {
        stillPending.push_back(request);
        continue;
      }
      const int removed = preview.start(request);
      if (i + 1 == preview.m_pending.size() && step == clear.firstStep) return removed;
    }
    preview.m_pending.swap(stillPending);
  }
  return 0;  // not reached: the clear is the last pending request and due at its own step
}

void WrenchScheduler::applyForStep(World& world, int64_t step) {
  // Start what is due, in acceptance order; keep the rest waiting.
  std::vector<WrenchRequest> stillPending;
  for (const WrenchRequest& request : m_pending) {
    if (request.firstStep <= step) {
      start(request);
    } else {
      stillPending.push_back(request);
    }
  }
  m_pending.swap(stillPending);

  // Drop the wrenches of removed bodies, then fix world points of wrenches
  // acting for the first time in their body (in its shape frame, the frame
  // body points are given in) and apply them all.
  std::erase_if(m_active,
                [&](const WrenchRequest& active) { return world.findBody(active.body).isNull(); });
  for (WrenchRequest& active : m_active) {
    const BodyId id = world.findBody(active.body);
    const BodyView body = world.body(id);
    const BodyDescription& description = body.description();
    if (active.pointFrame == WrenchFrame::World) {
      active.point = description.bodyToShapePoint(body.worldToBody(active.point));
      active.pointFrame = WrenchFrame::ShapeFrame;
    }
    Wrench wrench;
    wrench.point = description.shapeToBodyPoint(active.point);
    if (active.frame == WrenchFrame::World) {
      wrench.force = active.force;
      wrench.torque = active.torque;
      wrench.frame = Wrench::Frame::WorldAtBodyPoint;
    } else {
      wrench.force = description.shapeToBodyVector(active.force);
      wrench.torque = description.shapeToBodyVector(active.torque);
      wrench.frame = Wrench::Frame::Body;
    }
    // Limits and decoding have checked the values; an error here is a bug.
    [[maybe_unused]] const auto applied = world.applyWrench(id, wrench);
    assert(applied);
  }
}

void WrenchScheduler::finishStep(int64_t step) {
  std::erase_if(m_active, [&](const WrenchRequest& active) {
    switch (active.mode) {
      case WrenchMode::OneStep:
        return true;
      case WrenchMode::Duration:
        return step >= active.firstStep + active.durationSteps - 1;
      default:
        return false;
    }
  });
}

void WrenchScheduler::removeBody(const std::string& body) {
  const auto onBody = [&](const WrenchRequest& r) { return r.body == body; };
  std::erase_if(m_pending, onBody);
  std::erase_if(m_active, onBody);
}

}  // namespace rbsim
