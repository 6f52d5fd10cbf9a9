// Running gmsh and ccx with their conventions. See fem_programs.h.
#include "calibration/fem/fem_programs.h"
#include "core/numerics/text_file.h"

#include <filesystem>
#include <fstream>
#include <regex>
#include <stdexcept>

#include <fmt/format.h>

namespace railwear {
namespace {

// The first match of `pattern`'s group 1 in the program's output, or "unknown".
std::string VersionOf(const std::string& program, const std::vector<std::string>& args,
                      const std::string& work_dir, const std::string& log,
                      const std::regex& pattern) {
  ProgramRun run;
  run.argv = {program};
  run.argv.insert(run.argv.end(), args.begin(), args.end());
  run.work_dir = work_dir;
  run.log_path = log;
  run.timeout_s = 60.0;
  const ProgramResult r = RunProgram(run);
  const std::string text = ReadTextFile(r.log_path).value_or("");
  std::error_code ec;
  std::filesystem::remove(r.log_path, ec);
  std::smatch m;
  if (std::regex_search(text, m, pattern)) return m[1];
  return "unknown";
}

[[noreturn]] void FailWithLog(std::string_view what, const std::string& reason,
                              const std::string& work_dir, const ProgramResult& r) {
  throw std::runtime_error(ProgramFailureMessage(what, reason, work_dir, r));
}

}  // namespace

FemPrograms FindFemPrograms(const std::string& work_dir) {
  FemPrograms p;
  p.gmsh = FindProgram(GmshProgram());
  p.ccx = FindProgram(CcxProgram());
  p.gmsh_version = VersionOf(p.gmsh, {"--version"}, work_dir, "gmsh_version.log",
                             std::regex(R"(([0-9]+\.[0-9]+(\.[0-9]+)?))"));
  p.ccx_version = VersionOf(p.ccx, {"-v"}, work_dir, "ccx_version.log",
                            std::regex(R"(Version ([0-9]+\.[0-9]+[^\s]*))"));
  return p;
}

ProgramResult RunGmsh(const std::string& gmsh, const std::string& work_dir,
                      const std::string& geo_file, const std::string& msh_file, int threads,
                      double timeout_s) {
  namespace fs = std::filesystem;
  ProgramRun run;
  run.argv = {gmsh, "-3",     "-format", "msh22", "-nt", std::to_string(threads),
              "-o", msh_file, geo_file};
  run.work_dir = work_dir;
  run.log_path = msh_file + ".log";
  run.timeout_s = timeout_s;
  const ProgramResult r = RunProgram(run);
  if (!r.Succeeded()) FailWithLog("gmsh", r.Describe(), work_dir, r);
  const fs::path mesh = fs::path(work_dir) / msh_file;
  std::error_code ec;
  if (!fs::exists(mesh, ec) || fs::file_size(mesh, ec) == 0) {
    FailWithLog("gmsh", fmt::format("it wrote no {}", msh_file), work_dir, r);
  }
  return r;
}

ProgramResult RunCcx(const std::string& ccx, const std::string& work_dir, const std::string& job,
                     int threads, double timeout_s) {
  namespace fs = std::filesystem;
  ProgramRun run;
  run.argv = {ccx, "-i", job};
  run.work_dir = work_dir;
  run.log_path = job + ".log";
  run.timeout_s = timeout_s;
  const std::string n = std::to_string(threads);
  run.environment = {{"OMP_NUM_THREADS", n},
                     {"CCX_NPROC_STIFFNESS", n},
                     {"CCX_NPROC_EQUATION_SOLVER", n},
                     {"CCX_NPROC_RESULTS", n}};
  const ProgramResult r = RunProgram(run);
  if (!r.Succeeded()) FailWithLog("ccx (CalculiX)", r.Describe(), work_dir, r);
  if (ReadTextFile(r.log_path).value_or("").find("*ERROR") != std::string::npos) {
    FailWithLog("ccx (CalculiX)", "its log reports *ERROR", work_dir, r);
  }
  const fs::path frd = fs::path(work_dir) / (job + ".frd");
  std::error_code ec;
  if (!fs::exists(frd, ec) || fs::file_size(frd, ec) == 0) {
    FailWithLog("ccx (CalculiX)", fmt::format("it wrote no {}.frd", job), work_dir, r);
  }
  return r;
}

}  // namespace railwear
