#include "app/output_registry.hpp"

#include <stdexcept>

#include "app/frames_output.hpp"
#include "app/probes_output.hpp"

namespace fissure {

namespace {

void add(std::vector<OutputKind>& kinds, OutputKind kind) {
  for (const auto& k : kinds)
    if (k.name == kind.name)
      throw std::logic_error("the output '" + kind.name + "' is registered twice");
  register_option_parser(OutputOptionParser{kind.name, kind.keys, kind.parse});
  kinds.push_back(std::move(kind));
}

std::vector<OutputKind>& kinds() {
  static std::vector<OutputKind> registered = [] {
    std::vector<OutputKind> builtin;
    add(builtin, {"probes", {}, nullptr, [](const OutputContext& c) {
                    return std::make_unique<ProbesOutput>(c.scene, c.ledger);
                  }});
    add(builtin, {"frames", {}, nullptr, [](const OutputContext& c) {
                    return std::make_unique<FramesOutput>(c.scene.config);
                  }});
    return builtin;
  }();
  return registered;
}

}  // namespace

void register_output(OutputKind kind) { add(kinds(), std::move(kind)); }

const std::vector<OutputKind>& output_kinds() { return kinds(); }

}  // namespace fissure
