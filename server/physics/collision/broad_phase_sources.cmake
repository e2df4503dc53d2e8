# Broad phase, the collision pipeline and time of impact.
target_sources(rbsim_physics PRIVATE
  collision/dynamic_aabb_tree.cpp
  collision/broad_phase.cpp
  collision/collision_detector.cpp
  collision/time_of_impact.cpp
)
