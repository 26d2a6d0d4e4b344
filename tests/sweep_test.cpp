// `clmarch bench --sweep`: the sweep syntax and its errors, the combinations, and a tiny sweep whose
// CSV has the documented columns and whose errors order as the settings say they must. Timings are
// only checked to be present, never against thresholds: the machine is shared.
#include "bench/sweep_csv.hpp"
#include "bench/sweep_spec.hpp"
#include "common/errors.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <map>

namespace clmarch {
namespace {

using testing::run_clmarch;
using testing::source_path;

TEST(SweepSpec, ParsesSceneAndKernelKeys) {
  const SweepAxis epsilon = parse_sweep_axis("render.epsilon=1e-2,1e-3");
  EXPECT_EQ(epsilon.key, "render.epsilon");
  EXPECT_EQ(epsilon.values, (std::vector<std::string>{"1e-2", "1e-3"}));
  const SweepAxis lanes = parse_sweep_axis("lanes=1,16");
  EXPECT_EQ(lanes.values, (std::vector<std::string>{"1", "16"}));
  // Commas inside brackets belong to the YAML value.
  const SweepAxis position = parse_sweep_axis("camera.position=[0,0,5],[1,2,3]");
  EXPECT_EQ(position.values, (std::vector<std::string>{"[0,0,5]", "[1,2,3]"}));
  EXPECT_EQ(parse_sweep_axis("precision=float,double").values.size(), 2u);
  EXPECT_EQ(parse_sweep_axis("fast_math=on,off").values.size(), 2u);
  EXPECT_EQ(parse_sweep_axis("native_math=on").values.size(), 1u);
}

TEST(SweepSpec, RejectsBadSyntaxUnknownKeysAndValues) {
  for (const char* text : {"render.epsilon", "=1,2", "render.epsilon=", "render.epsilon=1e-3,,1e-4", "epsilon=1e-3",
                           "lanes=3", "precision=half", "fast_math=yes", "native_math=1"}) {
    EXPECT_THROW(parse_sweep_axis(text), InputError) << text;
  }
  try {
    parse_sweep_axis("colour=1,2");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown key 'colour'"), std::string::npos) << e.what();
  }
}

TEST(SweepSpec, ProductAndOneAtATime) {
  const std::vector<SweepAxis> axes = {parse_sweep_axis("render.epsilon=1e-2,1e-3"), parse_sweep_axis("lanes=1,4,16")};
  const std::vector<SweepCombination> product = expand_sweep(axes);
  ASSERT_EQ(product.size(), 6u);
  EXPECT_EQ(combination_label(product[0]), "render.epsilon=1e-2 lanes=1");
  EXPECT_EQ(combination_label(product[1]), "render.epsilon=1e-2 lanes=4");
  EXPECT_EQ(combination_label(product[5]), "render.epsilon=1e-3 lanes=16");
  EXPECT_EQ(scene_sets(product[5]), (std::vector<std::string>{"render.epsilon=1e-3"}));

  const std::vector<SweepCombination> each = expand_one_at_a_time(axes);
  ASSERT_EQ(each.size(), 6u);  // the base, then 2 + 3 single settings
  EXPECT_EQ(combination_label(each[0]), "");
  EXPECT_EQ(combination_label(each[2]), "render.epsilon=1e-3");
  EXPECT_EQ(combination_label(each[3]), "lanes=1");

  EXPECT_THROW(expand_sweep({axes[0], axes[0]}), InputError);
}

TEST(SweepSpec, AtMostAThousandCombinations) {
  const auto axis = [](const std::string& key, int values) {
    SweepAxis a{key, {}};
    for (int i = 1; i <= values; ++i) a.values.push_back(std::to_string(i));
    return a;
  };
  const std::string too_many = "--sweep: more than 1000 combinations; sweep fewer values";
  EXPECT_EQ(expand_sweep({axis("render.max_steps", 10), axis("render.width", 10), axis("render.height", 10)}).size(),
            1000u);
  try {
    expand_sweep({axis("render.max_steps", 10), axis("render.width", 10), axis("render.height", 11)});
    ADD_FAILURE() << "1100 combinations";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), too_many);
  }
  EXPECT_EQ(expand_one_at_a_time({axis("render.max_steps", 999)}).size(), 1000u) << "the base and 999 settings";
  try {
    expand_one_at_a_time({axis("render.max_steps", 500), axis("render.width", 500)});
    ADD_FAILURE() << "1001 combinations";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), too_many);
  }
}

TEST(SweepSpec, KernelKeysSetTheOptions) {
  const OpenClOptions options =
      with_kernel_settings({}, {{"lanes", "8"}, {"precision", "double"}, {"fast_math", "on"}, {"render.epsilon", "1"}});
  EXPECT_EQ(options.lanes, 8);
  EXPECT_EQ(options.variant.precision, Precision::Double);
  EXPECT_TRUE(options.variant.fast_math);
  EXPECT_FALSE(options.variant.native_math);
  EXPECT_THROW(with_kernel_settings({}, {{"precision", "double"}, {"native_math", "on"}}), InputError);
}

TEST(SweepCommand, BadInputIsOneLineAndExitCode2) {
  testing::TempDir dir;
  const std::string torus = source_path("scenes/torus.yaml").string();
  const std::string csv = (dir / "s.csv").string();
  for (const std::vector<std::string>& extra :
       {std::vector<std::string>{"--sweep", "render.epsilon", "--csv", csv},
        {"--sweep", "colour=1,2", "--csv", csv},
        {"--sweep", "lanes=3", "--csv", csv},
        {"--sweep", "render.epsilom=1e-3", "--csv", csv},
        {"--sweep", "render.epsilon=-1", "--csv", csv},
        {"--sweep", "render.epsilon=1e-3"},
        {"--csv", csv},
        {"--sweep", "render.epsilon=1e-3", "--csv", "/no/such/folder/s.csv"},
        {"--sweep", "precision=double", "--sweep", "native_math=on", "--csv", csv},
        {"--set", "render.precision=double", "--sweep", "native_math=on", "--csv", csv},
        {"--sweep", "render.width=16,32", "--csv", csv},
        {"--sweep", "lanes=1,1", "--csv", csv}}) {
    std::vector<std::string> args = {"bench", torus, "--size", "16x9"};
    args.insert(args.end(), extra.begin(), extra.end());
    const testing::CommandResult r = run_clmarch(args);
    EXPECT_EQ(r.exit_code, kExitBadInput) << extra[1] << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  // A swept value the loader refuses is named as the sweep's, not as a --set the user never gave.
  const testing::CommandResult negative =
      run_clmarch({"bench", torus, "--size", "16x9", "--sweep", "render.epsilon=1e-3,-1", "--csv", csv});
  EXPECT_EQ(negative.err.find("--sweep render.epsilon=-1: "), 0u) << negative.err;
  EXPECT_TRUE(dir.files().empty());
}

/// A CSV line's fields; a quoted field may hold commas (no quotes inside quotes in these tests).
std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (char c : line) {
    if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  return fields;
}

/// The CSV as rows of column name -> text.
std::vector<std::map<std::string, std::string>> read_csv(const std::filesystem::path& path, std::string* header) {
  std::ifstream in(path);
  std::getline(in, *header);
  const std::vector<std::string> names = csv_fields(*header);
  std::vector<std::map<std::string, std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    const std::vector<std::string> fields = csv_fields(line);
    EXPECT_EQ(fields.size(), names.size()) << line;
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < std::min(fields.size(), names.size()); ++i) row[names[i]] = fields[i];
    rows.push_back(row);
  }
  return rows;
}

TEST(SweepCommand, TinySweepWritesOrderedErrors) {
  testing::TempDir dir;
  const std::filesystem::path csv = dir / "torus.csv";
  const std::string torus = source_path("scenes/torus.yaml").string();
  const testing::CommandResult r =
      run_clmarch({"bench", torus, "--size", "48x27", "--repeat", "2", "-q", "--sweep", "render.epsilon=1e-2,1e-5",
                   "--sweep", "lanes=1,16", "--csv", csv.string()});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  std::string header;
  const auto rows = read_csv(csv, &header);
  std::string expected_header;
  for (const std::string& c : sweep_csv_columns()) expected_header += (expected_header.empty() ? "" : ",") + c;
  EXPECT_EQ(header, expected_header);
  ASSERT_EQ(rows.size(), 4u);
  std::map<std::string, std::map<std::string, std::string>> by;
  for (const auto& row : rows) {
    by[row.at("combination")] = row;
    EXPECT_EQ(row.at("width"), "48");
    EXPECT_GT(std::stod(row.at("kernel_ms")), 0.0);
    EXPECT_GT(std::stod(row.at("steps_per_pixel")), 0.0);
    EXPECT_EQ(row.at("precision"), "float");
    EXPECT_EQ(row.at("defaults"), "0");  // the scene's epsilon is 1e-4
    EXPECT_EQ(row.at("samples"), "1");
    EXPECT_EQ(row.at("adaptive"), "true");
    EXPECT_EQ(row.at("reference_samples"), "1") << "a sweep of march settings compares centre rays";
  }
  for (const char* lanes : {"1", "16"}) {
    const auto& coarse = by.at(std::string("render.epsilon=1e-2 lanes=") + lanes);
    const auto& fine = by.at(std::string("render.epsilon=1e-5 lanes=") + lanes);
    EXPECT_EQ(coarse.at("lanes"), lanes);
    EXPECT_EQ(std::stod(coarse.at("epsilon")), 1e-2);
    // A ten times coarser threshold stops rays further in front of the surface in fewer steps.
    EXPECT_GT(std::stod(coarse.at("depth_rms")), 10.0 * std::stod(fine.at("depth_rms"))) << lanes;
    EXPECT_GT(std::stod(coarse.at("depth_p99")), std::stod(fine.at("depth_p99"))) << lanes;
    EXPECT_LT(std::stod(coarse.at("steps_per_pixel")), std::stod(fine.at("steps_per_pixel"))) << lanes;
    EXPECT_LT(std::stod(coarse.at("color_psnr_db")), std::stod(fine.at("color_psnr_db"))) << lanes;
  }

  // --append adds rows under the same header; the base row of a one-at-a-time sweep has the
  // defaults, and a value equal to the scene's (epsilon 1e-4) is not rendered twice.
  const testing::CommandResult more =
      run_clmarch({"bench", torus, "--size", "48x27", "--repeat", "1", "-q", "--one-at-a-time", "--sweep",
                   "render.epsilon=1e-4,1e-3", "--append", "--csv", csv.string()});
  ASSERT_EQ(more.exit_code, kExitOk) << more.err;
  const auto all = read_csv(csv, &header);
  ASSERT_EQ(all.size(), 6u);
  EXPECT_EQ(all[4].at("combination"), "");
  EXPECT_EQ(all[4].at("defaults"), "1");
  EXPECT_EQ(all[5].at("combination"), "render.epsilon=1e-3");
  EXPECT_EQ(all[5].at("defaults"), "0");

  // Under --set the base is not the defaults; the row that restores the scene's own value is.
  const testing::CommandResult cone =
      run_clmarch({"bench", torus, "--size", "48x27", "--repeat", "1", "-q", "--one-at-a-time", "--set",
                   "render.epsilon=1e-3", "--sweep", "render.epsilon=1e-4", "--append", "--csv", csv.string()});
  ASSERT_EQ(cone.exit_code, kExitOk) << cone.err;
  const auto with_set = read_csv(csv, &header);
  ASSERT_EQ(with_set.size(), 8u);
  EXPECT_EQ(with_set[6].at("combination"), "");
  EXPECT_EQ(with_set[6].at("defaults"), "0");
  EXPECT_EQ(with_set[7].at("defaults"), "1");

  // An empty file takes the rows and their header, as a missing one does.
  std::ofstream(dir / "empty.csv").flush();
  const testing::CommandResult empty = run_clmarch({"bench", torus, "--size", "16x9", "--repeat", "1", "-q", "--sweep",
                                                    "lanes=16", "--append", "--csv", (dir / "empty.csv").string()});
  ASSERT_EQ(empty.exit_code, kExitOk) << empty.err;
  EXPECT_EQ(read_csv(dir / "empty.csv", &header).size(), 1u);
  EXPECT_EQ(header, expected_header);

  std::ofstream(dir / "other.csv") << "a,b\n1,2\n";
  const testing::CommandResult mismatch = run_clmarch(
      {"bench", torus, "--size", "16x9", "--sweep", "lanes=1", "--append", "--csv", (dir / "other.csv").string()});
  EXPECT_EQ(mismatch.exit_code, kExitBadInput) << mismatch.err;
}

// A sweep of the anti-aliasing compares with a 256-ray reference (issue 28): on white on black
// under ambient light, 16 rays a pixel are closer to it than one by more than the coverage's
// sampling error (RMS 0.27 at one ray against 0.046 at 16 over the rim, docs/performance.md: the
// PSNR over the image gains 20 log10(0.27 / 0.046) = 15 dB; 6 dB leaves room for the rim's share).
// Against a one-ray reference the one-ray render would be the closer.
TEST(SweepCommand, AntialiasingIsComparedWithAConvergedImage) {
  testing::TempDir dir;
  std::ofstream(dir / "disc.yaml") << "camera: {position: [0, 0, 5], look_at: [0, 0, 0], fov: 45}\n"
                                      "shading: {ambient: 1, background: 0}\n"
                                      "sdf: {sphere: {radius: 1}}\n";
  const std::filesystem::path csv = dir / "disc.csv";
  const testing::CommandResult r =
      run_clmarch({"bench", (dir / "disc.yaml").string(), "--size", "48x48", "--repeat", "1", "-q", "--sweep",
                   "render.samples=1,16", "--sweep", "render.adaptive=true,false", "--csv", csv.string()});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  std::string header;
  const auto rows = read_csv(csv, &header);
  ASSERT_EQ(rows.size(), 4u);
  std::map<std::string, double> psnr;
  for (const auto& row : rows) {
    EXPECT_EQ(row.at("reference_samples"), "256");
    EXPECT_EQ(row.at("combination"), "render.samples=" + row.at("samples") + " render.adaptive=" + row.at("adaptive"));
    psnr[row.at("combination")] = std::stod(row.at("color_psnr_db"));
  }
  for (const char* adaptive : {"true", "false"}) {
    const std::string suffix = std::string(" render.adaptive=") + adaptive;
    EXPECT_GT(psnr.at("render.samples=16" + suffix), psnr.at("render.samples=1" + suffix) + 6.0) << adaptive;
  }
}

// A key that changes the picture (the camera) gets a reference of its own picture: every row's depth
// error is the march's, though the two views see the torus from sides whose depths differ by up to
// ~2 (compared with the first view's reference, the second camera's rows measured depth RMS 1.8-2.8
// on a torus of radius 1). A ray stops where the distance falls below epsilon, epsilon / cos(i)
// short of the surface along the ray at incidence i: a few epsilon in RMS over a torus seen whole
// (1.6 and 2.5 here), and in proportion to epsilon.
TEST(SweepCommand, EachPictureIsComparedWithItsOwnReference) {
  testing::TempDir dir;
  const std::filesystem::path csv = dir / "camera.csv";
  const testing::CommandResult r = run_clmarch({"bench", source_path("scenes/torus.yaml").string(), "--size", "48x27",
                                                "--repeat", "1", "-q", "--sweep", "camera.position=[-2,4,4],[0,0.5,5]",
                                                "--sweep", "render.epsilon=1e-3,1e-4", "--csv", csv.string()});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  std::string header;
  const auto rows = read_csv(csv, &header);
  ASSERT_EQ(rows.size(), 4u);
  std::map<std::string, double> depth_rms;
  for (const auto& row : rows) {
    depth_rms[row.at("combination")] = std::stod(row.at("depth_rms"));
    EXPECT_LT(std::stod(row.at("depth_rms")), 5.0 * std::stod(row.at("epsilon"))) << row.at("combination");
    EXPECT_GT(std::stoi(row.at("both_hit")), 50) << row.at("combination");
  }
  for (const char* camera : {"camera.position=[-2,4,4]", "camera.position=[0,0.5,5]"}) {
    const std::string view(camera);
    EXPECT_GT(depth_rms.at(view + " render.epsilon=1e-3"), 5.0 * depth_rms.at(view + " render.epsilon=1e-4")) << view;
  }
}

// The sweep compares its renders without step-count occlusion, but the automatic choices stay those
// of the scene as it renders: a sphere on a floor (unbounded) with occlusion renders with neither
// the cone pass nor over-relaxation, which the same scene without occlusion would get. Its sweep row
// marches exactly as the render does.
TEST(SweepCommand, AutomaticChoicesAreThoseOfTheRender) {
  testing::TempDir dir;
  const std::string scene = (dir / "floor.yaml").string();
  std::ofstream(scene) << "camera: {position: [0, 1.5, 4], look_at: [0, 0.5, 0]}\n"
                          "render: {width: 48, height: 27}\n"
                          "sdf: {union: [{sphere: {center: [0, 1, 0]}}, {plane: {}}]}\n"
                          "shading: {step_ao: 2000}\n";
  const testing::CommandResult render =
      run_clmarch({"render", scene, "--stats", "-q", "-o", (dir / "floor.png").string()});
  ASSERT_EQ(render.exit_code, kExitOk) << render.err;
  const double render_steps = nlohmann::json::parse(render.out)["steps"];
  const std::filesystem::path csv = dir / "floor.csv";
  const testing::CommandResult sweep =
      run_clmarch({"bench", scene, "--repeat", "1", "-q", "--sweep", "lanes=16", "--csv", csv.string()});
  ASSERT_EQ(sweep.exit_code, kExitOk) << sweep.err;
  std::string header;
  const auto rows = read_csv(csv, &header);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].at("over_relaxation"), "1");
  // The CSV's 7 significant digits: within half a step of the render's integer count.
  EXPECT_NEAR(std::stod(rows[0].at("steps_per_pixel")) * 48 * 27, render_steps, 0.5);

  // Without occlusion the render itself takes the cone pass and omega 1.2, and so does its row.
  const testing::CommandResult plain = run_clmarch({"bench", scene, "--repeat", "1", "-q", "--set", "shading.step_ao=0",
                                                    "--sweep", "lanes=16", "--append", "--csv", csv.string()});
  ASSERT_EQ(plain.exit_code, kExitOk) << plain.err;
  const auto both = read_csv(csv, &header);
  ASSERT_EQ(both.size(), 2u);
  EXPECT_EQ(both[1].at("over_relaxation"), "1.2");
  EXPECT_LT(std::stod(both[1].at("steps_per_pixel")), std::stod(rows[0].at("steps_per_pixel")));

  // One at a time, a value that auto chose already restates the base and is not rendered again.
  const std::filesystem::path around = dir / "around.csv";
  const testing::CommandResult one =
      run_clmarch({"bench", scene, "--repeat", "1", "-q", "--one-at-a-time", "--sweep", "render.over_relaxation=1,1.2",
                   "--sweep", "render.coarse_pass=none,cone", "--csv", around.string()});
  ASSERT_EQ(one.exit_code, kExitOk) << one.err;
  const auto cases = read_csv(around, &header);
  ASSERT_EQ(cases.size(), 3u);
  EXPECT_EQ(cases[0].at("combination"), "");
  EXPECT_EQ(cases[0].at("defaults"), "1");
  EXPECT_EQ(cases[1].at("combination"), "render.over_relaxation=1.2");
  EXPECT_EQ(cases[2].at("combination"), "render.coarse_pass=cone");
  EXPECT_LT(std::stod(cases[2].at("steps_per_pixel")), std::stod(cases[0].at("steps_per_pixel")));
}

}  // namespace
}  // namespace clmarch
