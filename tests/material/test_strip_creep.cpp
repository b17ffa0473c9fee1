// Unit tests of the strip under a prescribed tension history (`sartor creep`):
// the strain split, the rows at load jumps, the thesis' closed forms for the
// creep-recovery test, sampling independence and history input checks.

#include "material/strip_creep.hpp"

#include "common/error.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#ifndef SARTOR_TEST_DATA_DIR
#error "SARTOR_TEST_DATA_DIR must name tests/material/data"
#endif

namespace sartor {
namespace {

std::string data(const std::string& name) {
  return std::string(SARTOR_TEST_DATA_DIR) + "/" + name;
}

::testing::AssertionResult near_relative(double actual, double expected, double rel) {
  const double error = std::abs(actual - expected);
  if (error <= rel * std::abs(expected)) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << "actual " << ::testing::PrintToString(actual) << " vs expected "
         << ::testing::PrintToString(expected) << ": relative error " << error / std::abs(expected)
         << " > " << rel;
}

::testing::AssertionResult contains(const std::string& text, const std::string& part) {
  if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "'" << text << "' does not contain '" << part << "'";
}

template <class Call>
std::string input_error(Call&& call) {
  try {
    call();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError thrown";
  return "";
}

// The thesis experiment: 20 kg on an 8 cm wide strip, one hour loaded, one
// hour of recovery, cotton-twill warp (elastic modulus K = 2 E).
const double tension = 20.0 * 9.80665 / 0.08;
const double hour = 3600.0;

DirectionalMaterial cotton_warp() {
  return preset_fabric("cotton_twill").in(Direction::warp);
}

std::vector<const StripState*> rows_at(const std::vector<StripState>& rows, double time) {
  std::vector<const StripState*> found;
  for (const auto& row : rows) {
    if (row.time == time) found.push_back(&row);
  }
  return found;
}

TEST(StripCreep, StrainComponentsAddUpInEveryRow) {
  const DirectionalMaterial m = cotton_warp();
  const TensionHistory history = TensionHistory::creep_recovery(tension, hour, hour);
  const auto rows = simulate_strip(m, history, log_sample_times(history, 0.1, 10));
  ASSERT_GT(rows.size(), 60u);
  for (const auto& row : rows) {
    SCOPED_TRACE(row.time);
    EXPECT_NEAR(row.strain_total,
                row.strain_elastic + row.strain_viscoelastic + row.strain_permanent,
                1e-15 * row.strain_total);
    // 1 + total = (1 + eps_elastic)(1 + eps_v + eps_p), eps_elastic from the curve.
    const double nonelastic = row.strain_viscoelastic + row.strain_permanent;
    const double eps_elastic = m.elastic.strain_at_tension(row.tension);
    EXPECT_TRUE(
        near_relative(1.0 + row.strain_total, (1.0 + eps_elastic) * (1.0 + nonelastic), 1e-15));
    EXPECT_GE(row.strain_viscoelastic, 0.0);
    EXPECT_GE(row.strain_permanent, 0.0);
  }
}

TEST(StripCreep, RowsOnBothSidesOfLoadJump) {
  const DirectionalMaterial m = cotton_warp();
  const TensionHistory history = TensionHistory::creep_recovery(tension, hour, hour);
  const auto rows = simulate_strip(m, history, uniform_sample_times(history, 60.0));
  const auto at_zero = rows_at(rows, 0.0);
  ASSERT_EQ(at_zero.size(), 2u);
  EXPECT_EQ(at_zero[0], &rows[0]);
  EXPECT_EQ(at_zero[0]->tension, 0.0);
  EXPECT_EQ(at_zero[0]->strain_total, 0.0);
  EXPECT_EQ(at_zero[1]->tension, tension);
  // Immediately after the jump: elastic only, sigma / K.
  const double K = 2.0 * 32600.0;
  EXPECT_TRUE(near_relative(at_zero[1]->strain_elastic, tension / K, 1e-15));
  EXPECT_EQ(at_zero[1]->strain_viscoelastic, 0.0);
  EXPECT_EQ(at_zero[1]->strain_permanent, 0.0);
  EXPECT_TRUE(near_relative(at_zero[1]->strain_total, tension / K, 1e-15));
}

TEST(StripCreep, RowsOnBothSidesOfUnloadJump) {
  const DirectionalMaterial m = cotton_warp();
  const TensionHistory history = TensionHistory::creep_recovery(tension, hour, hour);
  const auto rows = simulate_strip(m, history, uniform_sample_times(history, 60.0));
  const auto at_unload = rows_at(rows, hour);
  ASSERT_EQ(at_unload.size(), 2u);
  const StripState& loaded = *at_unload[0];
  const StripState& unloaded = *at_unload[1];
  EXPECT_EQ(loaded.tension, tension);
  EXPECT_EQ(unloaded.tension, 0.0);
  // The creep strains do not jump; the elastic strain vanishes.
  EXPECT_EQ(unloaded.strain_viscoelastic, loaded.strain_viscoelastic);
  EXPECT_EQ(unloaded.strain_permanent, loaded.strain_permanent);
  EXPECT_EQ(unloaded.strain_elastic, 0.0);
  EXPECT_GT(loaded.strain_elastic, 0.0);
  EXPECT_TRUE(
      near_relative(loaded.strain_total - unloaded.strain_total, loaded.strain_elastic, 1e-13));
}

TEST(StripCreep, TotalStrainAtEndOfLoadingMatchesClosedForm) {
  for (const auto& preset : fabric_presets()) {
    for (const Direction d : {Direction::warp, Direction::weft}) {
      SCOPED_TRACE(std::string(preset.name) + ":" + name_of(d));
      const DirectionalMaterial m = preset_fabric(preset.name).in(d);
      const double E = m.creep.creep_modulus;
      const double K = m.elastic.initial_modulus();
      const TensionHistory history = TensionHistory::creep_recovery(tension, hour, hour);
      const auto rows = simulate_strip(m, history, log_sample_times(history, 1.0, 5));
      const auto at_unload = rows_at(rows, hour);
      ASSERT_EQ(at_unload.size(), 2u);
      const double creep = tension / E * -std::expm1(-m.creep.lambda_load * hour);
      EXPECT_TRUE(near_relative(at_unload[0]->strain_total,
                                (1.0 + tension / K) * (1.0 + creep) - 1.0, 1e-12));
    }
  }
}

TEST(StripCreep, PermanentStrainAtEndOfRecoveryMatchesClosedForm) {
  for (const auto& preset : fabric_presets()) {
    for (const Direction d : {Direction::warp, Direction::weft}) {
      SCOPED_TRACE(std::string(preset.name) + ":" + name_of(d));
      const DirectionalMaterial m = preset_fabric(preset.name).in(d);
      const CreepParameters& p = m.creep;
      const TensionHistory history = TensionHistory::creep_recovery(tension, hour, hour);
      const auto rows = simulate_strip(m, history, log_sample_times(history, 1.0, 5));
      const StripState& last = rows.back();
      EXPECT_EQ(last.time, 2.0 * hour);
      EXPECT_EQ(last.tension, 0.0);
      const double saturation = tension / p.creep_modulus;
      const double loaded_fraction = -std::expm1(-p.lambda_load * hour);
      EXPECT_TRUE(
          near_relative(last.strain_permanent, p.alpha * saturation * loaded_fraction, 1e-12));
      EXPECT_TRUE(near_relative(last.strain_viscoelastic,
                                (1.0 - p.alpha) * saturation * loaded_fraction *
                                    std::exp(-p.lambda_unload * hour),
                                1e-12));
      EXPECT_EQ(last.strain_elastic, 0.0);
    }
  }
}

TEST(StripCreep, SampleRowsFollowEq56DuringLoading) {
  const DirectionalMaterial m = cotton_warp();
  const CreepParameters& p = m.creep;
  const TensionHistory history = TensionHistory::creep_recovery(tension, hour, hour);
  const auto rows = simulate_strip(m, history, log_sample_times(history, 0.01, 10));
  int checked = 0;
  for (const auto& row : rows) {
    if (row.time <= 0.0 || row.time >= hour) continue;
    ++checked;
    EXPECT_EQ(row.tension, tension);
    EXPECT_TRUE(near_relative(row.strain_viscoelastic + row.strain_permanent,
                              tension / p.creep_modulus * -std::expm1(-p.lambda_load * row.time),
                              1e-11))
        << row.time;
  }
  EXPECT_GT(checked, 50);
}

TEST(StripCreep, LogAndUniformSamplingAgreeAtSharedTimes) {
  const DirectionalMaterial m = cotton_warp();
  const TensionHistory history = TensionHistory::creep_recovery(tension, hour, hour);
  // One per decade from 1 s: 1, 10, 100, 1000 s after each change; the
  // uniform grid of 1 s contains them all.
  const auto log_rows = simulate_strip(m, history, log_sample_times(history, 1.0, 1));
  const auto uniform_rows = simulate_strip(m, history, uniform_sample_times(history, 1.0));
  std::map<double, const StripState*> uniform_by_time;
  for (const auto& row : uniform_rows)
    uniform_by_time.emplace(row.time, &row); // first of a jump
  int shared = 0;
  for (std::size_t i = 0; i < log_rows.size(); ++i) {
    const StripState& row = log_rows[i];
    // Compare the first row at each time (the one before a jump) ...
    if (i > 0 && log_rows[i - 1].time == row.time) continue;
    const auto it = uniform_by_time.find(row.time);
    if (it == uniform_by_time.end()) continue;
    ++shared;
    const StripState& other = *it->second;
    SCOPED_TRACE(row.time);
    EXPECT_EQ(row.tension, other.tension);
    for (const auto& [a, b] : {std::pair{row.strain_total, other.strain_total},
                               std::pair{row.strain_elastic, other.strain_elastic},
                               std::pair{row.strain_viscoelastic, other.strain_viscoelastic},
                               std::pair{row.strain_permanent, other.strain_permanent}}) {
      EXPECT_NEAR(a, b, 1e-13 * std::abs(b));
    }
  }
  // 0 and 3600 (breakpoints), 1, 10, 100, 1000 and 3601, 3610, 3700, 4600, 7200.
  EXPECT_GE(shared, 11);
  // ... and the last rows.
  EXPECT_NEAR(log_rows.back().strain_total, uniform_rows.back().strain_total,
              1e-13 * uniform_rows.back().strain_total);
}

// --- sample times ---------------------------------------------------------------------------

TEST(StripSampleTimes, UniformTimesEveryIntervalToTheEnd) {
  const TensionHistory history = TensionHistory::creep_recovery(tension, 100.0, 50.0);
  const auto times = uniform_sample_times(history, 10.0);
  ASSERT_EQ(times.size(), 15u);
  for (std::size_t k = 0; k < times.size(); ++k)
    EXPECT_EQ(times[k], 10.0 * double(k + 1));
}

TEST(StripSampleTimes, LogTimesPerDecadeAfterEachChange) {
  const TensionHistory history = TensionHistory::creep_recovery(tension, 1000.0, 1000.0);
  const auto times = log_sample_times(history, 1.0, 2);
  // After the load at 0 and the unload at 1000 s: 1, 3.16, 10, 31.6, 100,
  // 316 s later, at least up to the next change.
  for (const double start : {0.0, 1000.0}) {
    for (int k = 0; k < 6; ++k) {
      const double expected = start + std::pow(10.0, k / 2.0);
      const auto hit = std::find_if(times.begin(), times.end(), [&](double t) {
        return std::abs(t - expected) <= 1e-12 * expected;
      });
      EXPECT_NE(hit, times.end()) << "no sample at " << expected;
    }
  }
  for (const double t : times) {
    EXPECT_GT(t, history.start_time());
    EXPECT_LE(t, history.end_time());
  }
}

TEST(StripSampleTimes, LogTimesStrictlyIncrease) {
  // A load jump at the start of the history must not give every sample twice.
  const TensionHistory history = TensionHistory::creep_recovery(tension, hour, hour);
  const auto times = log_sample_times(history, 0.1, 10);
  for (std::size_t i = 1; i < times.size(); ++i) {
    EXPECT_LT(times[i - 1], times[i]) << "sample " << i;
    if (HasFailure()) break;
  }
}

TEST(StripSampleTimes, OnlyJumpsRepeatATimeInTheRows) {
  const TensionHistory history = TensionHistory::creep_recovery(tension, hour, hour);
  const auto rows = simulate_strip(cotton_warp(), history, log_sample_times(history, 0.1, 10));
  int repeats = 0;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    ASSERT_LE(rows[i - 1].time, rows[i].time);
    if (rows[i - 1].time == rows[i].time) {
      ++repeats;
      EXPECT_NE(rows[i - 1].tension, rows[i].tension) << "repeated row at t = " << rows[i].time;
    }
  }
  EXPECT_EQ(repeats, 2); // the load jump at 0 and the unload jump at 3600 s
}

// --- general histories ------------------------------------------------------------------------

TEST(StripCreep, RampHistoryRowsMatchCreepLaw) {
  const DirectionalMaterial m = cotton_warp();
  const TensionHistory history = TensionHistory::from_csv(data("history_ramp.csv"));
  const auto rows = simulate_strip(m, history, uniform_sample_times(history, 30.0));
  // Rows inside the ramp 60..180 s carry the interpolated tension.
  for (const auto& row : rows) {
    if (row.time > 60.0 && row.time < 180.0) {
      EXPECT_NEAR(row.tension, 1000.0 + 1500.0 * (row.time - 60.0) / 120.0, 1e-9) << row.time;
    }
  }
  // The last row is the creep law over the pieces.
  CreepState s = advance(m.creep, CreepState{}, 1000.0, 1000.0, 60.0);
  s = advance(m.creep, s, 1000.0, 2500.0, 120.0);
  s = advance(m.creep, s, 500.0, 500.0, 420.0);
  const StripState& last = rows.back();
  EXPECT_EQ(last.time, 600.0);
  EXPECT_TRUE(near_relative(last.strain_viscoelastic, s.viscoelastic, 1e-12));
  EXPECT_TRUE(near_relative(last.strain_permanent, s.permanent, 1e-12));
  EXPECT_TRUE(near_relative(
      last.strain_total, (1.0 + 500.0 / m.elastic.initial_modulus()) * (1.0 + s.nonelastic()) - 1.0,
      1e-12));
  // Both sides of the jump at 180 s.
  const auto at_jump = rows_at(rows, 180.0);
  ASSERT_EQ(at_jump.size(), 2u);
  EXPECT_EQ(at_jump[0]->tension, 2500.0);
  EXPECT_EQ(at_jump[1]->tension, 500.0);
}

// --- tension histories ------------------------------------------------------------------------

TEST(TensionHistoryInput, CreepRecoveryBreakpoints) {
  const TensionHistory history = TensionHistory::creep_recovery(tension, hour, 2.0 * hour);
  const auto& points = history.points();
  ASSERT_EQ(points.size(), 5u);
  const std::vector<std::pair<double, double>> expected{
      {0.0, 0.0}, {0.0, tension}, {hour, tension}, {hour, 0.0}, {3.0 * hour, 0.0}};
  for (std::size_t i = 0; i < points.size(); ++i) {
    EXPECT_EQ(points[i].time, expected[i].first);
    EXPECT_EQ(points[i].tension, expected[i].second);
  }
  EXPECT_EQ(history.start_time(), 0.0);
  EXPECT_EQ(history.end_time(), 3.0 * hour);
  EXPECT_EQ(TensionHistory::creep_recovery(tension, hour, 0.0).points().size(), 4u);
}

TEST(TensionHistoryInput, CreepRecoveryRejectsBadArguments) {
  EXPECT_THROW(TensionHistory::creep_recovery(0.0, hour, hour), InputError);
  EXPECT_THROW(TensionHistory::creep_recovery(-10.0, hour, hour), InputError);
  EXPECT_THROW(TensionHistory::creep_recovery(std::nan(""), hour, hour), InputError);
  EXPECT_THROW(TensionHistory::creep_recovery(tension, 0.0, hour), InputError);
  EXPECT_THROW(TensionHistory::creep_recovery(tension, hour, -1.0), InputError);
  EXPECT_THROW(TensionHistory::creep_recovery(tension, HUGE_VAL, hour), InputError);
}

TEST(TensionHistoryInput, ConstructorRejectsBadPoints) {
  EXPECT_THROW(TensionHistory({{0.0, 1.0}}), InputError);
  EXPECT_THROW(TensionHistory({{0.0, 1.0}, {1.0, -1.0}}), InputError);
  EXPECT_THROW(TensionHistory({{0.0, 1.0}, {2.0, 1.0}, {1.0, 1.0}}), InputError);
  EXPECT_THROW(TensionHistory({{0.0, 1.0}, {0.0, 2.0}}), InputError);
  EXPECT_THROW(TensionHistory({{0.0, 1.0}, {std::nan(""), 2.0}}), InputError);
}

TEST(TensionHistoryInput, FromCsvReadsBreakpointsAndJumps) {
  const TensionHistory history = TensionHistory::from_csv(data("history_ramp.csv"));
  const auto& points = history.points();
  ASSERT_EQ(points.size(), 6u);
  EXPECT_EQ(points[1].time, 0.0);
  EXPECT_EQ(points[1].tension, 1000.0);
  EXPECT_EQ(points[3].time, 180.0);
  EXPECT_EQ(points[3].tension, 2500.0);
  EXPECT_EQ(points[4].tension, 500.0);
  EXPECT_EQ(history.end_time(), 600.0);
  const TensionHistory short_names = TensionHistory::from_csv(data("history_short_names.csv"));
  EXPECT_EQ(short_names.points().back().tension, 100.0);
}

TEST(TensionHistoryInput, FromCsvNegativeTensionGivesLine) {
  const std::string path = data("history_negative.csv");
  const std::string what = input_error([&] { TensionHistory::from_csv(path); });
  EXPECT_EQ(what.rfind(path + ":6: ", 0), 0u) << what;
  EXPECT_TRUE(contains(what, "-5"));
}

TEST(TensionHistoryInput, FromCsvDecreasingTimeGivesLine) {
  const std::string path = data("history_decreasing.csv");
  const std::string what = input_error([&] { TensionHistory::from_csv(path); });
  EXPECT_EQ(what.rfind(path + ":5: ", 0), 0u) << what;
  EXPECT_TRUE(contains(what, "9 after 10"));
}

TEST(TensionHistoryInput, FromCsvMissingTensionColumn) {
  const std::string path = data("history_no_tension.csv");
  const std::string what = input_error([&] { TensionHistory::from_csv(path); });
  EXPECT_TRUE(contains(what, path));
  EXPECT_TRUE(contains(what, "tension_n_per_m"));
}

} // namespace
} // namespace sartor
