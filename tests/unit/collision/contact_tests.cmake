# Tests of the contact part of collision detection (narrow phase): manifolds
# against closed forms, one file per family of routines.
rbsim_add_gtest(test_collision_contacts
  unit/collision/test_contacts_spheres.cpp
  unit/collision/test_contacts_capsules.cpp
  unit/collision/test_contacts_boxes.cpp
  unit/collision/test_contacts_hulls.cpp
  unit/collision/test_hull_search.cpp
  unit/collision/test_contacts_cylinders.cpp
  unit/collision/test_contacts_classification.cpp
)
target_link_libraries(test_collision_contacts PRIVATE rbsim_physics_internal)
