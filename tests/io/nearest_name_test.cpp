// The name nearest a misspelt one (io/nearest_name.hpp), for the messages'
// "did you mean ...?": typing slips of each kind, and nothing suggested
// where no name is close.
#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <impactlab/io/nearest_name.hpp>

namespace impactlab {
namespace IMPACTLAB_TEST_FILE_SCOPE {

const std::vector<std::string_view> keys = {"omega", "V0", "mu", "e_n", "e_t",
                                            "integrator.rtol", "integrator.atol",
                                            "initial.theta", "initial.theta_dot"};

TEST(NearestName, EachKindOfSlipFindsTheKey) {
  EXPECT_EQ(nearest_name("omegaa", keys), "omega");              // an extra letter
  EXPECT_EQ(nearest_name("omga", keys), "omega");                // a missing one
  EXPECT_EQ(nearest_name("omeqa", keys), "omega");               // a wrong one
  EXPECT_EQ(nearest_name("omgea", keys), "omega");               // two swapped
  EXPECT_EQ(nearest_name("integrator.rtl", keys), "integrator.rtol");
  EXPECT_EQ(nearest_name("initial.theta_dto", keys), "initial.theta_dot");
  EXPECT_EQ(nearest_name("v0", keys), "V0");
}

TEST(NearestName, NothingCloseSuggestsNothing) {
  EXPECT_EQ(nearest_name("xyzzy", keys), std::nullopt);
  EXPECT_EQ(nearest_name("frequency", keys), std::nullopt);
  EXPECT_EQ(nearest_name("omega", {}), std::nullopt);
}

// the nearest, not the first within reach: "e_x" is one edit from both
// e_n and e_t, and the first of equals is kept; "e_tt" is nearer e_t
TEST(NearestName, TheNearestWinsAndTheFirstOfEquals) {
  EXPECT_EQ(nearest_name("e_x", keys), "e_n");
  EXPECT_EQ(nearest_name("e_tt", keys), "e_t");
}

}  // namespace
}  // namespace impactlab
