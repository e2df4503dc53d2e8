#pragma once
// World::forEachBody (declared in world.h, which sees Body only as a name).

#include "physics/body/body.h"
#include "physics/parallel/task_pool.h"
#include "rbsim/physics/world.h"

namespace rbsim {

template <class Visit>
void World::forEachBody(Visit&& visit) {
  constexpr std::size_t kBodiesPerChunk = 128;
  const std::size_t chunks = chunkCount(m_bodies.size(), kBodiesPerChunk);
  m_chunkSpeeds.assign(chunks, SpeedBound{});
  forEachChunk(taskPool(), m_bodies.size(), kBodiesPerChunk,
               [&](std::size_t chunk, std::size_t begin, std::size_t end) {
                 for (std::size_t i = begin; i < end; ++i) visit(i, m_chunkSpeeds[chunk]);
               });
  for (const SpeedBound& bound : m_chunkSpeeds) noteSpeeds(bound.squaredSpeed, bound.squaredSpin);
}

}  // namespace rbsim
