// The two programs of the FEM pipeline, run with their conventions: gmsh meshes a .geo file
// into an MSH 2.2 file, CalculiX `ccx` solves JOB.inp into JOB.frd. Both are found with
// FindProgram (PATH, or RAILWEAR_GMSH / RAILWEAR_CCX); a missing one is an InputError.
//
// ccx exits with code 0 even when it cannot open its input, and gmsh writes a mesh file even
// when meshing failed, so success is judged on the exit code, the log and the output file:
// RunGmsh and RunCcx throw std::runtime_error (quoting the log's tail) on any sign of failure.
#pragma once

#include <string>

#include "calibration/fem/external_program.h"

namespace railwear {

// The executables (FindProgram) and the versions they report, e.g. "4.8.4" and "2.20".
struct FemPrograms {
  std::string gmsh;
  std::string ccx;
  std::string gmsh_version;
  std::string ccx_version;
};
// Finds both programs (InputError when one is missing) and asks each for its version (running
// them in `work_dir`, which must exist).
FemPrograms FindFemPrograms(const std::string& work_dir);

// `gmsh -3 -format msh22 -o MSH GEO` in work_dir with `threads` threads; log "<msh>.log".
// Throws std::runtime_error when gmsh fails or writes no mesh.
ProgramResult RunGmsh(const std::string& gmsh, const std::string& work_dir,
                      const std::string& geo_file, const std::string& msh_file, int threads,
                      double timeout_s = 0.0);

// `ccx -i JOB` in work_dir (reads JOB.inp, writes JOB.frd) with OMP_NUM_THREADS and the
// CCX_NPROC_* variables set to `threads`; log "JOB.log". Throws std::runtime_error when ccx
// fails, its log holds "*ERROR", or it writes no JOB.frd.
ProgramResult RunCcx(const std::string& ccx, const std::string& work_dir, const std::string& job,
                     int threads, double timeout_s = 0.0);

}  // namespace railwear
