#pragma once
// Geometry sources for a body: primitives and mesh files, all turned into tetrahedra.
// Errors are thrown as InputError(file, "", reason); the scene loader adds the key path.
#include <array>
#include <string>

#include "mesh/tet_mesh.hpp"

namespace fissure {

using Vec3 = std::array<double, 3>;

// Primitives, tetrahedralized by TetGen at target edge length `edge_length` (λ).
TetMesh tetrahedralize_box(const Vec3& min, const Vec3& max, double edge_length);
TetMesh tetrahedralize_sphere(const Vec3& center, double radius, double edge_length);
TetMesh tetrahedralize_cylinder(const Vec3& p0, const Vec3& p1, double radius, double edge_length);

// A closed surface, tetrahedralized by TetGen at target edge length λ.
TetMesh tetrahedralize_surface(const SurfaceMesh& surface, double edge_length,
                               const std::string& source_file);

// Closed surfaces: .obj, .stl (ASCII or binary), .off, .ply (ASCII or binary little endian).
SurfaceMesh read_surface(const std::string& path);

// TetGen .node/.ele pair; `path` may name either file or the common base name.
TetMesh read_tetgen(const std::string& path);

// Dispatch on extension: .node/.ele read as is, surfaces tetrahedralized at λ.
TetMesh load_mesh_file(const std::string& path, double edge_length);

}  // namespace fissure
