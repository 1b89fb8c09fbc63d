// diagnostics.csv of an output folder (one row per step, docs/outputs.md) as columns of numbers.
#pragma once
#include <QString>
#include <QStringList>
#include <vector>

namespace talus::gui {

struct DiagnosticsTable {
  QStringList names;                        ///< the header's column names
  std::vector<std::vector<double>> columns;  ///< parallel to names, one value per row

  std::size_t rows() const { return columns.empty() ? 0 : columns.front().size(); }
  /// The column called name, or nullptr.
  const std::vector<double>* column(const QString& name) const;

  /// Reads the file; throws std::runtime_error naming it when it cannot be read or has no header.
  /// A row with another number of cells than the header (a cut-short last line) ends the table.
  static DiagnosticsTable read(const QString& path);
};

}  // namespace talus::gui
