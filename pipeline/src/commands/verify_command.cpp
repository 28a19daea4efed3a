// `fragmpm verify [CASE…] [--quick] [--stability] [-o DIR]`.
#include <omp.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <stdexcept>

#include "fragmpm/pipeline/commands.hpp"
#include "fragmpm/pipeline/pipeline_job.hpp"
#include "fragmpm/pipeline/scene.hpp"
#include "fragmpm/pipeline/verify.hpp"
#include "fragmpm/pipeline/verify_three_grain.hpp"

namespace fragmpm::pipeline {

const std::vector<VerifyCase>& verify_cases() {
  static const std::vector<VerifyCase> cases{
      {"bar", "V1 axial vibration of an elastic bar: centre-of-mass velocity over one period",
       verify_bar},
      {"billet", "P2 self-contact vs two-body contact vs one field: horizontal velocities",
       verify_billet},
      {"notched-bar", "V6 notched bar struck by a disk: damage dissipation vs G_f x crack",
       verify_notched_bar},
      {"bar-tension",
       "V8 uniform bar with a weaker column pulled apart: damage dissipation vs G_f x height, "
       "three resolutions",
       verify_bar_tension},
      {"phase-field-bar",
       "AT2 phase field: imposed crack profile vs exp(-|x|/(2 l0)) and its energy, and the crack "
       "energy of a bar pulled apart vs G_c x height, three resolutions",
       verify_phase_field_bar},
      {"plate-impact",
       "KT19 5.1 plate under impact, phase field at h = 0.25 and 0.125 mm: crack start, speed vs "
       "Rayleigh, branching; isotropic, cubic and orthotropic; phase-field figures at the paper's "
       "times",
       verify_plate_impact},
      {"sphere-beam",
       "KT19 5.3 disk striking a free beam, phase field: crack energy while the median crack "
       "crosses vs G_c x depth; three surface energies at the paper's h; phase-field figures",
       verify_sphere_beam},
      {"two-rings",
       "KT19 5.2 two phase-field rings colliding at 10 and 20 m/s: pieces per ring vs the paper's "
       "2 and 5; phase-field figures at the paper's times",
       verify_two_rings},
      {"kalthoff", "P1 Kalthoff-Winkler plate: crack angle and crack speed", verify_kalthoff},
      {"brazilian",
       "P5 dynamic Brazilian disk: fragment count, mean size and speed at two resolutions, three "
       "Weibull seeds, partitioned vs single field",
       verify_brazilian},
      {"hertz",
       "V5 Hertz line contact, cylinder on a rigid flat: contact half-width and pressure profile, "
       "relaxed to equilibrium",
       verify_hertz},
      {"conduction", "V4 one-dimensional heat conduction from a temperature step vs erfc",
       verify_conduction},
      {"contact-temperature",
       "V3 pressed aluminium blocks: steady contact-face temperatures, three pressures",
       verify_contact_temperature},
      {"sliding-block",
       "V2 sliding block, four friction laws: end-of-slide velocity and friction work vs the rigid "
       "block",
       verify_sliding_block},
      {"oscillating-block",
       "V7 oscillating block: friction work of one stick-slide-stick cycle over CFL factors, "
       "first- and second-order heating",
       verify_oscillating_block},
      {"disk-squish",
       "P3 disk squish: peak contact temperature and disk speed, isothermal / coupled / softening "
       "friction",
       verify_disk_squish},
      {"three-grain",
       "P4 three grains crushed at 8, 16 and 80 m/s, coupled and isothermal: fragment size and "
       "roundness of the top grain, platen force, temperature, energy balance",
       verify_three_grain},
  };
  return cases;
}

namespace {

struct VerifyArguments {
  std::vector<std::string> cases;
  std::string output = "verify-out";
  bool quick = false;
  bool stability = false;
  std::vector<std::string> scenes;
  bool list = false;
  int threads = 0;
  std::vector<std::string> variants;
  int level = -1;
  long long max_steps = 0;
};

int execute(const VerifyArguments& args) {
  if (args.threads > 0) omp_set_num_threads(args.threads);
  VerifyOptions options;
  options.quick = args.quick;
  options.threads = args.threads;
  options.output_directory = args.output;
  options.variants = args.variants;
  options.level = args.level;
  options.max_steps = args.max_steps;
  const bool selecting = !args.variants.empty() || args.level >= 0;
  if (args.list) {
    for (const auto& c : verify_cases())
      std::printf("%-16s %s\n", c.name.c_str(), c.description.c_str());
    return 0;
  }
  if (args.stability) {
    std::vector<StabilityResult> results;
    if (args.scenes.empty()) {
      results = run_stability(options);
    } else {
      for (const std::string& name : args.scenes) {
        try {
          results.push_back(run_stability_scene(name));
        } catch (const std::invalid_argument&) {
          std::fprintf(
              stderr, "fragmpm verify --scene: unknown stability scene '%s'; known:", name.c_str());
          for (const std::string& known : stability_scene_names())
            std::fprintf(stderr, " %s", known.c_str());
          std::fprintf(stderr, "\n");
          return 2;
        }
      }
    }
    bool all = true;
    for (const auto& r : results) {
      std::printf("\n%-24s %s  (%.2f s)\n", r.scene.c_str(), r.passed ? "PASS" : "FAIL",
                  r.wall_seconds);
      for (const auto& check : r.checks) std::printf("    %s\n", check.c_str());
      all = all && r.passed;
    }
    std::printf("\nstability: %s\n", all ? "all scenes passed" : "some scenes FAILED");
    if (!all) return 3;
    if (args.cases.empty()) return 0;
  }
  std::vector<const VerifyCase*> selected;
  for (const auto& name : args.cases) {
    const VerifyCase* found = nullptr;
    for (const auto& c : verify_cases())
      if (c.name == name) found = &c;
    if (!found) {
      std::fprintf(stderr, "fragmpm verify: unknown case '%s'; known cases:", name.c_str());
      for (const auto& c : verify_cases()) std::fprintf(stderr, " %s", c.name.c_str());
      std::fprintf(stderr, "\n");
      return 2;
    }
    selected.push_back(found);
  }
  if (selected.empty())
    for (const auto& c : verify_cases()) selected.push_back(&c);
  // The selection's CSV name: DIR/CASE-VARIANT…-levelN.csv beside a full run's DIR/CASE.csv.
  std::string selection;
  if (selecting) {
    const auto& selectable = variant_selection_cases();
    std::string names;
    for (const std::string& name : selectable) names += " " + name;
    if (args.cases.empty()) {
      std::fprintf(stderr,
                   "fragmpm verify: --variant and --level need a case; cases that offer "
                   "them:%s\n",
                   names.c_str());
      return 2;
    }
    for (const VerifyCase* c : selected)
      if (std::find(selectable.begin(), selectable.end(), c->name) == selectable.end()) {
        std::fprintf(stderr,
                     "fragmpm verify: case '%s' runs all its variants and levels together; "
                     "--variant and --level apply to:%s\n",
                     c->name.c_str(), names.c_str());
        return 2;
      }
    for (std::string variant : args.variants) {
      std::replace(variant.begin(), variant.end(), '/', '-');  // "10m/s" in a file name
      selection += (selection.empty() ? "" : "-") + variant;
    }
    if (args.level >= 0)
      selection += (selection.empty() ? "level" : "-level") + std::to_string(args.level);
  }
  std::vector<std::string> missed;
  for (const VerifyCase* c : selected) {
    try {
      if (!report_case(args.output, c->name, c->run(options), selection)) missed.push_back(c->name);
    } catch (const SceneError& e) {
      std::fprintf(stderr, "fragmpm verify %s: scene error: %s\n", c->name.c_str(), e.what());
      return 2;
    } catch (const PipelineError& e) {  // a data file of the source tree is missing
      std::fprintf(stderr, "fragmpm verify %s: %s\n", c->name.c_str(), e.what());
      return 2;
    } catch (const std::invalid_argument& e) {  // the selection names what the case lacks
      std::fprintf(stderr, "fragmpm verify %s: %s\n", c->name.c_str(), e.what());
      return 2;
    } catch (const std::runtime_error& e) {
      std::fprintf(stderr, "fragmpm verify %s: %s\n", c->name.c_str(), e.what());
      return 3;
    }
  }
  if (!missed.empty()) {
    std::printf("\nverify: target missed in");
    for (const auto& name : missed) std::printf(" %s", name.c_str());
    std::printf(" (exit code 1)\n");
    return 1;
  }
  return 0;
}

}  // namespace

void add_verify_command(CLI::App& app, CommandResult& result) {
  auto args = std::make_shared<VerifyArguments>();
  CLI::App* verify = app.add_subcommand("verify",
                                        "Run verification cases at successive resolutions (writes "
                                        "DIR/CASE.csv) or the stability scenes");
  verify->add_option("cases", args->cases, "Cases to run (default: all; --list shows them)");
  verify->add_option("-o,--output", args->output, "Directory for CSV files (default verify-out)");
  verify->add_flag("--quick", args->quick, "Fewer, coarser levels (for CI)");
  verify->add_flag("--stability", args->stability, "Run the stiff and extreme stability scenes");
  verify->add_option("--scene", args->scenes,
                     "With --stability: only these stability scenes (repeatable; e.g. "
                     "spinning-disk)");
  verify->add_flag("--list", args->list, "List the cases");
  verify->add_option("--threads", args->threads, "OpenMP threads");
  verify->add_option("--variant", args->variants,
                     "Only this variant of the case (repeatable; plate-impact, sphere-beam and "
                     "two-rings, whose runs at the papers' resolutions take up to hours each; the "
                     "case's variants are the first column of its table). Writes "
                     "DIR/CASE-VARIANT.csv");
  verify
      ->add_option("--level", args->level,
                   "Only this level of the case (0 the coarsest; with the cases of --variant)")
      ->check(CLI::NonNegativeNumber);
  verify
      ->add_option("--max-steps", args->max_steps,
                   "Stop the runs kept in a run file (plate-impact at level 1, hours each) after "
                   "this many steps, with a checkpoint in DIR/CASE/VARIANT-hH.h5; the same command "
                   "continues them")
      ->check(CLI::PositiveNumber);
  verify->callback([args, &result] { result.exit_code = execute(*args); });
}

}  // namespace fragmpm::pipeline
