// swlio-eval: trajectory accuracy with the conventions of evo v1.36 (APE, RPE) and of the KITTI
// odometry devkit (segment metric).
//
//   swlio-eval ape GT EST --format kitti|tum [--align se3|sim3|origin|none]
//                         [--relation trans|angle_deg|angle_rad|full|rot_part] [--json] [--plot P]
//   swlio-eval rpe GT EST --format kitti|tum [--delta N] [--delta-unit frames|m] [...as ape]
//   swlio-eval kitti GT EST [--times FILE] [--json]
//
// Defaults are evo's: no alignment, translation, RPE delta 1 frame, association within 0.01 s.

#include "report.h"

#include "swlio/eval/json.h"

#include <CLI/CLI.hpp>

#include <iostream>

namespace {

using namespace swlio;
using namespace swlio::tools;

struct CommonArgs {
  std::string ref_path;
  std::string est_path;
  std::string format;
  std::string align = "none";
  std::string relation = "trans";
  std::string times_path;
  std::string plot_path;
  double max_diff_s = 0.01;
  double t_offset_s = 0.0;
  bool json = false;
};

struct RpeArgs {
  double delta = 1.0;
  std::string delta_unit = "frames";
};

void AddCommon(CLI::App* cmd, CommonArgs& a) {
  cmd->add_option("GT", a.ref_path, "reference (ground truth) trajectory")->required();
  cmd->add_option("EST", a.est_path, "estimated trajectory")->required();
  cmd->add_option("--format", a.format, "file format")
      ->required()
      ->check(CLI::IsMember({"tum", "kitti"}));
  cmd->add_option("--align", a.align, "alignment of the estimate (default none)")
      ->check(CLI::IsMember({"none", "se3", "sim3", "origin"}));
  cmd->add_option("--relation", a.relation, "pose relation (default trans)")
      ->check(CLI::IsMember({"trans", "trans_part", "angle_deg", "angle_rad", "full", "rot_part"}));
  cmd->add_option("--times", a.times_path, "KITTI timestamp file (one time per line, both files)");
  cmd->add_option("--max-diff", a.max_diff_s, "TUM association tolerance in seconds (0.01)");
  cmd->add_option("--t-offset", a.t_offset_s, "seconds added to the estimate's stamps (0)");
  cmd->add_flag("--json", a.json, "print one JSON object with the statistics");
  cmd->add_option("--plot", a.plot_path,
                  "write a PNG: top view coloured by error, error over time");
}

std::string AlignmentNote(eval::Alignment alignment) {
  switch (alignment) {
    case eval::Alignment::kSe3:
      return "(with SE(3) Umeyama alignment)";
    case eval::Alignment::kSim3:
      return "(with Sim(3) Umeyama alignment)";
    case eval::Alignment::kOrigin:
      return "(with origin alignment)";
    case eval::Alignment::kNone:
      break;
  }
  return "(not aligned)";
}

int Report(const eval::Evaluation& result, const CommonArgs& a, const std::string& title) {
  const std::string label = eval::Describe(eval::ParsePoseRelation(a.relation));
  if (a.json) {
    std::cout << eval::ToJson(result.stats) << '\n';
  } else {
    PrintStatisticsTable(std::cout, title, result.stats);
  }
  if (!a.plot_path.empty()) {
    std::string error;
    if (!DrawPlot(a.plot_path, result, title, label, &error)) {
      std::cerr << "swlio-eval: " << error << '\n';
      return 1;
    }
  }
  return 0;
}

eval::PairedTrajectories Load(const CommonArgs& a) {
  return eval::LoadPaired(a.ref_path, a.est_path, eval::ParseFormat(a.format), a.times_path,
                          {a.max_diff_s, a.t_offset_s});
}

int RunApe(const CommonArgs& a) {
  eval::ApeOptions options;
  options.alignment = eval::ParseAlignment(a.align);
  options.relation = eval::ParsePoseRelation(a.relation);
  const eval::Evaluation result = eval::EvaluateApe(Load(a), options);
  return Report(
      result, a,
      "APE w.r.t. " + eval::Describe(options.relation) + "\n" + AlignmentNote(options.alignment));
}

int RunRpe(const CommonArgs& a, const RpeArgs& r) {
  eval::RpeOptions options;
  options.alignment = eval::ParseAlignment(a.align);
  options.relation = eval::ParsePoseRelation(a.relation);
  options.delta = r.delta;
  options.delta_unit = eval::ParseDeltaUnit(r.delta_unit);
  const eval::Evaluation result = eval::EvaluateRpe(Load(a), options);
  return Report(result, a,
                "RPE w.r.t. " + eval::Describe(options.relation) +
                    " for delta = " + CLI::detail::to_string(r.delta) + " (" + r.delta_unit +
                    ")\n" + AlignmentNote(options.alignment));
}

int RunKitti(const CommonArgs& a, std::size_t step) {
  const eval::Trajectory gt = eval::ReadKittiFile(a.ref_path, a.times_path);
  const eval::Trajectory est = eval::ReadKittiFile(a.est_path, a.times_path);
  eval::KittiOptions options;
  options.step_frames = step;
  const eval::KittiResult result = eval::KittiOdometryMetric(gt, est, options);
  if (a.json) {
    std::cout << eval::ToJson(result) << '\n';
  } else {
    PrintKittiTable(std::cout, result);
  }
  return 0;
}

}  // namespace

static int Run(int argc, char** argv) {
  CLI::App app{"swlio-eval: trajectory accuracy (APE/RPE as evo computes them, KITTI metric)"};
  app.require_subcommand(1);
  CommonArgs ape_args;
  CommonArgs rpe_args;
  RpeArgs rpe_extra;
  CommonArgs kitti_args;
  std::size_t kitti_step = 10;

  CLI::App* ape = app.add_subcommand("ape", "absolute pose error");
  AddCommon(ape, ape_args);
  CLI::App* rpe = app.add_subcommand("rpe", "relative pose error");
  AddCommon(rpe, rpe_args);
  rpe->add_option("--delta", rpe_extra.delta, "pair distance (default 1)");
  rpe->add_option("--delta-unit", rpe_extra.delta_unit, "frames or m (default frames)")
      ->check(CLI::IsMember({"frames", "m"}));
  CLI::App* kitti = app.add_subcommand("kitti", "KITTI odometry metric (KITTI pose files)");
  kitti->add_option("GT", kitti_args.ref_path, "ground truth poses (KITTI)")->required();
  kitti->add_option("EST", kitti_args.est_path, "estimated poses (KITTI)")->required();
  kitti->add_option("--times", kitti_args.times_path, "KITTI timestamp file");
  kitti->add_option("--step", kitti_step, "frames between segment starts (default 10)");
  kitti->add_flag("--json", kitti_args.json, "print one JSON object");

  CLI11_PARSE(app, argc, argv);
  try {
    if (ape->parsed()) return RunApe(ape_args);
    if (rpe->parsed()) return RunRpe(rpe_args, rpe_extra);
    if (kitti->parsed()) return RunKitti(kitti_args, kitti_step);
  } catch (const eval::EvalError& e) {
    std::cerr << "swlio-eval: " << e.what() << '\n';
    return 1;
  }
  return 1;
}

int main(int argc, char** argv) {
  try {
    return Run(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "swlio-eval: " << e.what() << "\n";
    return 2;
  }
}
