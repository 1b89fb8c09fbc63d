// Save-as into another folder: a run-file's relative input paths resolve against its own folder
// (the Map Directory, the TimeInput Directory, and the maps when no Map Directory is given), so a
// copy saved elsewhere would look for its maps in the wrong place. This rewrites them so that the
// copy names the same files.
#pragma once
#include <string>

#include "form/RunFileDocument.hpp"

namespace talus::gui {

/// Rewrites the relative input paths of `doc` (whose path is still the old one) so that they name
/// the same folders and files from `newDir`: the given input folders (every folder key but the
/// Output Directory, which a copy keeps next to itself) and, without a Map Directory, the map files
/// that exist, each relative to newDir (absolute when no relative path leads there). Absolute
/// paths, uniform values (numbers) and quoted values stay as written. Nothing changes when newDir
/// is the document's folder.
void rebaseInputPaths(RunFileDocument& doc, const std::string& newDir);

}  // namespace talus::gui
