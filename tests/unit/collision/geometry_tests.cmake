# Tests of the geometry part of collision detection: hulls, support
# functions, colliders, GJK distance and libccd penetration.
rbsim_add_gtest(test_collision_geometry
  unit/collision/test_convex_hull.cpp
  unit/collision/test_support.cpp
  unit/collision/test_collider.cpp
  unit/collision/test_gjk.cpp
  unit/collision/test_signed_distance.cpp
)
target_link_libraries(test_collision_geometry PRIVATE rbsim_physics_internal)
