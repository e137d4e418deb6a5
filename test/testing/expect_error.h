#ifndef VIO_TEST_TESTING_EXPECT_ERROR_H_
#define VIO_TEST_TESTING_EXPECT_ERROR_H_

// Checks on the errors of bad input: the project promises that every one
// names the file and the line or key, so tests look at the message text.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

namespace vio {

// Runs f and returns the message of the E it throws; records a test failure
// and returns "" when f throws nothing.
template <typename E, typename F>
std::string ErrorMessage(F&& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  ADD_FAILURE() << "no exception of the expected type was thrown";
  return "";
}

// Expects f to throw an E whose message contains text.
template <typename E, typename F>
void ExpectErrorContaining(F&& f, const std::string& text) {
  EXPECT_THAT(ErrorMessage<E>(std::forward<F>(f)), ::testing::HasSubstr(text));
}

}  // namespace vio

#endif  // VIO_TEST_TESTING_EXPECT_ERROR_H_
