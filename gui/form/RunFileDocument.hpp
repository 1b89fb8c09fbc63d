// A run-file as the user edits it: its lines kept as written (comments, order, section headers,
// unknown keys), with the values of declared keys readable and replaceable, so that saving changes
// only the edited values. Validation is RunConfig's job (form/RunValidation).
#pragma once
#include <string>
#include <vector>

#include "io/KeyRegistry.hpp"

namespace talus::gui {

class RunFileDocument {
 public:
  /// An empty document (a new run-file) for `keys`.
  explicit RunFileDocument(const io::KeyRegistry& keys);
  /// Reads a run-file. Throws talus::InputError when it cannot be read.
  static RunFileDocument load(const std::string& path, const io::KeyRegistry& keys);
  /// A document of run-file text that lives at `path` (relative paths resolve against its folder).
  static RunFileDocument fromText(const std::string& text, const std::string& path, const io::KeyRegistry& keys);

  /// The value text of a declared key (after the first '=', multiplier included) as the file gives
  /// it, or the key's default when the file does not give it.
  std::string value(const std::string& key) const;
  /// True when the file has a line for the key.
  bool isGiven(const std::string& key) const;
  /// Sets the value text of a declared key: its line is rewritten, or a line is added to the key's
  /// section (a value equal to the default of a key the file does not give adds nothing).
  void setValue(const std::string& key, const std::string& value);

  /// The run-file text.
  std::string text() const;
  /// Writes text() to `path` (which becomes the document's path). Throws talus::InputError.
  void save(const std::string& path);

  const std::string& path() const { return path_; }
  /// Absolute folder relative paths resolve against (the run-file's folder, else the working folder).
  std::string baseDir() const;
  bool isModified() const { return modified_; }
  const io::KeyRegistry& keys() const { return *keys_; }

 private:
  struct Line {
    std::string text;  ///< the line as written (rebuilt when the value changes)
    int key = -1;      ///< index of the declared key it sets, or -1 (comment, header, unknown)
    std::string name;  ///< the key name as written
    std::string value; ///< value text after the first '='
  };
  int findLine(int key) const;

  const io::KeyRegistry* keys_;
  std::vector<Line> lines_;
  std::string path_;
  bool modified_ = false;
};

}  // namespace talus::gui
