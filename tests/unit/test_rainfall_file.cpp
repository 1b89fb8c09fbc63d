// The OpenLISEM rainfall file (io/RainfallFile.hpp): files written here in the format that
// OpenLISEM Hazard's TimeSeries::LoadFromFile reads (lisem/model/timeseries.h lines 39-135: a
// description line, the column count, one name per column, then records of a time in minutes and
// intensities in mm/h), parsed to the right records; the step function and its integral; malformed
// files refused naming the file and the line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include "io/RainfallFile.hpp"
#include "support/ExpectInputError.hpp"

namespace fs = std::filesystem;
using talus::io::Rainfall;
using talus::io::readRainfallFile;
using talus::test::expectInputError;

namespace {

std::string writeFile(const std::string& name, const std::string& text) {
  const fs::path p = fs::temp_directory_path() / ("talus_rain_" + std::to_string(::getpid()) + "_" + name);
  std::ofstream(p) << text;
  return p.string();
}

}  // namespace

TEST(RainfallFile, ReadsOneStationInMinutesAndMmPerHour) {
  // Empty lines and Windows line ends are skipped as OpenLISEM skips them.
  const std::string f = writeFile("one.txt",
                                  "RUU CSF timeseries\r\n2\r\ntime\r\n\r\nstation 1\r\n0 0\r\n5 30.5\r\n"
                                  "  12.5\t60 \r\n30 0\r\n");
  const Rainfall r = readRainfallFile(f);
  ASSERT_EQ(r.times().size(), 4u);
  EXPECT_EQ(r.times()[1], 300.0);
  EXPECT_EQ(r.times()[2], 750.0);
  EXPECT_EQ(r.intensities()[1], 30.5);
  EXPECT_EQ(r.intensities()[2], 60.0);
  // Step-wise constant: each record from its time to the next.
  EXPECT_EQ(r.intensity(299.0), 0.0);
  EXPECT_EQ(r.intensity(300.0), 30.5);
  EXPECT_EQ(r.intensity(1000.0), 60.0);
  EXPECT_EQ(r.intensity(1e6), 0.0);
  // Depth over [200, 800] s: 100 s at 0, 450 s at 30.5 mm/h and 50 s at 60 mm/h, in metres.
  const double mm = (450.0 * 30.5 + 50.0 * 60.0) / 3600.0;
  EXPECT_NEAR(r.depth(200.0, 800.0), mm / 1000.0, 1e-18);
  // Additive over adjacent intervals (the run's steps add up to the series' total).
  EXPECT_NEAR(r.depth(0, 400) + r.depth(400, 2000), r.depth(0, 2000), 1e-18);
  fs::remove(f);
}

TEST(RainfallFile, ReadsOpenLisem6DayMinuteTimes) {
  // openLISEM 6 (lisRainfall.cpp) has the same layout and may stamp records as day:minute.
  const std::string f = writeFile("daymin.txt", "rain\n2\ntime\nstation 1\n001:0000 0\n001:0030 12\n002:0000 0\n");
  const Rainfall r = readRainfallFile(f);
  ASSERT_EQ(r.times().size(), 3u);
  EXPECT_EQ(r.times()[1] - r.times()[0], 1800.0);
  EXPECT_EQ(r.times()[2] - r.times()[0], 86400.0);
  fs::remove(f);
}

TEST(RainfallFile, FirstRecordHoldsBeforeAndLastAfter) {
  // OpenLISEM's fillValues: the first record's interval starts at -infinity, the last never ends.
  const Rainfall r({600.0, 1200.0}, {10.0, 20.0});
  EXPECT_EQ(r.intensity(0.0), 10.0);
  EXPECT_EQ(r.intensity(5000.0), 20.0);
  EXPECT_NEAR(r.depth(0, 1800), (1200.0 * 10 + 600.0 * 20) / 3600.0 / 1000.0, 1e-18);
  const Rainfall u = Rainfall::uniform(36.0);
  EXPECT_NEAR(u.depth(10.0, 110.0), 1e-3, 1e-18);  // 36 mm/h = 0.01 mm/s
  EXPECT_EQ(Rainfall().depth(0, 100), 0.0);
}

TEST(RainfallFile, MalformedFilesAreRefusedNamingFileAndLine) {
  const std::string missing = (fs::temp_directory_path() / "talus_no_such_rain.txt").string();
  expectInputError([&] { readRainfallFile(missing); }, {"rainfall file '" + missing + "' cannot be opened"});
  const std::string count = writeFile("count.txt", "rain\ntwo\ntime\nP1\n0 1\n");
  expectInputError([&] { readRainfallFile(count); }, {count + "' line 2", "expected the number of columns"});
  const std::string stations = writeFile("stations.txt", "rain\n3\ntime\nP1\nP2\n0 1 2\n");
  expectInputError([&] { readRainfallFile(stations); }, {stations + "' line 2", "2 stations", "one station"});
  const std::string time = writeFile("time.txt", "rain\n2\ntime\nP1\n0 1\n1:2:3:4 1\n");
  expectInputError([&] { readRainfallFile(time); }, {time + "' line 6", "neither minutes nor day:minute"});
  const std::string bad = writeFile("bad.txt", "rain\n2\ntime\nP1\n0 1\n\n10 x1\n");
  expectInputError([&] { readRainfallFile(bad); }, {bad + "' line 7", "rainfall maps ('x1') are not supported"});
  const std::string nan = writeFile("nan.txt", "rain\n2\ntime\nP1\n0 1\n10 1,5\n");
  expectInputError([&] { readRainfallFile(nan); }, {nan + "' line 6", "intensity '1,5' is not a number"});
  const std::string order = writeFile("order.txt", "rain\n2\ntime\nP1\n0 1\n10 2\n10 3\n");
  expectInputError([&] { readRainfallFile(order); }, {order + "' line 7", "record times must increase"});
  const std::string negative = writeFile("neg.txt", "rain\n2\ntime\nP1\n0 -1\n");
  expectInputError([&] { readRainfallFile(negative); }, {negative + "' line 5", "negative intensity"});
  const std::string short_ = writeFile("short.txt", "rain\n2\ntime\nP1\n0\n");
  expectInputError([&] { readRainfallFile(short_); }, {short_ + "' line 5", "found 1 values"});
  const std::string empty = writeFile("empty.txt", "rain\n2\ntime\nP1\n");
  expectInputError([&] { readRainfallFile(empty); }, {"has no records"});
  for (const std::string& f : {time, count, stations, bad, nan, order, negative, short_, empty}) fs::remove(f);
}
