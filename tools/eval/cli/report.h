#pragma once
/// @file
/// Output of swlio-eval: human-readable tables (JSON is swlio/eval/json.h) and the plot (a CSV
/// written here, drawn by scripts/eval_plot.py with Debian's python3-matplotlib).

#include "swlio/eval/evaluate.h"
#include "swlio/eval/kitti_metric.h"

#include <filesystem>
#include <ostream>
#include <string>

namespace swlio::tools {

/// evo-like table: one "name\tvalue" line per statistic.
void PrintStatisticsTable(std::ostream& out, const std::string& title, const eval::Statistics& s);

void PrintKittiTable(std::ostream& out, const eval::KittiResult& result);

/// Writes the plot data: one row per pose, `t_s,ref_x,ref_y,ref_z,est_x,est_y,est_z,error`
/// (t_s is the stamp, or the pose index without stamps; error empty where none was computed).
void WritePlotCsv(const std::filesystem::path& csv_path, const eval::Evaluation& evaluation);

/// Writes `png` (and its data `png` with extension .csv) by running /usr/bin/python3 on the plot
/// script. Returns false and sets `error` on failure.
bool DrawPlot(const std::filesystem::path& png,
              const eval::Evaluation& evaluation,
              const std::string& title,
              const std::string& error_label,
              std::string* error);

}  // namespace swlio::tools
