// swlio-eval output: tables, JSON and the plot (see report.h).

#include "report.h"

#include "swlio/eval/json.h"

#include <spawn.h>
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <vector>

namespace swlio::tools {
namespace {

std::string Num(double value) { return eval::FormatExact(value); }

std::filesystem::path PlotScript() {
  if (const char* env = std::getenv("SWLIO_EVAL_PLOT_SCRIPT"); env != nullptr && *env != '\0') {
    return env;
  }
  return SWLIO_EVAL_PLOT_SCRIPT;
}

/// Runs argv[0] with argv (no shell) and waits; returns its exit status or -1.
int RunProgram(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  argv.reserve(args.size() + 1);
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawn(&pid, argv[0], nullptr, nullptr, argv.data(), environ) != 0) return -1;
  int status = 0;
  if (waitpid(pid, &status, 0) != pid) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

void PrintStatisticsTable(std::ostream& out, const std::string& title, const eval::Statistics& s) {
  char buf[200];
  out << title << "\n\n";
  std::snprintf(buf, sizeof(buf),
                "%10s\t%zu\n%10s\t%.12g\n%10s\t%.12g\n%10s\t%.12g\n%10s\t%.12g\n%10s\t%.12g\n", "n",
                s.n, "max", s.max, "mean", s.mean, "median", s.median, "min", s.min, "rmse",
                s.rmse);
  out << buf;
  std::snprintf(buf, sizeof(buf), "%10s\t%.12g\n%10s\t%.12g\n", "sse", s.sse, "std", s.std);
  out << buf;
}

void PrintKittiTable(std::ostream& out, const eval::KittiResult& r) {
  char buf[160];
  out << "KITTI odometry metric (devkit: segments 100..800 m, every 10th first frame)\n\n";
  out << "  length (m)  segments  t_err (%)  r_err (deg/100m)\n";
  for (const auto& l : r.per_length) {
    std::snprintf(buf, sizeof(buf), "%12.0f  %8zu  %9.4f  %16.4f\n", l.length_m, l.n,
                  l.t_err_percent, l.r_err_deg_per_100m);
    out << buf;
  }
  std::snprintf(buf, sizeof(buf), "%12s  %8zu  %9.4f  %16.4f\n", "all", r.segments.size(),
                r.t_err_percent, r.r_err_deg_per_100m);
  out << buf;
}

void WritePlotCsv(const std::filesystem::path& csv_path, const eval::Evaluation& evaluation) {
  const eval::Trajectory& ref = evaluation.data.ref;
  const eval::Trajectory& est = evaluation.data.est;
  std::vector<std::string> error_text(ref.Size());
  for (std::size_t k = 0; k < evaluation.errors.size(); ++k) {
    error_text[evaluation.error_pose_ids[k]] = Num(evaluation.errors[k]);
  }
  std::ofstream out(csv_path);
  if (!out) throw eval::EvalError(csv_path.string() + ": cannot write");
  out << "t_s,ref_x,ref_y,ref_z,est_x,est_y,est_z,error\n";
  for (std::size_t i = 0; i < ref.Size(); ++i) {
    const double t = ref.HasStamps() ? ref.stamps_s[i] : static_cast<double>(i);
    const Eigen::Vector3d p = ref.Position(i);
    const Eigen::Vector3d q = est.Position(i);
    out << Num(t) << ',' << Num(p.x()) << ',' << Num(p.y()) << ',' << Num(p.z()) << ','
        << Num(q.x()) << ',' << Num(q.y()) << ',' << Num(q.z()) << ',' << error_text[i] << '\n';
  }
  if (!out) throw eval::EvalError(csv_path.string() + ": write failed");
}

bool DrawPlot(const std::filesystem::path& png,
              const eval::Evaluation& evaluation,
              const std::string& title,
              const std::string& error_label,
              std::string* error) {
  std::filesystem::path csv = png;
  csv.replace_extension(".csv");
  WritePlotCsv(csv, evaluation);
  const std::filesystem::path script = PlotScript();
  if (!std::filesystem::exists(script)) {
    *error = "plot script not found: " + script.string() + " (set SWLIO_EVAL_PLOT_SCRIPT)";
    return false;
  }
  const int status =
      RunProgram({"/usr/bin/python3", script.string(), csv.string(), png.string(), title,
                  evaluation.data.ref.HasStamps() ? "t" : "index", error_label});
  if (status != 0) {
    *error =
        "plot script failed (exit " + std::to_string(status) + "); data left in " + csv.string();
    return false;
  }
  return true;
}

}  // namespace swlio::tools
