#pragma once
// Suggestions for a misspelt name: the nearest valid one by edit distance, and the message for a
// value that is not one of a list. No YAML, so the layers that check their own choices (an
// integrator's type, an ARKODE method) can use it without the config reader.
#include <string>
#include <vector>

namespace fissure {

// The closest of `candidates` to `word` by edit distance, or "" if none is close.
std::string nearest(const std::string& word, const std::vector<std::string>& candidates);

// "unknown <what> '<value>'; did you mean '<nearest>'? (valid: a, b, …)" for a value that is not
// one of `valid`.
std::string unknown_choice(const std::string& what, const std::string& value,
                           const std::vector<std::string>& valid);

}  // namespace fissure
