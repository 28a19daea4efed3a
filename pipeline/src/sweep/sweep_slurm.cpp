// `fragmpm sweep --slurm`: a job-array script, one array task per member.
#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "fragmpm/pipeline/sweep_schedule.hpp"

namespace fragmpm::pipeline {

namespace fs = std::filesystem;

namespace {
/// Single quotes for the shell, with embedded single quotes closed and reopened.
std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}
}  // namespace

std::string write_slurm_script(const SweepSpec& spec, const std::string& dir, int threads,
                               const std::string& executable) {
  const fs::path out = fs::absolute(dir);
  const fs::path script = out / "sweep.slurm";
  const std::string text = fmt::format(
      "#!/bin/bash\n"
      "# FragMPM sweep {sweep}: {n} members, one per array task.\n"
      "# Submit with: sbatch {script}\n"
      "# A task skips its member when it is finished already, so resubmitting reruns only the\n"
      "# failed or interrupted ones; each task rewrites {dir}/manifest.csv when it ends.\n"
      "#SBATCH --job-name=fragmpm-sweep\n"
      "#SBATCH --array=1-{n}\n"
      "#SBATCH --ntasks=1\n"
      "#SBATCH --cpus-per-task={threads}\n"
      "#SBATCH --output={dir}/slurm-%A_%a.out\n"
      "set -euo pipefail\n"
      "export OMP_NUM_THREADS=\"${{SLURM_CPUS_PER_TASK:-{threads}}}\"\n"
      "exec {exe} sweep {sweep_q} -o {dir_q} --member \"$SLURM_ARRAY_TASK_ID\" "
      "--threads \"$OMP_NUM_THREADS\"\n",
      fmt::arg("sweep", fs::absolute(spec.path).string()), fmt::arg("n", spec.members.size()),
      fmt::arg("script", script.string()), fmt::arg("dir", out.string()),
      fmt::arg("threads", threads), fmt::arg("exe", shell_quote(executable)),
      fmt::arg("sweep_q", shell_quote(fs::absolute(spec.path).string())),
      fmt::arg("dir_q", shell_quote(out.string())));
  std::ofstream f(script, std::ios::trunc);
  f << text;
  if (!f) throw std::runtime_error(script.string() + ": cannot write");
  f.close();
  fs::permissions(script, fs::perms::owner_exec | fs::perms::group_exec, fs::perm_options::add);
  return script.string();
}

}  // namespace fragmpm::pipeline
