#pragma once
// The crack-face set of paper §5.2: interior faces of the tet mesh across which the material
// broke. A face joins the set when the bond between the particles of its two tets breaks; it
// leaves the set (is retired) once it has caused a vertex split. Being cracked is permanent: a
// retired face still separates its tets when later splits group the tets around a vertex.
#include <cstdint>
#include <vector>

namespace fissure {

class CrackFaces {
 public:
  explicit CrackFaces(int tet_count) : state_(4 * static_cast<std::size_t>(tet_count), kIntact) {}

  // True for either side's id (4 t + k) of a cracked face.
  bool cracked(int face) const { return state_[face] != kIntact; }
  bool active(int face) const { return state_[face] == kActive; }
  // Adds the face with ids `face` and `opposite` (its two sides) to the set.
  void add(int face, int opposite);
  // Marks an active face (either side) retired; `end_pass` drops it from the set.
  void retire(int face, int opposite);
  // After a splitting pass: drops the retired faces and counts every face as examined.
  void end_pass();

  // The faces in the set (one side's id each), in the order they were added; those from
  // `fresh_begin()` on were added since the last pass.
  const std::vector<int>& set() const { return set_; }
  std::size_t fresh_begin() const { return fresh_begin_; }
  // Faces ever cracked, retired or not.
  std::size_t total() const { return total_; }

 private:
  static constexpr std::uint8_t kIntact = 0, kActive = 1, kRetired = 2;
  std::vector<std::uint8_t> state_;  // per face side
  std::vector<int> set_;
  std::size_t fresh_begin_ = 0;
  std::size_t total_ = 0;
  std::size_t retired_ = 0;  // retired since the last pass, still in set_
};

}  // namespace fissure
