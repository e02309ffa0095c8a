#include "app/output_registry.hpp"

#include "app/frames_output.hpp"
#include "app/probes_output.hpp"
#include "scene/kind_list.hpp"

namespace fissure {

namespace {

std::vector<OutputKind>& kinds() {
  static std::vector<OutputKind> registered = [] {
    std::vector<OutputKind> builtin;
    add_kind(builtin,
             {"probes",
              {},
              nullptr,
              [](const OutputContext& c) {
                return std::make_unique<ProbesOutput>(c.scene, c.ledger, c.halo);
              }},
             "output");
    add_kind(
        builtin,
        {"frames",
         {},
         nullptr,
         [](const OutputContext& c) { return std::make_unique<FramesOutput>(c.scene.config); }},
        "output");
    return builtin;
  }();
  return registered;
}

}  // namespace

void register_output(OutputKind kind) { add_kind(kinds(), std::move(kind), "output"); }

const std::vector<OutputKind>& output_kinds() { return kinds(); }

}  // namespace fissure
