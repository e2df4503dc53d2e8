# Collision geometry, colliders and signed distance (GJK + libccd).
target_sources(rbsim_physics PRIVATE
  collision/convex_hull.cpp
  collision/convex_geometry.cpp
  collision/collider.cpp
  collision/gjk.cpp
  collision/ccd_support.cpp
  collision/signed_distance.cpp
  collision/triangle_mesh_bvh.cpp
  collision/active_edges.cpp
  collision/triangle_mesh_collider.cpp
)
