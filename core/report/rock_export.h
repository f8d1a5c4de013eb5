// `ipd export rocks`: one row per rock pair (per model and domain pair) so the numbers behind every IPD can
// be analysed elsewhere (pandas reads the CSV and the JSON as they are). The mean of `diff` over a cell's
// paired rows is that cell's IPD.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "core/ipd/ipd.h"
#include "core/report/provenance.h"

namespace ipd {

struct RockRow {
  std::string model, trained_on, a, b, scene;
  std::string cls;                 // the rocks' class: its name, or its number where no file names it
  int index_a = -1, index_b = -1;  // 0-based rock indices; -1: no rock on that side (an unpaired row)
  double perf_a = std::numeric_limits<double>::quiet_NaN(), perf_b = std::numeric_limits<double>::quiet_NaN();
  double diff = std::numeric_limits<double>::quiet_NaN();  // |perf_a - perf_b|, NaN on unpaired rows
  Box box_a, box_b;  // normalised centre and size, as in the label files (with the outline: mask_area_a/_b columns)
  double residual_px = std::numeric_limits<double>::quiet_NaN();  // |affine(centre a) - centre b| in B's pixels
  std::string source;     // "auto" (registration) or "hand" (pairs/<A>__<B>/<stem>.json)
  bool excluded = false;  // an unpaired row's rock left out of the IPD on purpose (its pairs file says so)
};

struct RockExportOptions {
  bool unpaired = false;  // also a row for every rock left unpaired (or excluded), partner fields empty

  // Always empty: a flag alone has no value to reject; kept so every options struct is checked alike.
  std::string validate() const { return {}; }
};

// Rows in a stable order: cells as in the table (models × domain pairs), scenes by stem, counted pairs in
// pairing order, then unpaired A rocks, then unpaired B rocks. Cells without predictions give no rows.
// Residuals use the scene's registration affine, or for hand-paired scenes a least-squares affine on the
// hand pairs (needs 3); they are NaN when the picture size is unknown.
std::vector<RockRow> rock_rows(const StudyLabels& labels, const CrossTable& table, const RockExportOptions& options);

// Header + one line per row; NaN -> empty. With `provenance`, its columns (provenance_csv_fields) end
// every row, so a reader of the rows alone can tell which label files and hand edits they come from.
std::string rock_rows_csv(const std::vector<RockRow>& rows, const Provenance* provenance = nullptr);
// An array of records (what pandas.read_json reads); NaN -> null; with `provenance`, its scalar fields in
// every record, as in the CSV.
std::string rock_rows_json(const std::vector<RockRow>& rows, const Provenance* provenance = nullptr);

}  // namespace ipd
