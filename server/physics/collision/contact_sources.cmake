# Narrow-phase contact manifolds.
target_sources(rbsim_physics PRIVATE
  collision/contact_generation.cpp
  collision/piece_pair_contact.cpp
  collision/sphere_contacts.cpp
  collision/capsule_contacts.cpp
  collision/box_box_contact.cpp
  collision/hull_contacts.cpp
  collision/plane_contacts.cpp
  collision/general_contacts.cpp
  collision/support_features.cpp
  collision/polygon_clipping.cpp
  collision/closest_points.cpp
  collision/box_features.cpp
  collision/triangle_contacts.cpp
  collision/triangle_mesh_contacts.cpp
)
