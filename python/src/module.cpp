// The _clmarch extension: scenes, render sessions, fields, checks, benchmarks and devices of the
// core library (host/api/) for the Python package clmarch (python/clmarch/__init__.py), which
// gives them their documented signatures. Long calls release the GIL and stop on Ctrl-C.
#include "frame_arrays.hpp"
#include "interrupt_scope.hpp"

#include "api/check.hpp"
#include "api/field.hpp"
#include "api/render_session.hpp"
#include "api/scene_request.hpp"
#include "api/stats_json.hpp"
#include "bench/bench_report.hpp"
#include "cl/device_program.hpp"
#include "cl/devices.hpp"
#include "common/cancellation.hpp"
#include "common/errors.hpp"
#include "common/log.hpp"
#include "common/progress.hpp"
#include "mesh/scene_mesh.hpp"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <fmt/format.h>

#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace py = pybind11;

namespace clmarch::python {
namespace {

/// A loaded scene with the request it came from, so that a render with other overrides, another
/// time or size loads it again.
struct PyScene {
  SceneRequest request;
  Scene scene;
};

using Overrides = std::vector<std::pair<std::string, std::string>>;
using Size = std::optional<std::pair<int, int>>;

std::shared_ptr<PyScene> load(SceneRequest request) {
  auto loaded = std::make_shared<PyScene>();
  loaded->scene = load_scene(request);
  loaded->request = std::move(request);
  return loaded;
}

void add_overrides(SceneRequest& request, const Overrides& overrides) {
  for (const auto& [path, value] : overrides) request.overrides.push_back({path, value});
}

std::shared_ptr<PyScene> load_scene_for_python(const std::optional<std::string>& path,
                                               const std::optional<std::string>& text, const std::string& source_name,
                                               const Overrides& overrides, double time, Size size,
                                               std::optional<int> samples) {
  SceneRequest request;
  if (path) request.path = *path;
  if (text) request.text = *text;
  request.source_name = source_name;
  add_overrides(request, overrides);
  request.time = time;
  request.size = size;
  request.size_label = "size";
  request.samples = samples;
  return load(std::move(request));
}

/// Lines the library logged during a call, handed to Python's logging and warnings after it.
struct LogLines {
  std::mutex mutex;
  std::vector<std::pair<std::string, std::string>> lines;
};
LogLines& log_lines() {
  static LogLines lines;
  return lines;
}

/// Runs work without the GIL, with Ctrl-C cancelling it; raises KeyboardInterrupt when it came.
template <class Work>
auto interruptible(Work&& work) {
  InterruptScope scope;
  try {
    py::gil_scoped_release release;
    auto result = work();
    if (InterruptScope::interrupted()) throw Cancelled();
    return result;
  } catch (const Cancelled&) {
    if (!InterruptScope::interrupted()) throw;
    PyErr_SetNone(PyExc_KeyboardInterrupt);
    throw py::error_already_set();
  }
}

std::string json_text(const nlohmann::json& json) { return json.dump(); }

int checked_lanes(std::optional<int> lanes) {
  if (lanes && *lanes != 1 && *lanes != 4 && *lanes != 8 && *lanes != 16) {
    throw InputError(fmt::format("lanes must be 1, 4, 8 or 16 (got {})", *lanes));
  }
  return lanes.value_or(0);
}

SessionOptions session_options(std::optional<int> device, std::optional<int> lanes) {
  checked_lanes(lanes);
  return {device, lanes};
}

class PySession {
 public:
  PySession(std::optional<int> device, std::optional<int> lanes) : session_(session_options(device, lanes)) {}

  py::tuple render(const PyScene& scene, const std::string& backend_name, bool ray_status) {
    FrameRequest request;
    request.backend = parse_backend(backend_name, "backend");
    request.buffers = true;
    request.ray_status = ray_status;
    const std::lock_guard lock(mutex_);
    auto frame = interruptible([&] { return hold_frame(session_.render(scene.scene, request), scene.scene); });
    nlohmann::json stats = render_stats_json(request.backend, scene.scene, frame->stats);
    stats["programs_built"] = session_.programs_built();
    return py::make_tuple(frame_channels(frame), json_text(stats));
  }

  std::uint64_t programs_built() const { return session_.programs_built(); }
  std::string source() const { return session_.source(); }

 private:
  /// One render at a time per session (its renderer and program are one).
  std::mutex mutex_;
  RenderSession session_;
};

/// distance (N), color (N x 3) and id (N) for an N x 3 array of points.
py::tuple field(const PyScene& scene, const py::array_t<double, py::array::c_style | py::array::forcecast>& points,
                const std::string& backend_name, std::optional<int> device, std::optional<int> lanes) {
  if (points.ndim() != 2 || points.shape(1) != 3) {
    throw InputError(fmt::format("points must be an N x 3 array (got shape {})",
                                 py::str(py::object(points.attr("shape"))).cast<std::string>()));
  }
  const Backend backend = parse_backend(backend_name, "backend");
  const SessionOptions options = session_options(device, lanes);
  std::vector<glm::dvec3> at(static_cast<std::size_t>(points.shape(0)));
  const auto xyz = points.unchecked<2>();
  for (py::ssize_t i = 0; i < points.shape(0); ++i) at[static_cast<std::size_t>(i)] = {xyz(i, 0), xyz(i, 1), xyz(i, 2)};
  for (const glm::dvec3& p : at) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw InputError("points: every coordinate must be finite (got NaN or infinity)");
  }
  // The arrays are float32 (the module's documented type); the distances are rounded to it.
  struct Held {
    FieldSamples samples;
    std::vector<float> distance;
  };
  auto held = std::make_shared<Held>();
  held->samples = interruptible([&] { return sample_field(scene.scene, at, backend, options); });
  for (const double d : held->samples.distance) held->distance.push_back(static_cast<float>(d));
  const std::shared_ptr<void> owner = held;
  const auto n = static_cast<py::ssize_t>(at.size());
  return py::make_tuple(view_of(held->distance, {n}, owner), view_of(held->samples.color, {n, 3}, owner),
                        view_of(held->samples.id, {n}, owner));
}

/// An N x 3 array of T over data (no copy), kept alive by owner.
template <class T>
py::array_t<T> rows_of_three(const T* data, std::size_t rows, const std::shared_ptr<void>& owner) {
  py::capsule base(new std::shared_ptr<void>(owner),
                   [](void* held) { delete static_cast<std::shared_ptr<void>*>(held); });
  const auto item = static_cast<py::ssize_t>(sizeof(T));
  return py::array_t<T>({static_cast<py::ssize_t>(rows), py::ssize_t{3}}, {3 * item, item}, data, base);
}

/// vertices (V x 3 float64), faces (V x 3 uint32), normals and colors (V x 3 float32), stats.
py::tuple mesh(const PyScene& scene, int resolution, const std::string& backend_name, const std::string& precision,
               std::optional<int> device, const std::string& cells, bool sharp) {
  if (resolution < 8 || resolution > 8192) {
    throw InputError(fmt::format("resolution must be from 8 to 8192 (got {})", resolution));
  }
  if (precision != "float" && precision != "double") {
    throw InputError(fmt::format("precision must be 'float' or 'double' (got '{}')", precision));
  }
  if (cells != "cubes" && cells != "tetrahedra") {
    throw InputError(fmt::format("cells must be 'cubes' or 'tetrahedra' (got '{}')", cells));
  }
  if (sharp && cells != "cubes") {
    throw InputError("sharp applies to cells='cubes': tetrahedra put vertices inside cells, which a fan would drop");
  }
  const Backend backend = parse_backend(backend_name, "backend");
  Scene meshed = scene.scene;
  if (precision == "double") meshed.render.precision = Precision::Double;
  OpenClOptions cl;
  cl.device = device;
  MeshSettings settings;
  settings.resolution = resolution;
  settings.cells = cells == "tetrahedra" ? CellMethod::Tetrahedra : CellMethod::Cubes;
  settings.sharp = sharp;
  auto result = std::make_shared<SceneMesh>(interruptible([&] {
    return mesh_scene(
        meshed, settings,
        [&](const glm::dvec3& origin) {
          return backend == Backend::Reference ? reference_field(meshed, origin) : opencl_field(meshed, cl, origin);
        },
        fmt::format("resolution {}", resolution));
  }));
  const std::shared_ptr<void> owner = result;
  const TriangleMesh& m = result->mesh;
  return py::make_tuple(rows_of_three(&m.positions.data()->x, m.positions.size(), owner),
                        rows_of_three(m.triangles.data()->data(), m.triangles.size(), owner),
                        rows_of_three(&m.normals.data()->x, m.normals.size(), owner),
                        rows_of_three(&m.colors.data()->x, m.colors.size(), owner), json_text(result->stats.to_json()));
}

std::string check(const PyScene& scene, std::optional<int> device, std::optional<int> lanes) {
  const SessionOptions options = session_options(device, lanes);
  const CheckOutcome outcome = interruptible([&] { return check_scene(scene.scene, options); });
  nlohmann::json json = outcome.report.to_json();
  json["device"] = outcome.opencl.stats.device;
  json["lanes"] = outcome.opencl.stats.lanes;
  return json_text(json);
}

std::string bench(const PyScene& scene, int repeat, bool reference, std::optional<int> device,
                  std::optional<int> lanes) {
  if (repeat < 1 || repeat > 1000) throw InputError(fmt::format("repeat must be from 1 to 1000 (got {})", repeat));
  OpenClOptions cl;
  cl.device = device;
  cl.lanes = lanes;
  checked_lanes(lanes);
  BenchSettings settings;
  settings.repeat = repeat;
  settings.reference = reference;
  return json_text(interruptible([&] { return run_bench(scene.scene, cl, settings); }).to_json());
}

py::list devices() {
  py::list out;
  for (const DeviceEntry& d : list_devices()) {
    py::dict entry;
    entry["index"] = d.index;
    entry["name"] = d.name;
    entry["platform"] = d.platform_name;
    entry["type"] = d.is_gpu ? "gpu" : d.is_cpu ? "cpu" : "other";
    entry["fp64"] = d.has_fp64();
    entry["default_lanes"] = default_lanes(d);
    out.append(entry);
  }
  return out;
}

py::list drain_log() {
  LogLines& log = log_lines();
  const std::lock_guard lock(log.mutex);
  py::list out;
  for (const auto& [level, line] : log.lines) out.append(py::make_tuple(level, line));
  log.lines.clear();
  return out;
}

void set_verbosity_by_name(const std::string& name) {
  if (name == "quiet") return set_verbosity(Verbosity::Quiet);
  if (name == "normal") return set_verbosity(Verbosity::Normal);
  if (name == "verbose") return set_verbosity(Verbosity::Verbose);
  throw InputError(fmt::format("verbosity must be quiet, normal or verbose (got '{}')", name));
}

}  // namespace
}  // namespace clmarch::python

PYBIND11_MODULE(_clmarch, m) {
  using namespace clmarch;
  using namespace clmarch::python;
  m.doc() = "The clmarch core library; use the clmarch package, which documents these calls.";
  // Errors of the input become ValueError, of the device RuntimeError, of writing OSError (the
  // message is the CLI's, one line naming the file, line:column or argument).
  py::register_exception_translator([](std::exception_ptr error) {
    try {
      if (error) std::rethrow_exception(error);
    } catch (const InputError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const DeviceError& e) {
      PyErr_SetString(PyExc_RuntimeError, e.what());
    } catch (const OutputError& e) {
      PyErr_SetString(PyExc_OSError, e.what());
    } catch (const Cancelled&) {
      PyErr_SetNone(PyExc_KeyboardInterrupt);
    }
  });
  m.def(
      "set_progress",
      [](const py::object& callback) {
        if (callback.is_none()) return set_progress_sink({});
        if (!PyCallable_Check(callback.ptr())) throw InputError("set_progress: expected a callable or None");
        // Held by the sink; released (with the GIL) when the sink is replaced.
        auto held = std::shared_ptr<py::object>(new py::object(callback), [](py::object* f) {
          const py::gil_scoped_acquire gil;
          delete f;
        });
        set_progress_sink([held](std::string_view label, long long done, long long total) {
          const py::gil_scoped_acquire gil;
          try {
            (*held)(std::string(label), done, total);
          } catch (py::error_already_set& e) {
            // An exception of the callback stops the work, as Ctrl-C would, and is reported.
            e.discard_as_unraisable("clmarch progress callback");
            cancellation_requested().store(true);
          }
        });
      },
      py::arg("callback"));
  set_log_sink([](LogLevel level, std::string_view line) {
    LogLines& log = log_lines();
    const std::lock_guard lock(log.mutex);
    const char* name = level == LogLevel::Warning ? "warning" : level == LogLevel::Verbose ? "verbose" : "info";
    log.lines.emplace_back(name, std::string(line));
  });

  py::class_<PyScene, std::shared_ptr<PyScene>>(m, "Scene",
                                                "A loaded, validated scene (clmarch.load): the scene file's or "
                                                "text's tree and settings with the overrides, time and size applied")
      .def_property_readonly("source_name", [](const PyScene& s) { return s.scene.source_name; })
      .def_property_readonly("path", [](const PyScene& s) { return s.request.path; })
      .def_property_readonly("width", [](const PyScene& s) { return s.scene.render.width; })
      .def_property_readonly("height", [](const PyScene& s) { return s.scene.render.height; })
      .def_property_readonly("samples", [](const PyScene& s) { return s.scene.render.samples; })
      .def_property_readonly("time", [](const PyScene& s) { return s.scene.time; })
      .def_property_readonly("overrides",
                             [](const PyScene& s) {
                               Overrides out;
                               for (const SceneOverride& o : s.request.overrides) out.emplace_back(o.path, o.value);
                               return out;
                             })
      .def(
          "changed",
          [](const PyScene& s, const Overrides& overrides, std::optional<double> time, Size size,
             std::optional<int> samples) {
            SceneRequest request = s.request;
            add_overrides(request, overrides);
            if (time) request.time = *time;
            if (size) request.size = size;
            if (samples) request.samples = samples;
            return load(std::move(request));
          },
          py::arg("overrides"), py::arg("time"), py::arg("size"), py::arg("samples"));
  m.def("load_scene", &load_scene_for_python, py::arg("path"), py::arg("text"), py::arg("source_name"),
        py::arg("overrides"), py::arg("time"), py::arg("size"), py::arg("samples"));
  m.def("parse_override", [](const std::string& text) {
    const SceneOverride o = parse_override(text);
    return std::make_pair(o.path, o.value);
  });

  py::class_<PySession>(m, "Session", "A render session of the core library (clmarch.Session wraps it)")
      .def(py::init<std::optional<int>, std::optional<int>>(), py::arg("device"), py::arg("lanes"))
      .def("render", &PySession::render, py::arg("scene"), py::arg("backend"), py::arg("ray_status"))
      .def_property_readonly("programs_built", &PySession::programs_built)
      .def_property_readonly("source", &PySession::source);

  m.def("field", &field, py::arg("scene"), py::arg("points"), py::arg("backend"), py::arg("device"), py::arg("lanes"));
  m.def("mesh", &mesh, py::arg("scene"), py::arg("resolution"), py::arg("backend"), py::arg("precision"),
        py::arg("device"), py::arg("cells"), py::arg("sharp"));
  m.def("check", &check, py::arg("scene"), py::arg("device"), py::arg("lanes"));
  m.def("bench", &bench, py::arg("scene"), py::arg("repeat"), py::arg("reference"), py::arg("device"),
        py::arg("lanes"));
  m.def("devices", &devices);
  m.def("programs_compiled", &device_programs_compiled);
  m.def("drain_log", &drain_log);
  m.def("set_verbosity", &set_verbosity_by_name);
  m.attr("__version__") = CLMARCH_VERSION;
}
