// report.html (see report_html.hpp). The page is plain HTML5 with one inline style sheet: it opens
// from a copied folder, an e-mail attachment or a file browser without a server or a network.
#include "fragmpm/pipeline/report_html.hpp"

#include <fmt/format.h>

#include <fstream>
#include <regex>

#include "fragmpm/mpm/xdmf.hpp"
#include "fragmpm/pipeline/pipeline_job.hpp"

namespace fragmpm::pipeline {

namespace {

/// Element content and attribute values: the run file's XML escaping serves HTML as well.
std::string escape(const std::string& text) {
  return mpm::xml_escape(text);
}

/// A relative path as an attribute value: each byte outside the unreserved set percent-encoded,
/// so spaces or '#' in file names still resolve.
std::string url_path(const std::string& path) {
  std::string out;
  for (unsigned char c : path) {
    if (std::isalnum(c) || c == '/' || c == '.' || c == '_' || c == '-')
      out += static_cast<char>(c);
    else
      out += fmt::format("%{:02X}", c);
  }
  return out;
}

constexpr const char* style = R"(body{font-family:"DejaVu Sans",Helvetica,Arial,sans-serif;
margin:2em auto;max-width:1100px;padding:0 1em;color:#111;line-height:1.4}
h1{font-size:1.6em;margin-bottom:.2em}h2{font-size:1.25em;margin-top:2em;border-bottom:1px solid #ccc}
p.sub{color:#555;margin-top:0}
table{border-collapse:collapse;margin:.5em 0}td,th{padding:.25em .8em;text-align:left;
vertical-align:top;border-bottom:1px solid #e4e4e4}th{background:#f3f3f3}
tr.attention td{background:#fff1e0}td.flag{font-weight:bold;color:#b35900}td.info{color:#666}
.verdict{padding:.6em 1em;border-radius:4px;margin:1em 0}
.ok{background:#eaf6ea;border:1px solid #9c9}.look{background:#fff1e0;border:1px solid #e0a060}
.figures{display:flex;flex-wrap:wrap;gap:1.2em}
figure{margin:0;flex:1 1 480px;max-width:520px}figure img{width:100%;border:1px solid #ddd}
figcaption{font-size:.9em;color:#333;margin-top:.3em}
pre{background:#f7f7f7;padding:1em;overflow-x:auto;font-size:.85em}
)";

void rows(std::string& html, const std::vector<ReportRow>& list, bool flags) {
  html += "<table>\n";
  for (const ReportRow& r : list) {
    html += r.attention ? "<tr class=\"attention\">" : "<tr>";
    html += "<th>" + escape(r.label) + "</th><td>" + escape(r.value) + "</td>";
    if (flags)
      html += !r.limited    ? "<td class=\"info\">info</td>"
              : r.attention ? "<td class=\"flag\">look</td>"
                            : "<td>ok</td>";
    html += "</tr>\n";
  }
  html += "</table>\n";
}

}  // namespace

std::string report_html(const Report& report) {
  std::string html =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" +
      escape(report.title) + "</title>\n<style>\n" + style + "</style>\n</head>\n<body>\n";
  html += "<h1>" + escape(report.title) + "</h1>\n";
  if (!report.subtitle.empty()) html += "<p class=\"sub\">" + escape(report.subtitle) + "</p>\n";
  std::size_t attention = 0, limited = 0;
  for (const ReportRow& r : report.checks) {
    attention += r.limited && r.attention ? 1 : 0;
    limited += r.limited ? 1 : 0;
  }
  if (limited > 0)
    html += attention == 0
                ? "<div class=\"verdict ok\">Every check below is within its limit.</div>\n"
                : fmt::format(
                      "<div class=\"verdict look\">{} of {} checks need a look (marked "
                      "below).</div>\n",
                      attention, limited);
  if (!report.summary.empty()) {
    html += "<h2>" + escape(report.summary_title) + "</h2>\n";
    rows(html, report.summary, false);
  }
  if (!report.checks.empty()) {
    html += "<h2>Can it be trusted?</h2>\n";
    rows(html, report.checks, true);
  }
  for (const ReportSection& s : report.sections) {
    if (s.figures.empty()) continue;
    html += "<h2>" + escape(s.title) + "</h2>\n<div class=\"figures\">\n";
    for (const ReportFigure& f : s.figures)
      html += "<figure><a href=\"" + url_path(f.path) + "\"><img src=\"" + url_path(f.path) +
              "\" alt=\"" + escape(f.caption) + "\"></a><figcaption>" + escape(f.caption) +
              "</figcaption></figure>\n";
    html += "</div>\n";
  }
  if (!report.details.empty())
    html += "<h2>Summary as text</h2>\n<pre>" + escape(report.details) + "</pre>\n";
  html += "</body>\n</html>\n";
  return html;
}

void write_report(const Report& report, const std::string& path) {
  std::ofstream out(path, std::ios::binary);
  out << report_html(report);
  if (!out) throw PipelineError(fmt::format("{}: cannot write the report", path));
}

std::string figure_caption(const std::string& relative_path) {
  static const std::vector<std::pair<std::regex, std::string>> known{
      {std::regex(R"((^|/)segmentation(_\d+)?\.png$)"),
       "The micrograph's segmentation: each grain found in the image in its own colour."},
      {std::regex(R"((^|/)damage_last\.png$)"),
       "Damage d of every particle at the last frame (0 intact, 1 failed)."},
      {std::regex(R"((^|/)speed_last\.png$)"), "Particle speed at the last frame."},
      {std::regex(R"((^|/)stress_last\.png$)"),
       "Largest principal stress at the last frame (tension positive)."},
      {std::regex(R"((^|/)body_last\.png$)"), "The grains (bodies) at the last frame."},
      {std::regex(R"((^|/)fragments_(\d+)\.png$)"),
       "Fragments of an analysed frame, one colour each."},
      {std::regex(R"((^|/)energy\.png$)"),
       "Energy against time: input work, kinetic and strain energy, every booked loss and the "
       "balance error."},
      {std::regex(R"((^|/)force_displacement\.png$)"), "Platen force against platen displacement."},
      {std::regex(R"((^|/)cdf_equivalent_diameter\.png$)"),
       "Cumulative number fraction of fragments against equivalent diameter, per analysed frame."},
      {std::regex(R"((^|/)cdf_equivalent_diameter_mass\.png$)"),
       "Cumulative mass fraction against equivalent diameter (a grading curve), per analysed "
       "frame."},
      {std::regex(R"((^|/)cdf_roundness\.png$)"),
       "Cumulative number fraction of fragments against roundness, per analysed frame."},
      {std::regex(R"((^|/)cdf_roundness_mass\.png$)"),
       "Cumulative mass fraction against roundness, per analysed frame."},
      {std::regex(R"((^|/)fragment_count\.png$)"),
       "Number of resolved fragments and of fines against time."},
      {std::regex(R"((^|/)fragment_size\.png$)"),
       "Mean and largest equivalent diameter of the fragments against time."},
  };
  for (const auto& [pattern, caption] : known)
    if (std::regex_search(relative_path, pattern)) return caption;
  return {};
}

}  // namespace fragmpm::pipeline
