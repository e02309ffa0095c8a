#pragma once
// What an input error says: the InputError a call throws, its message, and a check that it
// names the file and the reason.
#include <gtest/gtest.h>

#include <optional>
#include <string>

#include "core/error.hpp"

namespace fissure::test {

// The InputError `call` throws, or none if it returns.
template <class Call>
std::optional<InputError> input_error(Call&& call) {
  try {
    call();
  } catch (const InputError& e) {
    return e;
  }
  return std::nullopt;
}

// The message of the InputError `call` throws, or "" if it returns.
template <class Call>
std::string input_error_message(Call&& call) {
  const auto e = input_error(call);
  return e ? e->what() : "";
}

// Runs `call`, expecting an InputError naming `file` whose message contains `reason`.
template <class Call>
void expect_input_error(Call&& call, const std::string& file, const std::string& reason) {
  const auto e = input_error(call);
  if (!e) {
    ADD_FAILURE() << "expected an InputError containing '" << reason << "'";
    return;
  }
  const std::string what = e->what();
  EXPECT_EQ(e->file(), file) << what;
  EXPECT_NE(what.find(file), std::string::npos) << what;
  EXPECT_NE(what.find(reason), std::string::npos) << what;
}

}  // namespace fissure::test
