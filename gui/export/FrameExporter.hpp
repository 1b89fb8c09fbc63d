// Exports what the viewer shows: one screenshot (PNG), or a numbered frame sequence (frame_00000.png,
// ...) for animations, one frame per new snapshot while recording.
#pragma once
#include <QString>

namespace talus::gui {

class ViewerWidget;

class FrameExporter {
 public:
  /// Saves the viewer's current image as PNG. Returns "" or the problem.
  static QString saveScreenshot(ViewerWidget& viewer, const QString& path);

  /// Starts writing frames into `folder` (created if missing). Returns "" or the problem.
  QString startSequence(const QString& folder);
  void stopSequence() { recording_ = false; }
  bool isRecording() const { return recording_; }
  /// While recording: writes the viewer's image as the next frame. Returns "" or the problem
  /// (which also stops the recording).
  QString captureFrame(ViewerWidget& viewer);
  int framesWritten() const { return frames_; }
  const QString& folder() const { return folder_; }

 private:
  bool recording_ = false;
  QString folder_;
  int frames_ = 0;
};

}  // namespace talus::gui
