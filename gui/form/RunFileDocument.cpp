#include "form/RunFileDocument.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/Error.hpp"

namespace talus::gui {

namespace fs = std::filesystem;

namespace {

std::string trim(const std::string& s) {
  const std::size_t a = s.find_first_not_of(" \t\r\n");
  if (a == std::string::npos) return "";
  const std::size_t b = s.find_last_not_of(" \t\r\n");
  return s.substr(a, b - a + 1);
}

}  // namespace

RunFileDocument::RunFileDocument(const io::KeyRegistry& keys) : keys_(&keys) {
  lines_.push_back({"[Talus run file]", -1, "", ""});
}

RunFileDocument RunFileDocument::load(const std::string& path, const io::KeyRegistry& keys) {
  // A folder opens as an empty stream here: say so instead of listing every key as missing.
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw InputError("cannot read run-file '" + path + "': it is a folder");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("cannot read run-file '" + path + "': " + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  return fromText(text.str(), path, keys);
}

RunFileDocument RunFileDocument::fromText(const std::string& text, const std::string& path,
                                          const io::KeyRegistry& keys) {
  RunFileDocument doc(keys);
  doc.lines_.clear();
  doc.path_ = path;
  std::istringstream in(text);
  std::string raw;
  while (std::getline(in, raw)) {
    if (!raw.empty() && raw.back() == '\r') raw.pop_back();
    Line line{raw, -1, "", ""};
    const std::string t = trim(raw);
    const std::size_t eq = t.find('=');
    if (!t.empty() && t[0] != '#' && t[0] != ';' && t[0] != '[' && eq != std::string::npos) {
      line.name = trim(t.substr(0, eq));
      line.value = trim(t.substr(eq + 1));
      line.key = keys.indexOf(line.name);
    }
    doc.lines_.push_back(std::move(line));
  }
  return doc;
}

int RunFileDocument::findLine(int key) const {
  for (std::size_t k = 0; k < lines_.size(); ++k)
    if (lines_[k].key == key) return static_cast<int>(k);
  return -1;
}

std::string RunFileDocument::value(const std::string& key) const {
  const int idx = keys_->indexOf(key);
  if (idx < 0) return "";
  const int line = findLine(idx);
  return line >= 0 ? lines_[static_cast<std::size_t>(line)].value : keys_->keys()[static_cast<std::size_t>(idx)].defaultValue;
}

bool RunFileDocument::isGiven(const std::string& key) const {
  const int idx = keys_->indexOf(key);
  return idx >= 0 && findLine(idx) >= 0;
}

void RunFileDocument::setValue(const std::string& key, const std::string& value) {
  const int idx = keys_->indexOf(key);
  if (idx < 0) return;
  const io::KeySpec& spec = keys_->keys()[static_cast<std::size_t>(idx)];
  const std::string v = trim(value);
  const int at = findLine(idx);
  if (at >= 0) {
    Line& line = lines_[static_cast<std::size_t>(at)];
    if (line.value == v) return;
    line.value = v;
    line.text = line.name + "=" + v;
    modified_ = true;
    return;
  }
  if (v == spec.defaultValue) return;
  // Insert after the last line of the key's [Section], or append the section.
  const std::string header = io::normalizeKeyName("[" + spec.section + "]");
  std::size_t insertAt = lines_.size();
  bool inSection = false, found = false;
  for (std::size_t k = 0; k < lines_.size(); ++k) {
    const std::string t = trim(lines_[k].text);
    if (!t.empty() && t[0] == '[') {
      if (inSection) {
        insertAt = k;
        break;
      }
      inSection = io::normalizeKeyName(t) == header;
      found = found || inSection;
    }
  }
  if (!found) {
    lines_.push_back({"[" + spec.section + "]", -1, "", ""});
    insertAt = lines_.size();
  }
  // Keep blank lines that end the section after the new line.
  while (insertAt > 0 && trim(lines_[insertAt - 1].text).empty()) --insertAt;
  lines_.insert(lines_.begin() + static_cast<std::ptrdiff_t>(insertAt), Line{spec.name + "=" + v, idx, spec.name, v});
  modified_ = true;
}

std::string RunFileDocument::text() const {
  std::string out;
  for (const Line& l : lines_) out += l.text + "\n";
  return out;
}

void RunFileDocument::save(const std::string& path) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError("cannot write run-file '" + path + "': " + std::strerror(errno));
    out << text();
    if (!out.flush()) throw InputError("cannot write run-file '" + path + "': write error");
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) throw InputError("cannot write run-file '" + path + "': " + ec.message());
  path_ = path;
  modified_ = false;
}

std::string RunFileDocument::baseDir() const {
  if (path_.empty()) return fs::current_path().string();
  return fs::absolute(fs::path(path_)).parent_path().string();
}

}  // namespace talus::gui
