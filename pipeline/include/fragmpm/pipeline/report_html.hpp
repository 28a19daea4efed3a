#pragma once
// report.html: one static page (no scripts, no network, figures by relative path) that says what
// a run or study produced and whether to trust it: a summary table, the trust checks, and the
// figures in sections, each with a one-line caption.
#include <string>
#include <vector>

namespace fragmpm::pipeline {

struct ReportRow {
  std::string label, value;
  /// A check that failed or needs a look: the row is marked, and the page's header says so.
  bool attention = false;
  /// False for a row of the checks table that has no limit (a value to read, such as the largest
  /// stress): it shows "info" instead of a verdict and is not counted among the checks.
  bool limited = true;
};

struct ReportFigure {
  std::string path;  ///< relative to the page's folder, '/' separated
  std::string caption;
};

struct ReportSection {
  std::string title;
  std::vector<ReportFigure> figures;
};

struct Report {
  std::string title;
  std::string subtitle;  ///< one line under the title (what was run, when, where)
  std::string summary_title = "The run";
  std::vector<ReportRow> summary;  ///< what the run (or study) is
  std::vector<ReportRow> checks;   ///< what says whether to trust it
  std::vector<ReportSection> sections;
  std::string details;  ///< preformatted text at the end (the summary.txt), may be empty
};

/// The page as HTML5 text; every text field is escaped.
std::string report_html(const Report& report);

/// Writes the page to `path`; throws PipelineError naming the file when it cannot.
void write_report(const Report& report, const std::string& path);

/// The caption of a figure that FragMPM writes, from its file name (`fragments/cdf_roundness.png`,
/// `figures/energy.png`, …); empty for a file it does not know.
std::string figure_caption(const std::string& relative_path);

}  // namespace fragmpm::pipeline
