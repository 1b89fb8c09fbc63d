// Times of a run in seconds from the run-file's minutes (OpenLISEM Hazard's unit for Start Time,
// End Time and the checkpoint intervals), landing on the report times they are meant to hit.
#pragma once

namespace talus::sim {

/// Seconds of a span given in minutes, snapped onto the report grid: when 60 * minutes lies within
/// a relative 1e-6 of a whole number n of report intervals, the result is n * interval exactly.
/// Decimal minutes cannot write most whole seconds (5 s is 0.0833... min); users write 6 or 7
/// digits, whose round-off (up to 5e-7 relative at 6 digits) would otherwise end a run a few
/// microseconds before its last report, which is then never written. 1e-6 is far below any span a
/// user means to distinguish from a report time (a microsecond in a second of simulated time).
double minutesOnReportGrid(double minutes, double reportInterval);

}  // namespace talus::sim
