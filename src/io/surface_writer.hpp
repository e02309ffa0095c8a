#pragma once
// Per-frame output of the embedded mesh (paper §5.2): the boundary surface, crack faces included,
// as VTU and OBJ (`output.surface`), and the whole tet mesh as VTU (`output.tets`), each with a
// ParaView collection (surface.pvd, tets.pvd). Files are written atomically.
#include <string>
#include <vector>

#include "fracture/embedded_mesh.hpp"
#include "io/vtu_writer.hpp"

namespace fissure {

class SurfaceWriter {
 public:
  SurfaceWriter(std::string dir, bool surface, bool tets);
  // Writes frame `frame` at simulated time `time`. `damage` (φ per particle) may be empty (no
  // fracture); `body` is the body of each particle.
  void write(int frame, double time, const EmbeddedMesh& mesh, const std::vector<double>& damage,
             const std::vector<int>& body);
  // A resumed run: the collections list frames 0 … times.size() − 1 at these times again.
  void reset(const std::vector<double>& times);

 private:
  std::string dir_;
  bool surface_, tets_;
  PvdIndex surface_pvd_, tets_pvd_;
};

// Removes the embedded-mesh files an earlier run left in `dir`.
void remove_surface_output(const std::string& dir);

}  // namespace fissure
