// The summary table `sixway eval --scene` prints (eval/summary_table.h): one row per method in the given
// order, numbers with two decimals, "-" where the report has nothing to measure.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "eval/summary_table.h"

namespace sixway::test {
namespace {

TEST(SummaryTableTest, OneRowPerMethodWithItsFigures) {
  const nlohmann::json summary = {{"image",
                                   {{"neural",
                                     {{"psnr_masked_db", 24.181},
                                      {"mean_frame_psnr_masked_db", 24.0},
                                      {"psnr_full_db", 30.5},
                                      {"psnr_band_db", 22.5}}},
                                    {"reference", {{"psnr_masked_db", nullptr}, {"psnr_full_db", 40.0}}}}},
                                  {"median_ms", {{"neural", {{"total_ms", 12.34}, {"wall_ms", 20.0}}}}},
                                  {"lightmap", {{"psnr_masked_db", 20.88}}},
                                  {"lightmap_ms", {{"psnr_masked_db", 25.1}}},
                                  {"detail", {{"methods", {{"neural", 0.812}}}}}};
  const nlohmann::json equalTime = {
      {"budget_ms", 12.3}, {"equal_time_spp", 1}, {"equal_time", {{"psnr_masked_db", 9.5}}}};
  const std::string table = eval::summaryTable(summary, equalTime, {"reference", "neural"});
  EXPECT_THAT(table, ::testing::HasSubstr("  neural                24.18           24.00       30.50         "
                                          " 22.50    0.81           12.3           20.0\n"));
  EXPECT_THAT(table, ::testing::HasSubstr("  reference                 -               -       40.00         "
                                          "     -       -              -              -\n"));
  EXPECT_LT(table.find("  reference "), table.find("  neural ")) << "rows in the order given";
  EXPECT_THAT(table, ::testing::HasSubstr(
                         "neural lightmaps: 20.88 dB against the single-scattering baker's, 25.10 dB"));
  EXPECT_THAT(table, ::testing::HasSubstr("path tracer in the neural frame's 12.3 ms: 1 spp, 9.50 dB"));
  EXPECT_EQ(table.find("frame-to-frame"), std::string::npos) << "no temporal line without the report's";
}

TEST(SummaryTableTest, FrameToFrameChangeOverTheTruths) {
  const nlohmann::json temporal = {
      {"truth", {{"rms", 0.02}, {"rms_without_noise", 0.015}, {"noise_rms", 0.0132}}},
      {"truth_noise_removed", true},
      {"methods", {{"neural", {{"rms_ratio", 1.061}}}, {"reference", {{"rms_ratio", nullptr}}}}}};
  const std::string table = eval::summaryTable({{"temporal", temporal}}, nullptr, {"neural", "reference"});
  EXPECT_THAT(table,
              ::testing::HasSubstr("frame-to-frame change (RMS where the smoke is): truth 0.0200, 0.0150 "
                                   "without its noise (0.0132); x the truth's: neural 1.06 reference -\n"));
}

}  // namespace
}  // namespace sixway::test
