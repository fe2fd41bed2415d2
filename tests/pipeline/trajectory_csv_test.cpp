// The trajectory CSV's bookkeeping against exact rational arithmetic.

#include <gtest/gtest.h>

#include "pipeline/trajectory_csv.h"

namespace {

using namespace coinroll;

TEST(SampleCount, MatchesExactRationalArithmeticWhereTheQuotientRoundsBelowAWholeNumber) {
  // Rows k = 0 .. floor(d / S) for every duration 0.01 .. 30 s (step 0.01 s) and common sample
  // steps, all decimals: floor(dNum SDen / (dDen SNum)) + 1 in integers. In many of these the
  // double d / S lands just below its whole number (0.29 / 0.01 = 28.999999999999996).
  struct Ratio {
    long num, den;
  };
  int roundedBelow = 0, failures = 0;
  for (long n = 1; n <= 3000; ++n) {
    for (const Ratio S :
         {Ratio{1, 100}, Ratio{1, 1000}, Ratio{1, 10}, Ratio{2, 100}, Ratio{5, 100}, Ratio{25, 100}, Ratio{4, 1000}}) {
      const double d = static_cast<double>(n) / 100, dt = static_cast<double>(S.num) / static_cast<double>(S.den);
      const long expected = n * S.den / (100 * S.num) + 1;
      const long actual = pipeline::sampleCount(d, dt);
      if (actual != expected && ++failures <= 10) {
        ADD_FAILURE() << "sampleCount(" << n << " / 100 s, " << S.num << " / " << S.den << " s) = " << actual
                      << ", exactly " << expected;
      }
      if (n * S.den % (100 * S.num) == 0 && d / dt < static_cast<double>(expected - 1)) ++roundedBelow;
    }
  }
  EXPECT_EQ(failures, 0);
  EXPECT_GT(roundedBelow, 100);
}

}  // namespace
