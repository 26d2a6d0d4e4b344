// Routes of the preview server.
#include "preview/preview_server.hpp"

#include "common/errors.hpp"
#include "preview/preview_page.hpp"

#include <fmt/format.h>
#include <httplib.h>

#include <charconv>
#include <set>

namespace clmarch {
namespace {

/// Largest request body taken: the page sends none.
constexpr std::size_t kMaxPayload = 64 * 1024;

double number_of(const std::string& text, const std::string& name) {
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value))
    throw InputError(fmt::format("{}: expected a finite number (got '{}')", name, text));
  return value;
}

glm::dvec3 vec3_of(const std::string& text, const std::string& name) {
  glm::dvec3 v(0.0);
  std::size_t start = 0;
  for (int axis = 0; axis < 3; ++axis) {
    const std::size_t comma = text.find(',', start);
    const bool last = axis == 2;
    if (last != (comma == std::string::npos))
      throw InputError(fmt::format("{}: expected three numbers x,y,z (got '{}')", name, text));
    v[axis] = number_of(text.substr(start, last ? std::string::npos : comma - start), name);
    start = comma + 1;
  }
  return v;
}

void send_error(httplib::Response& response, int status, const std::string& message) {
  response.status = status;
  response.set_content(one_line(message) + "\n", "text/plain; charset=utf-8");
}

}  // namespace

FrameQuery parse_frame_query(const std::multimap<std::string, std::string>& params) {
  static const std::set<std::string> known = {"seq", "view", "coarse", "t", "pos", "look", "up", "fov"};
  for (const auto& [name, value] : params) {
    if (!known.count(name)) throw InputError(fmt::format("unknown parameter '{}'", name));
    if (params.count(name) > 1) throw InputError(fmt::format("{}: given twice", name));
  }
  const auto get = [&](const char* name) -> std::optional<std::string> {
    const auto it = params.find(name);
    return it == params.end() ? std::nullopt : std::optional<std::string>(it->second);
  };
  FrameQuery query;
  const std::optional<std::string> seq = get("seq");
  if (!seq) throw InputError("seq: required (the page's number of the frame)");
  const auto [end, error] = std::from_chars(seq->data(), seq->data() + seq->size(), query.sequence);
  if (error != std::errc() || end != seq->data() + seq->size())
    throw InputError(fmt::format("seq: expected a whole number (got '{}')", *seq));
  if (const auto view = get("view")) {
    const std::optional<PreviewView> chosen = preview_view_from_name(*view);
    if (!chosen) throw InputError(fmt::format("view: unknown view '{}'", *view));
    query.view = *chosen;
  }
  if (const auto coarse = get("coarse")) {
    if (*coarse != "0" && *coarse != "1") throw InputError(fmt::format("coarse: expected 0 or 1 (got '{}')", *coarse));
    query.coarse = *coarse == "1";
  }
  if (const auto t = get("t")) query.time = number_of(*t, "t");
  const int camera_keys =
      static_cast<int>(params.count("pos") + params.count("look") + params.count("up") + params.count("fov"));
  if (camera_keys != 0 && camera_keys != 4) throw InputError("pos, look, up and fov: give all four or none");
  if (camera_keys == 4) {
    PreviewCamera camera;
    camera.position = vec3_of(*get("pos"), "pos");
    camera.look_at = vec3_of(*get("look"), "look");
    camera.up = vec3_of(*get("up"), "up");
    camera.fov_degrees = number_of(*get("fov"), "fov");
    check_preview_camera(camera);
    query.camera = camera;
  }
  return query;
}

struct PreviewServer::Impl {
  httplib::Server server;
};

PreviewServer::PreviewServer(PreviewSession& session) : impl_(std::make_unique<Impl>()) {
  httplib::Server& server = impl_->server;
  PreviewSession& s = session;
  server.set_payload_max_length(kMaxPayload);
  // The response's headers and body go out in two writes: with Nagle's algorithm on, the body
  // waited for the browser's delayed ACK of the headers on its kept-alive connection, 40 ms a
  // frame (scripts/preview-bench.py --browser: drag to coarse picture 50 ms on the torus, whose
  // frame renders in under 1 ms). Do not turn it back on.
  server.set_tcp_nodelay(true);
  server.Get("/", [](const httplib::Request&, httplib::Response& response) {
    response.set_header("Cache-Control", "no-store");
    response.set_content(preview_page(), "text/html; charset=utf-8");
  });
  server.Get("/state", [&s](const httplib::Request& request, httplib::Response& response) {
    if (!request.params.empty()) return send_error(response, 400, "/state takes no parameters");
    response.set_content(s.state().dump(), "application/json");
  });
  server.Get("/frame", [&s](const httplib::Request& request, httplib::Response& response) {
    const FrameQuery query = parse_frame_query(request.params);
    const std::optional<PreviewFrame> frame = s.frame(query);
    if (!frame) return send_error(response, 409, fmt::format("frame {} superseded by a newer one", query.sequence));
    response.set_header("X-Clmarch-Stats", frame->stats.dump());
    response.set_header("Cache-Control", "no-store");
    response.set_content(std::string(frame->png.begin(), frame->png.end()), "image/png");
  });
  server.Get("/pixel", [&s](const httplib::Request& request, httplib::Response& response) {
    for (const auto& [name, value] : request.params) {
      if (name != "x" && name != "y") return send_error(response, 400, fmt::format("unknown parameter '{}'", name));
    }
    if (!request.has_param("x") || !request.has_param("y")) return send_error(response, 400, "x and y: required");
    const double x = number_of(request.get_param_value("x"), "x");
    const double y = number_of(request.get_param_value("y"), "y");
    const std::optional<nlohmann::json> values =
        x == std::floor(x) && y == std::floor(y) && std::abs(x) < 1e6 && std::abs(y) < 1e6
            ? s.pixel(static_cast<int>(x), static_cast<int>(y))
            : std::nullopt;
    if (!values) return send_error(response, 404, "no such pixel in the last full frame");
    response.set_content(values->dump(), "application/json");
  });
  // Other methods on any path: not allowed (nothing here takes a body or changes state).
  const auto not_allowed = [](const httplib::Request& request, httplib::Response& response) {
    send_error(response, 405, fmt::format("{} is not allowed: the preview answers GET only", request.method));
  };
  server.Post(".*", not_allowed);
  server.Put(".*", not_allowed);
  server.Patch(".*", not_allowed);
  server.Delete(".*", not_allowed);
  server.Options(".*", not_allowed);
  server.set_exception_handler([](const httplib::Request&, httplib::Response& response, std::exception_ptr error) {
    try {
      std::rethrow_exception(error);
    } catch (const InputError& e) {
      send_error(response, 400, e.what());
    } catch (const std::exception& e) {
      send_error(response, 500, e.what());
    }
  });
  server.set_error_handler([](const httplib::Request& request, httplib::Response& response) {
    // Handlers' own errors keep their message; the library's (404, 413, 414) get one.
    if (!response.body.empty()) return;
    const std::string what = response.status == 404   ? fmt::format("no such page: {}", request.path)
                             : response.status == 413 ? "request too large"
                             : response.status == 414 ? "address too long"
                                                      : "bad request";
    send_error(response, response.status, what);
  });
}

PreviewServer::~PreviewServer() = default;

int PreviewServer::bind(const std::string& host, int port) {
  httplib::Server& server = impl_->server;
  const int bound = port == 0 ? server.bind_to_any_port(host) : (server.bind_to_port(host, port) ? port : -1);
  if (bound < 0) {
    throw InputError(
        fmt::format("--host {} --port {}: cannot listen there (in use, not an address of this machine, or not allowed)",
                    host, port));
  }
  return bound;
}

bool PreviewServer::serve() { return impl_->server.listen_after_bind(); }

void PreviewServer::stop() { impl_->server.stop(); }

}  // namespace clmarch
