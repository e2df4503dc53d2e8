# Tests of the broad_phase part of collision detection: rbsim_add_gtest(test_collision_broad_phase ...)
rbsim_add_gtest(test_collision_broad_phase
  unit/collision/test_dynamic_aabb_tree.cpp
  unit/collision/test_broad_phase.cpp
  unit/collision/test_time_of_impact.cpp
  unit/collision/test_collision_detector.cpp
)
target_link_libraries(test_collision_broad_phase PRIVATE rbsim_physics_internal)
