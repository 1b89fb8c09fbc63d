// Helpers of the GUI tests: a scratch copy of the example run-file, waiting on the event loop, and
// image statistics for the rendered-frame checks.
#pragma once
#include <QFileDialog>
#include <QImage>
#include <QString>
#include <QWidget>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <string>

namespace talus::gui {
class MainWindow;
}

namespace talus::guitest {

/// A fresh folder under the system temp folder (removed at the next call with the same name).
std::filesystem::path scratchDir(const std::string& name);
/// Writes the example scene's run-file into `dir`, maps read from data/kot_dambreak, outputs into
/// dir/out, with extra "Key=Value" lines replacing those keys. Returns its path.
std::string writeExampleRunFile(const std::filesystem::path& dir, const std::string& extraLines = "");
/// Runs the example scene for 0.05 s with a series frame every report into dir/out (through the
/// engine, as `talus run`); returns dir/out.
std::filesystem::path writeExampleResults(const std::filesystem::path& dir, const std::string& extraLines = "");
/// The whole content of a text file ("" when it cannot be read).
std::string readText(const std::filesystem::path& file);
/// The last row of a diagnostics.csv, by column name (empty when the file has no data row).
std::map<std::string, double> lastDiagnosticsRow(const std::filesystem::path& csv);
/// Processes events until `done` is true or `seconds` pass; returns done().
bool waitFor(const std::function<bool()>& done, double seconds);
/// Calls `act` with the next modal dialog that opens within `seconds` (from the event loop the
/// dialog runs), then stops watching.
void onNextModal(const std::function<void(QWidget*)>& act, double seconds = 30);
/// Answers the next message box that opens (within `seconds`) with `button`; the returned string
/// receives the box's text once it was answered (empty while none was).
std::shared_ptr<QString> answerNextMessageBox(int button, double seconds = 30);
/// Chooses `file` in a file dialog and accepts it: its folder, and its name typed into the dialog's
/// file-name field (QFileDialog::selectFile leaves that field alone while it has the keyboard focus,
/// which it gets as the dialog shows, sooner or later: in ctest's build folder the dialog kept its
/// default name).
void chooseInFileDialog(QFileDialog* dialog, const std::filesystem::path& file);
/// Shows `w` at width x height with the example run-file (writeExampleRunFile) opened from `dir`,
/// drawn. Use with ASSERT_NO_FATAL_FAILURE.
void showExampleWindow(talus::gui::MainWindow& w, const std::filesystem::path& dir, int width = 1200, int height = 800);
/// Number of distinct colours of an image.
int distinctColours(const QImage& image);
/// Standard deviation of the grey value (0..255) over the image.
double greyDeviation(const QImage& image);

}  // namespace talus::guitest
