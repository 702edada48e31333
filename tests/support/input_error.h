#pragma once
// Checks on the one-line InputError messages: which file they name and which problem they state.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <exception>
#include <filesystem>
#include <string>

#include "io/error.h"

namespace sixway::test {

// The message of the InputError that `action` throws; records a test failure and returns "" when it throws
// nothing or something else.
template <typename Action>
std::string inputErrorMessage(Action&& action) {
  try {
    action();
  } catch (const io::InputError& error) {
    return error.what();
  } catch (const std::exception& error) {
    ADD_FAILURE() << "expected an InputError, got another exception: " << error.what();
    return "";
  }
  ADD_FAILURE() << "expected an InputError, nothing was thrown";
  return "";
}

// Matches a single-line message "<path>: ..." that states `problem`.
inline auto namesFileAndProblem(const std::filesystem::path& path, const std::string& problem) {
  using ::testing::AllOf, ::testing::HasSubstr, ::testing::Not, ::testing::StartsWith;
  return AllOf(StartsWith(path.string() + ": "), HasSubstr(problem), Not(HasSubstr("\n")));
}

}  // namespace sixway::test
