// `railwear fem-reference` end to end: config parsing (defaults, overrides, resolved outputs),
// exit code 2 with file:line messages for bad configs and for a missing ccx, exit code 1 with the
// log's path when ccx fails, and a tiny real run (a coarse flat block, about a second) whose
// CSV the calibration reader accepts. Runs the built binary (RAILWEAR_BINARY).
#include <filesystem>
#include <map>
#include <string>

#include <gtest/gtest.h>

#include "app/fem_reference_command.h"
#include "calibration/displacement_curves.h"
#include "calibration/fem/external_program.h"
#include "core/numerics/input_error.h"

#include "tests/app/fem_reference_fixture.h"

namespace {

namespace fs = std::filesystem;

using railwear::CurveBody;
using railwear::CurveLoad;
using railwear::InputError;
using railwear::test::Contains;
using railwear::test::Outcome;
using railwear::test::ReadFile;

// A coarse flat block: one normal-load solve of about 1.5k nodes.
constexpr const char* kTinyConfig =
    "[fem]\n"
    "mesh_size_at_load_mm = 0.3\n"
    "mesh_growth = 0.4\n"
    "max_element_mm = 100\n"
    "max_distance_mm = 10\n"
    "loads = [\"normal\"]\n"
    "\n"
    "[[experiment]]\n"
    "name = \"tiny\"\n"
    "body = \"flat\"\n"
    "output = \"out/tiny.csv\"\n";

class FemReferenceTest : public railwear::test::FemReferenceFixture {};

TEST_F(FemReferenceTest, ConfigDefaultsAndOverrides) {
  Write("c.toml",
        "[fem]\n"
        "mesh_size_at_load_mm = 0.2\n"
        "material = { E_MPa = 200000, nu = 0.3 }\n"
        "compare_range_mm = [2, 8]\n"
        "jobs = 1\n"
        "[[experiment]]\n"
        "name = \"a\"\n"
        "body = \"convex\"\n"
        "radius_mm = 15\n"
        "[[experiment]]\n"
        "name = \"b\"\n"
        "kind = \"displacement\"\n"
        "body = \"concave\"\n"
        "radius_mm = 15.1\n"
        "mesh_size_at_load_mm = 0.15\n"
        "loads = [\"axial\"]\n"
        "supports = \"far_faces\"\n"
        "depth_mm = 80\n"
        "output = \"sub/b.csv\"\n"
        "compare_with = \"a\"\n");
  const auto config = railwear::app::ReadFemReferenceConfig((dir_ / "c.toml").string(), "");
  ASSERT_EQ(config.experiments.size(), 2u);
  const auto& a = config.experiments[0];
  EXPECT_EQ(a.name, "a");
  EXPECT_EQ(a.line, 6);
  EXPECT_EQ(a.options.body, CurveBody::kConvex);
  EXPECT_DOUBLE_EQ(a.options.radius_m, 15e-3);
  EXPECT_DOUBLE_EQ(a.options.mesh_size_at_load_m, 0.2e-3);
  EXPECT_DOUBLE_EQ(a.options.mesh_growth, 0.12);  // the library default
  EXPECT_DOUBLE_EQ(a.options.material.youngs_modulus_Pa, 200000e6);
  EXPECT_EQ(a.options.loads.size(), 3u);
  EXPECT_EQ(a.options.jobs, 1);
  EXPECT_DOUBLE_EQ(a.compare_from_m, 2e-3);
  EXPECT_EQ(a.output, (dir_ / "a.csv").string());
  const auto& b = config.experiments[1];
  EXPECT_DOUBLE_EQ(b.options.mesh_size_at_load_m, 0.15e-3);
  EXPECT_EQ(b.options.loads, std::vector<CurveLoad>({CurveLoad::kAxial}));
  EXPECT_EQ(b.options.supports, railwear::FemSupports::kFarFaces);
  EXPECT_DOUBLE_EQ(b.options.depth_m, 80e-3);
  EXPECT_EQ(b.output, (dir_ / "sub/b.csv").string());
  EXPECT_EQ(b.compare_with, "a");
  // --out-dir: outputs relative to it.
  const auto moved = railwear::app::ReadFemReferenceConfig((dir_ / "c.toml").string(), "/x/y");
  EXPECT_EQ(moved.experiments[1].output, "/x/y/sub/b.csv");
}

TEST_F(FemReferenceTest, BadConfigsNameFileLineKeyAndExpectation) {
  const std::string head = "[[experiment]]\nname = \"a\"\nbody = \"flat\"\n";
  EXPECT_TRUE(Contains(ConfigError("[fem]\nmesh_size = 0.1\n" + head),
                       "bad.toml:2: key 'fem.mesh_size' = 0.1: expected one of the keys allowed "
                       "in [fem]: 'mesh_size_at_load_mm'"));
  EXPECT_TRUE(Contains(ConfigError("[fem]\nmesh_growth = 3\n" + head),
                       "bad.toml:2: key 'fem.mesh_growth' = 3: expected a number in (0, 2]"));
  EXPECT_TRUE(Contains(ConfigError("[fem]\nmaterial = { E_MPa = 210000, nu = 0.7 }\n" + head),
                       "key 'fem.material.nu' = 0.7: expected a number in [0, 0.5)"));
  EXPECT_TRUE(Contains(ConfigError("[fem]\njobs = 1.5\n" + head),
                       "key 'fem.jobs' = 1.5: expected an integer >= 1"));
  EXPECT_TRUE(Contains(ConfigError("[fem]\nloads = [\"normal\", \"shear\"]\n" + head),
                       "key 'fem.loads' = [\"normal\", \"shear\"]: expected a non-empty array of "
                       "distinct loads"));
  EXPECT_TRUE(Contains(ConfigError("[fem]\ncompare_range_mm = [10, 1]\n" + head),
                       "expected two distances [from, to] in mm with 0 < from < to"));
  EXPECT_TRUE(Contains(ConfigError("[fem]\n"),
                       "bad.toml:1: key 'experiment' is missing: expected at least one "
                       "[[experiment]] table"));
  EXPECT_TRUE(Contains(ConfigError("[[experiment]]\nname = \"a\"\nbody = 3\n"),
                       "bad.toml:3: key 'experiment[0].body' = 3: expected one of 'flat', "
                       "'convex', 'concave'"));
  EXPECT_TRUE(Contains(ConfigError("[[experiment]]\nname = \"a\"\n"),
                       "key 'experiment[0].body' is missing"));
  EXPECT_TRUE(Contains(ConfigError("[[experiment]]\nname = \"a b\"\nbody = \"flat\"\n"),
                       "key 'experiment[0].name' = \"a b\": expected a name of letters"));
  EXPECT_TRUE(Contains(ConfigError(head + head),
                       "bad.toml:5: key 'experiment[1].name' = \"a\": expected a name not used "
                       "before (line 1 has it)"));
  // A contact experiment has its own keys (tests/app/fem_contact_cli_test.cpp): no body.
  EXPECT_TRUE(Contains(ConfigError(head + "kind = \"contact\"\n"),
                       "key 'experiment[0].body' = \"flat\": expected one of the keys allowed in "
                       "[experiment[0]]: 'name', 'kind', 'case'"));
  EXPECT_TRUE(Contains(ConfigError(head + "radius_mm = 15\n"),
                       "key 'experiment[0].radius_mm' = 15: expected no radius for a flat body"));
  EXPECT_TRUE(Contains(ConfigError("[[experiment]]\nname = \"a\"\nbody = \"convex\"\n"),
                       "key 'experiment[0].radius_mm' is missing: expected a number > 0"));
  EXPECT_TRUE(
      Contains(ConfigError("[[experiment]]\nname = \"a\"\nbody = \"convex\"\nradius_mm = 15\n"
                           "width_mm = 50\n"),
               "key 'experiment[0].width_mm' = 50: expected no width for a convex body"));
  EXPECT_TRUE(Contains(ConfigError(head + "length_mm = 50\n"),
                       "bad.toml:1: experiment 'a': body length 50 mm: expected at least 4 "
                       "max_distance = 100 mm"));
  EXPECT_TRUE(Contains(ConfigError(head + "compare_with = \"b\"\n"),
                       "key 'experiment[0].compare_with' = \"b\": expected the name of an earlier "
                       "experiment of this file (there is none)"));
  EXPECT_TRUE(Contains(ConfigError(head + "[[experiment]]\nname = \"b\"\nbody = \"flat\"\n"
                                          "output = \"a.csv\"\n"),
                       "key 'experiment[1].output' = \"a.csv\": expected a file no other "
                       "experiment writes ('a' writes it)"));
  EXPECT_TRUE(Contains(ConfigError("[fem\n"), "bad.toml:1:5: TOML syntax error"));
}

// Issue 17: every numeric key has a range the mesher and solver bear, and a mesh estimated too
// large is refused before gmsh runs (exit 2, file:line, the keys to change), in a fraction of a
// second where the run would take hours and tens of GB.
TEST_F(FemReferenceTest, OutOfRangeKeysAndOversizedMeshesExitTwoBeforeMeshing) {
  const std::string head = "[[experiment]]\nname = \"a\"\nbody = \"flat\"\n";
  struct Case {
    std::string config, expected;
  };
  const std::vector<Case> cases = {
      {"[fem]\nmesh_size_at_load_mm = 0.001\n" + head,
       "key 'fem.mesh_size_at_load_mm' = 0.001: expected a number in [0.005, 1000]"},
      {"[fem]\nmax_element_mm = 1e308\n" + head, "key 'fem.max_element_mm' = 1e+308"},
      {"[fem]\njobs = 100000\n" + head, "key 'fem.jobs' = 100000: expected an integer in [1, 256]"},
      {"[fem]\ntimeout_s = 1e300\n" + head, "key 'fem.timeout_s'"},
      {"[[experiment]]\nname = \"a\"\nbody = \"convex\"\nradius_mm = 1e-9\n",
       "key 'experiment[0].radius_mm' = 1e-09: expected a number in [0.1, 10000]"},
      {head + "length_mm = 1e9\n",
       "key 'experiment[0].length_mm' = 1000000000: expected a number in [1, 10000]"},
      {"[[experiment]]\nname = \"c\"\nkind = \"contact\"\ncase = \"wheel_in_groove\"\n"
       "load_N = 1e30\n",
       "key 'experiment[0].load_N' = 1e+30: expected a number in [1, 10000000]"},
      {"[[experiment]]\nname = \"c\"\nkind = \"contact\"\ncase = \"wheel_in_groove\"\n"
       "mesh_sizes_mm = [0.7, 0.0001]\n",
       "key 'experiment[0].mesh_sizes_mm' = [0.7, 0.0001]: expected a non-empty array of element "
       "sizes in mm, each in [0.005, 1000]"},
      // In range, but the mesh would be enormous: refused by the estimate, naming the keys.
      {"[fem]\nmesh_size_at_load_mm = 0.005\nmesh_growth = 0.01\n" + head,
       "bad.toml:4: experiment 'a': the mesh would have about"},
      {"[fem]\nmesh_size_at_load_mm = 0.005\nmesh_growth = 0.01\n" + head,
       "expected a coarser mesh: a larger mesh_size_at_load_mm, mesh_growth or max_element_mm"},
      {"[[experiment]]\nname = \"c\"\nkind = \"contact\"\ncase = \"wheel_in_groove\"\n"
       "mesh_sizes_mm = [0.7, 0.05]\n",
       "bad.toml:1: experiment 'c': the mesh level of 0.05 mm would have about"},
  };
  for (const Case& c : cases) {
    EXPECT_TRUE(Contains(ConfigError(c.config), c.expected)) << c.config << ConfigError(c.config);
  }
  // Through the command: exit 2 before any program runs.
  Write("big.toml", "[fem]\nmesh_size_at_load_mm = 0.005\nmesh_growth = 0.01\n" + head);
  const Outcome o = Run("fem-reference big.toml");
  EXPECT_EQ(o.exit_code, 2) << o.err;
  EXPECT_TRUE(Contains(o.err,
                       "railwear: error: big.toml:4: experiment 'a': the mesh would have "
                       "about"))
      << o.err;
  // The documented meshes pass (the example configs are read by ExampleConfigsAnd...).
  EXPECT_EQ(ConfigError(kTinyConfig), "");
}

TEST_F(FemReferenceTest, BadConfigExitsWith2) {
  Write("bad.toml", "[[experiment]]\nname = \"a\"\nbody = \"round\"\n");
  const Outcome o = Run("fem-reference bad.toml");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_TRUE(Contains(o.err, "railwear: error: bad.toml:3: key 'experiment[0].body' = \"round\""));
  EXPECT_TRUE(o.out.empty());
  const Outcome missing = Run("fem-reference nothing.toml");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_TRUE(Contains(missing.err, "nothing.toml: cannot read the fem-reference config"));
}

TEST_F(FemReferenceTest, MissingCcxExitsWith2) {
  Write("c.toml", kTinyConfig);
  const Outcome o = Run("fem-reference c.toml", "RAILWEAR_CCX=/nonexistent/ccx");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_TRUE(Contains(o.err,
                       "ccx (CalculiX) not found: environment variable RAILWEAR_CCX = "
                       "'/nonexistent/ccx' is not an executable file"));
  // Not on PATH (gmsh given by its path, so ccx is the one missing).
  const std::string gmsh = railwear::FindOnPath("gmsh");
  const Outcome no_path =
      Run("fem-reference c.toml", "PATH=/nonexistent RAILWEAR_GMSH='" +
                                      (gmsh.empty() ? std::string("/usr/bin/gmsh") : gmsh) + "'");
  EXPECT_EQ(no_path.exit_code, 2);
  EXPECT_TRUE(Contains(no_path.err,
                       "ccx (CalculiX) is not installed or not on PATH: install the "
                       "Debian package calculix-ccx (bash .ci/install-deps.sh), or "
                       "set RAILWEAR_CCX"));
  EXPECT_FALSE(fs::exists(dir_ / "out" / "tiny.csv"));
}

TEST_F(FemReferenceTest, UnknownOnlyNameExitsWith2) {
  Write("c.toml", kTinyConfig);
  const Outcome o = Run("fem-reference c.toml --only nope");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_TRUE(Contains(o.err, "--only nope: no such experiment in c.toml; expected one of 'tiny'"));
}

TEST_F(FemReferenceTest, TinyRunWritesCurvesCalibrationReads) {
  if (const std::string why = railwear::test::MissingFemPrograms(); !why.empty()) {
    GTEST_SKIP() << why;
  }
  Write("c.toml", kTinyConfig);
  const Outcome o = Run("fem-reference c.toml --keep-work");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_TRUE(Contains(o.out, "tiny: flat body, E = 210000 MPa, nu = 0.28"));
  EXPECT_TRUE(Contains(o.out, "written to out/tiny.csv"));
  EXPECT_TRUE(
      Contains(o.out, "half-space (Boussinesq normal, Cerruti tangential) from 1 to 10 mm"));
  EXPECT_TRUE(Contains(o.err, "fem-reference: tiny: solving normal load"));
  const railwear::DisplacementCurves c =
      railwear::ReadDisplacementCurves((dir_ / "out/tiny.csv").string());
  EXPECT_EQ(c.body, CurveBody::kFlat);
  EXPECT_GT(c.points.size(), 10u);
  for (const auto& p : c.points) {
    EXPECT_EQ(p.load, CurveLoad::kNormal);
    EXPECT_GT(p.w_m_per_N, 0.0);  // pressed into the body everywhere within 10 mm
  }
  EXPECT_TRUE(Contains(ReadFile(dir_ / "out/tiny.csv"),
                       "# supports = bottom face z = -100 mm "
                       "clamped (u = 0); every other face free"));
  EXPECT_TRUE(fs::exists(dir_ / "tiny.work" / "normal.frd"));  // --keep-work: next to the config

  // --report-only prints the comparison again from the CSV, running nothing.
  const Outcome report = Run("fem-reference c.toml --report-only", "RAILWEAR_CCX=/nonexistent");
  ASSERT_EQ(report.exit_code, 0) << report.err;
  EXPECT_TRUE(Contains(
      report.out, "tiny: " + std::to_string(c.points.size()) + " points read from out/tiny.csv"));
  EXPECT_TRUE(Contains(report.out, "normal load, axis path:"));
}

TEST_F(FemReferenceTest, ReportOnlyNeedsTheOutputs) {
  Write("c.toml", kTinyConfig);
  const Outcome o = Run("fem-reference c.toml --report-only");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_TRUE(Contains(o.err,
                       "c.toml:8: experiment 'tiny': --report-only reads its output "
                       "out/tiny.csv, which does not exist; run that experiment first"));
}

// The example configs are valid (running them takes minutes: README), and the committed
// reference data of the paper experiment is what its config says, with every curve calibration
// fits.
TEST_F(FemReferenceTest, ExampleConfigsAndCommittedReferenceData) {
  const std::string examples = std::string(RAILWEAR_SOURCE_DIR) + "/examples/fem/";
  using railwear::app::ReadFemReferenceConfig;
  EXPECT_EQ(ReadFemReferenceConfig(examples + "boussinesq_block.toml", "").experiments.size(), 4u);
  EXPECT_EQ(ReadFemReferenceConfig(examples + "mesh_convergence.toml", "").experiments.size(), 2u);
  EXPECT_EQ(ReadFemReferenceConfig(examples + "convex_height.toml", "").experiments.size(), 3u);
  const auto paper = ReadFemReferenceConfig(examples + "paper_experiment.toml", "");
  ASSERT_EQ(paper.experiments.size(), 4u);
  for (const auto& e : paper.experiments) {
    SCOPED_TRACE(e.name);
    ASSERT_TRUE(fs::exists(e.output)) << "run: railwear fem-reference " << paper.path;
    const railwear::DisplacementCurves c = railwear::ReadDisplacementCurves(e.output);
    EXPECT_EQ(c.body, e.options.body);
    EXPECT_DOUBLE_EQ(c.radius_m, e.options.radius_m);
    EXPECT_DOUBLE_EQ(c.material.poisson_ratio, 0.28);
    std::map<std::string, int> curves;
    for (const auto& p : c.points) {
      ++curves[std::string(railwear::ToString(p.load)) + "/" +
               std::string(railwear::ToString(p.path))];
    }
    for (const char* curve : {"normal/arc", "normal/axis", "axial/axis", "circumferential/arc"}) {
      EXPECT_GE(curves[curve], 20) << curve;
    }
    std::map<std::string, std::string> meta(c.metadata.begin(), c.metadata.end());
    for (const char* key : {"source", "supports", "body_length_mm", "body_width_mm",
                            "body_depth_mm", "mesh_size_at_load_mm", "nodes"}) {
      EXPECT_EQ(meta.count(key), 1u) << key;
    }
  }
}

// ccx that fails: exit code 1, the message names the log, which is kept.
TEST_F(FemReferenceTest, FailingCcxExitsWith1AndKeepsItsLog) {
  if (const std::string why = railwear::test::MissingFemPrograms(); !why.empty()) {
    GTEST_SKIP() << why;
  }
  Write("c.toml", kTinyConfig);
  const Outcome o = Run("fem-reference c.toml", "RAILWEAR_CCX=false");
  EXPECT_EQ(o.exit_code, 1);
  EXPECT_TRUE(Contains(o.err, "railwear: error: ccx (CalculiX) failed (exit code 1)"));
  const size_t at = o.err.find("log ");
  ASSERT_NE(at, std::string::npos);
  const std::string log = o.err.substr(at + 4, o.err.find(" ends with") - at - 4);
  EXPECT_TRUE(fs::exists(log)) << log;
  fs::remove_all(fs::path(log).parent_path());
  EXPECT_FALSE(fs::exists(dir_ / "out" / "tiny.csv"));
}

}  // namespace
