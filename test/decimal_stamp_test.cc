#include "dataset/decimal_stamp.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <random>
#include <string>

namespace vio {
namespace {

// The stamp `text` reads as, or -1 with the test failed when it does not.
int64_t Ns(const std::string& text) {
  int64_t t_ns = -1;
  EXPECT_EQ(ParseDecimalSeconds(text, &t_ns), DecimalStampStatus::kOk) << text;
  return t_ns;
}

TEST(DecimalStamp, ReadsDecimalAndScientificSecondsToTheNanosecond) {
  EXPECT_EQ(Ns("1403715529.112143517"), 1403715529112143517LL);
  // numpy's "%.18e", which evo's TUM writer uses: 19 significant digits.
  EXPECT_EQ(Ns("1.403715529112143517e+09"), 1403715529112143517LL);
  EXPECT_EQ(Ns("1.403715529112143517E9"), 1403715529112143517LL);
  EXPECT_EQ(Ns("14037155291121.43517e-4"), 1403715529112143517LL);
  EXPECT_EQ(Ns("0.000001403715529112143517e15"), 1403715529112143517LL);
  EXPECT_EQ(Ns("1403715529"), 1403715529000000000LL);
  EXPECT_EQ(Ns("1e9"), 1000000000000000000LL);
  EXPECT_EQ(Ns("+2.5"), 2500000000LL);
  EXPECT_EQ(Ns(".5"), 500000000LL);
  EXPECT_EQ(Ns("5."), 5000000000LL);
  EXPECT_EQ(Ns("-1.5"), -1500000000LL);
  EXPECT_EQ(Ns("-1.5e-9"), -1);
  EXPECT_EQ(Ns("0007.000000001"), 7000000001LL);
  EXPECT_EQ(Ns("0"), 0);
  EXPECT_EQ(Ns("-0.0e5"), 0);
}

TEST(DecimalStamp, CutsDigitsBelowOneNanosecond) {
  EXPECT_EQ(Ns("1.0000000019"), 1000000001LL);
  EXPECT_EQ(Ns("-1.0000000019"), -1000000001LL);  // toward zero
  EXPECT_EQ(Ns("9.99e-10"), 0);
  EXPECT_EQ(Ns("1e-999999999999"), 0);  // the exponent is clamped, not wrapped
}

TEST(DecimalStamp, AgreesWithPrintfOnRandomStamps) {
  // Integer nanoseconds printed as "%lld.%09lld" seconds and back.
  std::mt19937_64 rng(42);
  std::uniform_int_distribution<int64_t> u(-8999999999999999999LL,
                                           8999999999999999999LL);
  for (int i = 0; i < 1000; ++i) {
    const int64_t t = u(rng);
    const uint64_t a = t < 0 ? -static_cast<uint64_t>(t) : t;
    char text[64];
    std::snprintf(text, sizeof(text), "%s%llu.%09llu", t < 0 ? "-" : "",
                  static_cast<unsigned long long>(a / 1000000000ULL),
                  static_cast<unsigned long long>(a % 1000000000ULL));
    ASSERT_EQ(Ns(text), t) << text;
  }
}

TEST(DecimalStamp, RefusesWhatIsNotANumber) {
  for (const char* text :
       {"", "+", "-", ".", "e5", ".e5", "1e", "1e+", "1.5.3", "1.-5", "--1",
        "0x10", "nan", "inf", "1_000", "1.5s", "1 5", "1e5.5", "1,5"}) {
    int64_t t_ns = 7;
    EXPECT_EQ(ParseDecimalSeconds(text, &t_ns), DecimalStampStatus::kNotANumber)
        << "'" << text << "'";
    EXPECT_EQ(t_ns, 7) << text;  // untouched
  }
}

TEST(DecimalStamp, RefusesStampsPastNineBillionSeconds) {
  int64_t t_ns = 0;
  EXPECT_EQ(ParseDecimalSeconds("8999999999.999999999", &t_ns),
            DecimalStampStatus::kOk);
  for (const char* text : {"9000000000", "9e9", "-9e9", "99999999999.5", "1e10",
                           "1e999999999999", "18446744073709551616"}) {
    EXPECT_EQ(ParseDecimalSeconds(text, &t_ns), DecimalStampStatus::kOutOfRange)
        << text;
  }
}

}  // namespace
}  // namespace vio
