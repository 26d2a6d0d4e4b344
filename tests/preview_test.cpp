// `clmarch preview`: camera moves, views and edits of numbers re-render without building; a saved
// file re-renders, a broken one keeps the last picture and shows its error; the HTTP server
// answers its page, frames, pixels and state, and every other request with an error status; Ctrl-C
// stops it.
#include "common/errors.hpp"
#include "preview/preview_server.hpp"
#include "preview/preview_session.hpp"
#include "support/child_process.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>
#include <httplib.h>
#include <nlohmann/json.hpp>

#include <csignal>
#include <fstream>
#include <thread>

namespace clmarch {
namespace {

using testing::TempDir;

/// A sphere of radius RADIUS at the origin seen from z = 4, over a floor.
std::string sphere_over_floor(const std::string& radius) {
  return "camera: {position: [0, 0, 4], look_at: [0, 0, 0], fov: 40}\n"
         "render: {width: 48, height: 32, epsilon: 1e-5}\n"
         "sdf:\n  union:\n    - sphere: {radius: " +
         radius +
         ", color: [0.8, 0.3, 0.2]}\n"
         "    - plane: {normal: [0, 1, 0], offset: 1.5}\n"
         "lights: [{point: {position: [2, 3, 4]}}]\n";
}

/// Writes text to path with a modification time a second after the file's last one, so that a
/// rewrite within the same second is seen as a change.
void write_scene_later(const std::filesystem::path& path, const std::string& text) {
  std::error_code error;
  const auto before = std::filesystem::last_write_time(path, error);
  std::ofstream(path) << text;
  if (!error) std::filesystem::last_write_time(path, before + std::chrono::seconds(1));
}

/// The width and height in a PNG's header.
std::pair<int, int> png_size(const std::vector<unsigned char>& png) {
  EXPECT_GE(png.size(), 24u);
  EXPECT_EQ(std::string(png.begin() + 1, png.begin() + 4), "PNG");
  const auto word = [&](int at) { return png[at] << 24 | png[at + 1] << 16 | png[at + 2] << 8 | png[at + 3]; };
  return {word(16), word(20)};
}

class PreviewSessionTest : public ::testing::Test {
 protected:
  PreviewSessionTest() { write_scene_later(dir_ / "scene.yaml", sphere_over_floor("1")); }
  PreviewOptions options() const {
    PreviewOptions o;
    o.scene_path = (dir_ / "scene.yaml").string();
    return o;
  }
  TempDir dir_;
};

TEST_F(PreviewSessionTest, CameraMovesAndViewsNeverBuild) {
  PreviewSession session(options());
  FrameQuery query;
  query.sequence = 1;
  const std::optional<PreviewFrame> first = session.frame(query);
  ASSERT_TRUE(first);
  EXPECT_EQ(png_size(first->png), std::make_pair(48, 32));
  const auto built = first->stats.at("programs_built").get<int>();
  for (int move = 0; move < 6; ++move) {
    FrameQuery moved;
    moved.sequence = 2 + move;
    moved.camera = PreviewCamera{{0.5 * move, 1.0, 4.0}, {0, 0, 0}, {0, 1, 0}, 40.0 + move};
    moved.coarse = move % 2 == 0;
    moved.view = static_cast<PreviewView>(move % 9);
    const std::optional<PreviewFrame> frame = session.frame(moved);
    ASSERT_TRUE(frame);
    EXPECT_EQ(png_size(frame->png), moved.coarse ? std::make_pair(12, 8) : std::make_pair(48, 32));
    EXPECT_EQ(frame->stats.at("programs_built").get<int>(), built) << "move " << move;
  }
}

TEST_F(PreviewSessionTest, ThePixelReadoutIsTheLastFullFramesHit) {
  PreviewSession session(options());
  FrameQuery query;
  query.sequence = 1;
  ASSERT_TRUE(session.frame(query));
  // The ray through pixel (24, 16), half a pixel off the axis each way, meets the unit sphere at
  // its position: within the hit threshold 1e-5 (and float rounding) of radius 1, at its depth
  // from the camera at z = 4 (3.0015 for that slant).
  const nlohmann::json centre = *session.pixel(24, 16);
  EXPECT_EQ(centre.at("status"), "hit");
  EXPECT_EQ(centre.at("id"), 0.0);
  const glm::dvec3 hit(centre["position"][0], centre["position"][1], centre["position"][2]);
  EXPECT_NEAR(glm::length(hit), 1.0, 2e-5);
  EXPECT_NEAR(centre.at("depth").get<double>(), glm::length(hit - glm::dvec3(0, 0, 4)), 1e-5);
  EXPECT_NEAR(centre.at("depth").get<double>(), 3.0015, 1e-4);
  const nlohmann::json corner = *session.pixel(0, 0);
  EXPECT_TRUE(corner.at("depth").is_null()) << "the top left ray passes above everything";
  EXPECT_NE(corner.at("status"), "hit");
  EXPECT_FALSE(session.pixel(48, 0)) << "outside the frame";
}

TEST_F(PreviewSessionTest, ASavedFileReRendersABrokenOneKeepsThePicture) {
  PreviewSession session(options());
  FrameQuery query;
  query.sequence = 1;
  ASSERT_TRUE(session.frame(query));
  const auto radius_at_centre = [&] {
    const nlohmann::json p = *session.pixel(24, 16);
    return glm::length(glm::dvec3(p["position"][0], p["position"][1], p["position"][2]));
  };
  EXPECT_NEAR(radius_at_centre(), 1.0, 2e-5);
  EXPECT_FALSE(session.refresh()) << "nothing changed";

  write_scene_later(dir_ / "scene.yaml", sphere_over_floor("0.5"));
  EXPECT_TRUE(session.refresh());
  nlohmann::json state = session.state();
  EXPECT_EQ(state.at("version"), 2);
  EXPECT_EQ(state.at("error"), "");
  query.sequence = 2;
  const std::optional<PreviewFrame> edited = session.frame(query);
  ASSERT_TRUE(edited);
  EXPECT_NEAR(radius_at_centre(), 0.5, 2e-5) << "the edited sphere";
  const auto built = edited->stats.at("programs_built").get<int>();
  EXPECT_LE(built, 2) << "a number's edit builds at most once more";

  write_scene_later(dir_ / "scene.yaml", "camera: {fov: 40\nsdf: {sphere: {}}\n");
  EXPECT_TRUE(session.refresh());
  state = session.state();
  EXPECT_EQ(state.at("version"), 3);
  const std::string error = state.at("error");
  EXPECT_EQ(error.rfind((dir_ / "scene.yaml").string() + ":", 0), 0u) << error;
  query.sequence = 3;
  ASSERT_TRUE(session.frame(query)) << "the last good scene still renders";
  EXPECT_NEAR(radius_at_centre(), 0.5, 2e-5);

  write_scene_later(dir_ / "scene.yaml", sphere_over_floor("0.75"));
  EXPECT_TRUE(session.refresh());
  EXPECT_EQ(session.state().at("error"), "");
  query.sequence = 4;
  const std::optional<PreviewFrame> fixed = session.frame(query);
  ASSERT_TRUE(fixed);
  EXPECT_NEAR(radius_at_centre(), 0.75, 2e-5);
  EXPECT_EQ(fixed->stats.at("programs_built").get<int>(), built) << "no build for a third value";
}

TEST_F(PreviewSessionTest, ANewerFrameSupersedesAnOlderOne) {
  PreviewSession session(options());
  FrameQuery newer;
  newer.sequence = 7;
  ASSERT_TRUE(session.frame(newer));
  FrameQuery older;
  older.sequence = 6;
  EXPECT_FALSE(session.frame(older));
}

TEST(PreviewCamera, CamerasThatCannotRenderAreRefused) {
  const auto error_of = [](const PreviewCamera& camera) {
    try {
      check_preview_camera(camera);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(error_of({{0, 0, 4}, {0, 0, 0}, {0, 1, 0}, 180.0}), "camera: fov must be in (0, 180) degrees (got 180)");
  EXPECT_EQ(error_of({{0, 0, 4}, {0, 0, 4}, {0, 1, 0}, 40.0}), "camera: position and look_at must differ");
  EXPECT_EQ(error_of({{0, 4, 0}, {0, 0, 0}, {0, 1, 0}, 40.0}),
            "camera: up must not be along the view direction (or zero)");
  EXPECT_EQ(error_of({{0, 0, NAN}, {0, 0, 0}, {0, 1, 0}, 40.0}), "camera: every number must be finite");
  EXPECT_EQ(error_of({{0, 0, 4}, {0, 0, 0}, {0, 1, 0}, 40.0}), "no error");
}

class PreviewServerTest : public PreviewSessionTest {
 protected:
  PreviewServerTest() : session_(options()), server_(session_), port_(server_.bind("127.0.0.1", 0)) {
    thread_ = std::thread([this] { server_.serve(); });
  }
  ~PreviewServerTest() override {
    server_.stop();
    thread_.join();
  }
  httplib::Result get(const std::string& path) {
    httplib::Client client("127.0.0.1", port_);
    return client.Get(path);
  }
  PreviewSession session_;
  PreviewServer server_;
  int port_;
  std::thread thread_;
};

TEST_F(PreviewServerTest, ServesThePageFramesPixelsAndState) {
  const httplib::Result page = get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_EQ(page->get_header_value("Content-Type"), "text/html; charset=utf-8");
  EXPECT_NE(page->body.find("<img id=\"frame\""), std::string::npos);
  EXPECT_EQ(page->body.find("http://"), std::string::npos) << "nothing fetched from elsewhere";
  EXPECT_EQ(page->body.find("https://"), std::string::npos);

  const httplib::Result frame = get("/frame?seq=1&view=normals&coarse=0&t=0&pos=1,1,4&look=0,0,0&up=0,1,0&fov=45");
  ASSERT_TRUE(frame);
  ASSERT_EQ(frame->status, 200) << frame->body;
  EXPECT_EQ(frame->get_header_value("Content-Type"), "image/png");
  const std::vector<unsigned char> png(frame->body.begin(), frame->body.end());
  EXPECT_EQ(png_size(png), std::make_pair(48, 32));
  const nlohmann::json stats = nlohmann::json::parse(frame->get_header_value("X-Clmarch-Stats"));
  EXPECT_EQ(stats.at("view"), "normals");

  const httplib::Result pixel = get("/pixel?x=24&y=16");
  ASSERT_TRUE(pixel);
  EXPECT_EQ(pixel->status, 200);
  EXPECT_EQ(nlohmann::json::parse(pixel->body).at("status"), "hit");
  const httplib::Result state = get("/state");
  ASSERT_TRUE(state);
  EXPECT_EQ(nlohmann::json::parse(state->body).at("version"), 1);
  // The newest frame number asked for: a page loaded later numbers its frames after it.
  EXPECT_EQ(nlohmann::json::parse(state->body).at("sequence"), 1);
}

TEST_F(PreviewServerTest, BadRequestsGetAnErrorStatusAndOneLine) {
  const struct {
    std::string path;
    int status;
    std::string message;
  } cases[] = {
      {"/frame", 400, "seq: required"},
      {"/frame?seq=x", 400, "seq: expected a whole number (got 'x')"},
      {"/frame?seq=1&view=xray", 400, "view: unknown view 'xray'"},
      {"/frame?seq=1&coarse=2", 400, "coarse: expected 0 or 1 (got '2')"},
      {"/frame?seq=1&pos=1,2&look=0,0,0&up=0,1,0&fov=45", 400, "pos: expected three numbers x,y,z (got '1,2')"},
      {"/frame?seq=1&pos=1,2,3", 400, "pos, look, up and fov: give all four or none"},
      {"/frame?seq=1&pos=0,0,4&look=0,0,0&up=0,1,0&fov=200", 400, "camera: fov must be in (0, 180)"},
      {"/frame?seq=1&t=inf", 400, "t: expected a finite number (got 'inf')"},
      {"/frame?seq=1&zoom=2", 400, "unknown parameter 'zoom'"},
      {"/frame?seq=1&seq=2", 400, "seq: given twice"},
      {"/state?x=1", 400, "/state takes no parameters"},
      {"/pixel?x=1", 400, "x and y: required"},
      {"/pixel?x=a&y=1", 400, "x: expected a finite number (got 'a')"},
      {"/pixel?x=0&y=0", 404, "no such pixel in the last full frame"},
      {"/nope", 404, "no such page: /nope"},
      {"/../../etc/passwd", 404, "no such page"},
      {"/scene.yaml", 404, "no such page"},
      {"/" + std::string(10000, 'a'), 414, "address too long"},
  };
  for (const auto& c : cases) {
    const httplib::Result result = get(c.path);
    ASSERT_TRUE(result) << c.path;
    EXPECT_EQ(result->status, c.status) << c.path.substr(0, 80) << ": " << result->body;
    EXPECT_NE(result->body.find(c.message), std::string::npos) << c.path.substr(0, 80) << ": " << result->body;
    EXPECT_EQ(std::count(result->body.begin(), result->body.end(), '\n'), 1) << result->body;
  }
  httplib::Client client("127.0.0.1", port_);
  const httplib::Result post = client.Post("/frame", "x", "text/plain");
  ASSERT_TRUE(post);
  EXPECT_EQ(post->status, 405);
  const httplib::Result big = client.Post("/", std::string(100000, 'x'), "text/plain");
  ASSERT_TRUE(big);
  EXPECT_EQ(big->status, 413);
  const httplib::Result alive = get("/");
  ASSERT_TRUE(alive);
  EXPECT_EQ(alive->status, 200) << "the server still answers";
}

TEST(PreviewCommand, ServesUntilCtrlC) {
  TempDir dir;
  write_scene_later(dir / "scene.yaml", sphere_over_floor("1"));
  testing::ClmarchProcess preview({"preview", (dir / "scene.yaml").string(), "--port", "0"});
  ASSERT_TRUE(preview.wait_for_stderr("(Ctrl-C stops it)", std::chrono::seconds(60))) << preview.err();
  const std::string err = preview.err();
  const std::size_t at = err.find("http://127.0.0.1:");
  ASSERT_NE(at, std::string::npos) << err;
  const int port = std::stoi(err.substr(at + 17));
  httplib::Client client("127.0.0.1", port);
  const httplib::Result frame = client.Get("/frame?seq=1&coarse=1");
  ASSERT_TRUE(frame);
  EXPECT_EQ(frame->status, 200) << frame->body;
  preview.send_signal(SIGINT);
  EXPECT_EQ(preview.wait(std::chrono::seconds(30)), 130);
  EXPECT_NE(preview.err().find("clmarch: preview stopped"), std::string::npos) << preview.err();
}

TEST(PreviewCommand, BadOptionsAreOneLine) {
  const std::string torus = testing::source_path("scenes/torus.yaml").string();
  for (const auto& [args, expected] : std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"preview", torus, "--port", "70000"}, "--port"},
           {{"preview", torus, "--size", "0x10"}, "--size 0x10"},
           {{"preview", "/no/such/scene.yaml"}, "/no/such/scene.yaml"},
           {{"preview", torus, "--host", "256.1.1.1", "--port", "0"}, "--host 256.1.1.1"},
       }) {
    const testing::CommandResult result = testing::run_clmarch(args);
    EXPECT_EQ(result.exit_code, kExitBadInput) << result.err;
    EXPECT_NE(result.err.find(expected), std::string::npos) << result.err;
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  }
}

}  // namespace
}  // namespace clmarch
