#include "scene/option_parsers.hpp"

#include <stdexcept>

namespace fissure {

namespace {

template <class Options>
std::vector<OptionParser<Options>>& parsers() {
  static std::vector<OptionParser<Options>> list;
  return list;
}

template <class Options>
void add(OptionParser<Options> parser) {
  auto& list = parsers<Options>();
  for (const auto& p : list)
    if (p.name == parser.name)
      throw std::logic_error("the option parser '" + parser.name + "' is registered twice");
  list.push_back(std::move(parser));
}

}  // namespace

void register_option_parser(IntegratorOptionParser parser) { add(std::move(parser)); }
void register_option_parser(ModelOptionParser parser) { add(std::move(parser)); }
void register_option_parser(ColliderOptionParser parser) { add(std::move(parser)); }
void register_option_parser(OutputOptionParser parser) { add(std::move(parser)); }

const std::vector<IntegratorOptionParser>& integrator_option_parsers() {
  return parsers<IntegratorOptions>();
}

const std::vector<ModelOptionParser>& model_option_parsers() { return parsers<ModelOptions>(); }

const std::vector<ColliderOptionParser>& collider_option_parsers() {
  return parsers<ColliderOptions>();
}

const std::vector<OutputOptionParser>& output_option_parsers() { return parsers<OutputOptions>(); }

}  // namespace fissure
