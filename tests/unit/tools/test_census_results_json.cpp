// mmh-bench: the census's stops in results.json (`stop_events`) and back, also from a record
// written before a stop's hold and lowest speed were measured.
#include <gtest/gtest.h>

#include <cmath>

#include "flight_spec.hpp"

namespace {

mmh::bench::FlightResult withOneStop(double held_s, double lowest_speed_mps) {
  mmh::bench::FlightResult r;
  mmh::StopRecord s;
  s.time_s = 2.81;
  s.trigger = "retry";
  s.cause = "no usable answer + danger ahead";
  s.held_s = held_s;
  s.lowest_speed_mps = lowest_speed_mps;
  r.census.stops.push_back(s);
  return r;
}

TEST(CensusResultsJson, AStopsHoldAndLowestSpeedGoThereAndBack) {
  const nlohmann::json j = mmh::bench::toJson(withOneStop(0.33, 2.69));
  const nlohmann::json& event = j.at("stop_events").at(0);
  EXPECT_DOUBLE_EQ(event.at("held_s").get<double>(), 0.33);
  EXPECT_DOUBLE_EQ(event.at("lowest_speed_mps").get<double>(), 2.69);
  const mmh::StopRecord back = mmh::bench::fromJson(j).census.stops.at(0);
  EXPECT_DOUBLE_EQ(back.held_s, 0.33);
  EXPECT_DOUBLE_EQ(back.lowest_speed_mps, 2.69);
  EXPECT_FALSE(back.reachedRest());
  EXPECT_TRUE(mmh::bench::fromJson(mmh::bench::toJson(withOneStop(2.0, 0.0)))
                  .census.stops.at(0)
                  .reachedRest());
}

TEST(CensusResultsJson, AnOlderRecordWithoutThemReadsAsUnknownNotAtRest) {
  nlohmann::json old = mmh::bench::toJson(withOneStop(0.33, 0.0));
  old.at("stop_events").at(0).erase("held_s");
  old.at("stop_events").at(0).erase("lowest_speed_mps");
  const mmh::StopRecord back = mmh::bench::fromJson(old).census.stops.at(0);
  EXPECT_TRUE(std::isnan(back.held_s));
  EXPECT_TRUE(std::isnan(back.lowest_speed_mps));
  EXPECT_FALSE(back.reachedRest());
}

}  // namespace
