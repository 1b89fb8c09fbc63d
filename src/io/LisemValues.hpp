// Readings of values as OpenLISEM Hazard users write them, for RunConfig: decimal commas
// (`Manning=0,05`), day:minute times (`End Time=001:0030`), Windows drive paths
// (`Map Directory=C:/lisemcourse/maps/`) and file names whose case differs from the file's.
// Each returns what it found so that the caller can say so in a note or an error.
#pragma once
#include <string>

namespace talus::io {

/// Outcome of reading a decimal-comma number.
enum class DecimalComma {
  None,       ///< the text is not digits,digits (a plain number, a list, a file name, ...)
  Read,       ///< read: `dotted` holds the text with the comma as a decimal point
  Ambiguous,  ///< 1,000-like: a decimal comma (1.0) or a thousands separator (1000)
};

/// Reads "0,05", "-2,5" or "1,5e-3": digits, one comma, digits (an optional sign and exponent).
/// Text with a leading digit other than 0, one to three digits before the comma and exactly
/// three after ("1,000", "12,500") is Ambiguous and not read: the value would be a guess.
DecimalComma readDecimalComma(const std::string& text, std::string& dotted);

/// Reads OpenLISEM's day:minute time "ddd:mmmm" (openLISEM 6: day number, then the minute of the
/// day; lisRainfall.cpp getTimefromString) or "ddd:hh:mm" as minutes since day 0:
/// day * 1440 + hour * 60 + minute. False when the text is not of that form.
bool readDayMinute(const std::string& text, double& minutes);

/// True for a Windows drive path: a letter, ':' and a slash or backslash ("C:/data", "d:\\maps").
bool isWindowsDrivePath(const std::string& text);

/// The last non-empty component of a path with '/' or '\\' separators ("maps" of "C:/x/maps/").
std::string lastPathComponent(const std::string& text);

/// The existing file in path's folder whose name equals path's file name but for letter case,
/// or "" when there is none or more than one (DEM.MAP for dem.map).
std::string findIgnoringCase(const std::string& path);

}  // namespace talus::io
