// The mesh's field on an OpenCL device: the scene's eval_points program, built once, running
// eval_points (pruning), mesh_sample_bricks and mesh_place_vertices (kernels/eval_points.cl).
#include "cl/cl_errors.hpp"
#include "common/cancellation.hpp"
#include "mesh/mesh_field.hpp"
#include "render/device_inputs.hpp"
#include "render/dispatch_plan.hpp"
#include "render/prepared_program.hpp"
#include "render/real_plane.hpp"

#include <algorithm>
#include <array>

namespace clmarch {
namespace {

class DeviceField final : public MeshField {
 public:
  DeviceField(const Scene& scene, const OpenClOptions& options, const glm::dvec3& origin)
      : prepared_(prepare_program(scene, options, KernelPurpose::EvalPoints)) {
    DeviceProgram& dp = prepared_.program;
    with_device_errors(dp.device, [&] {
      values_ = make_scene_values(prepared_, scene);
      eval_ = cl::Kernel(dp.program, "eval_points");
      sample_ = cl::Kernel(dp.program, "mesh_sample_bricks");
      place_ = cl::Kernel(dp.program, "mesh_place_vertices");
    });
    // origin = hi + lo, each a float: a double program adds them in double.
    const glm::vec3 hi(origin);
    const glm::vec3 lo(origin - glm::dvec3(hi));
    origin_hi_ = cl_float4{{hi.x, hi.y, hi.z, 0.0f}};
    origin_lo_ = cl_float4{{lo.x, lo.y, lo.z, 0.0f}};
  }

  std::vector<float> distances(const std::vector<glm::dvec3>& offsets) override {
    std::vector<float> out(offsets.size());
    if (offsets.empty()) return out;
    DeviceProgram& dp = prepared_.program;
    const Dispatch dispatch = plan_point_dispatch(dp.device, offsets.size(), prepared_.lanes);
    const std::size_t n = dispatch.plane_stride;
    // Points and distances in the program's real (kernels/eval_points.cl), the rest float.
    const bool in_double = prepared_.kernel_options.variant.precision == Precision::Double;
    std::vector<RealPlane> planes = coordinate_planes(offsets, n, in_double);
    RealPlane distance(n, in_double);
    with_device_errors(dp.device, [&] {
      // The buffers live until the kernel is done: an argument does not hold its buffer.
      std::vector<cl::Buffer> buffers;
      for (RealPlane& plane : planes)
        buffers.emplace_back(dp.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, plane.size_bytes(), plane.data());
      // Distance, colour distance, red, green, blue, primitive number: only the first is read.
      for (int k = 0; k < 2; ++k) buffers.emplace_back(dp.context, CL_MEM_WRITE_ONLY, distance.size_bytes());
      for (int k = 0; k < 4; ++k) buffers.emplace_back(dp.context, CL_MEM_WRITE_ONLY, n * sizeof(float));
      for (int k = 0; k < 9; ++k) eval_.setArg(k, buffers[static_cast<std::size_t>(k)]);
      set_scene_values_arg(eval_, 9, values_);
      eval_.setArg(10, origin_hi_);
      eval_.setArg(11, origin_lo_);
      run(eval_, dispatch);
      dp.queue.enqueueReadBuffer(buffers[3], CL_TRUE, 0, distance.size_bytes(), distance.data());
    });
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = static_cast<float>(distance.get(i));
    return out;
  }

  void sample_bricks(std::span<const glm::ivec3> corners, int side, double cell, std::span<float> out) override {
    if (corners.empty()) return;
    DeviceProgram& dp = prepared_.program;
    const std::size_t points = static_cast<std::size_t>(side) * side * side;
    // A whole number of packets per brick, so that no packet spans two.
    const auto lanes = static_cast<std::size_t>(prepared_.lanes);
    const std::size_t stride = (points + lanes - 1) / lanes * lanes;
    const Dispatch dispatch = plan_point_dispatch(dp.device, corners.size() * stride, prepared_.lanes);
    // The dispatch's last work-items read bricks past the batch: copies of its last brick.
    std::vector<cl_int4> bricks((dispatch.plane_stride + stride - 1) / stride);
    for (std::size_t b = 0; b < bricks.size(); ++b) {
      const glm::ivec3& c = corners[std::min(b, corners.size() - 1)];
      bricks[b] = cl_int4{{c.x, c.y, c.z, 0}};
    }
    std::vector<float> values(dispatch.plane_stride);
    with_device_errors(dp.device, [&] {
      const cl::Buffer in(dp.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, bricks.size() * sizeof(cl_int4),
                          bricks.data());
      const cl::Buffer distance(dp.context, CL_MEM_WRITE_ONLY, values.size() * sizeof(float));
      sample_.setArg(0, in);
      sample_.setArg(1, distance);
      set_scene_values_arg(sample_, 2, values_);
      sample_.setArg(3, static_cast<cl_int>(side));
      sample_.setArg(4, static_cast<cl_int>(stride));
      sample_.setArg(5, static_cast<cl_float>(cell));
      sample_.setArg(6, origin_hi_);
      sample_.setArg(7, origin_lo_);
      run(sample_, dispatch);
      dp.queue.enqueueReadBuffer(distance, CL_TRUE, 0, values.size() * sizeof(float), values.data());
    });
    for (std::size_t b = 0; b < corners.size(); ++b) {
      std::copy_n(values.begin() + static_cast<std::ptrdiff_t>(b * stride), points, out.begin() + b * points);
    }
  }

  void place_vertices(std::span<const EdgeSeed> seeds, double cell, const PlacementSettings& settings,
                      std::span<PlacedVertex> out) override {
    if (seeds.empty()) return;
    DeviceProgram& dp = prepared_.program;
    const Dispatch dispatch = plan_point_dispatch(dp.device, seeds.size(), prepared_.lanes);
    const std::size_t n = dispatch.plane_stride;
    // In: the edge's start and direction (offsets), its end values; padding has both values 0,
    // which the kernel leaves alone.
    std::array<std::vector<float>, 8> in;
    for (auto& plane : in) plane.assign(n, 0.0f);
    for (std::size_t i = 0; i < seeds.size(); ++i) {
      const EdgeSeed& s = seeds[i];
      const glm::ivec3 d = step_offset(s.step);
      for (int axis = 0; axis < 3; ++axis) {
        in[axis][i] = static_cast<float>(s.point[axis] * cell);
        in[3 + axis][i] = static_cast<float>(d[axis] * cell);
      }
      in[6][i] = s.value_from;
      in[7][i] = s.value_to;
    }
    // Out: place, normal x y z, red, green, blue, evaluations.
    std::array<std::vector<float>, 8> result;
    for (auto& plane : result) plane.resize(n);
    with_device_errors(dp.device, [&] {
      std::array<cl::Buffer, 8> inputs;
      for (int k = 0; k < 8; ++k) {
        inputs[k] = input(in[k]);
        place_.setArg(k, inputs[k]);
      }
      std::array<cl::Buffer, 8> outputs;
      for (int k = 0; k < 8; ++k) {
        outputs[k] = cl::Buffer(dp.context, CL_MEM_WRITE_ONLY, n * sizeof(float));
        place_.setArg(8 + k, outputs[k]);
      }
      set_scene_values_arg(place_, 16, values_);
      place_.setArg(17, static_cast<cl_float>(settings.level));
      place_.setArg(18, static_cast<cl_float>(settings.tolerance));
      place_.setArg(19, static_cast<cl_int>(settings.max_steps));
      place_.setArg(20, static_cast<cl_float>(settings.normal_step));
      place_.setArg(21, origin_hi_);
      place_.setArg(22, origin_lo_);
      run(place_, dispatch);
      for (int k = 0; k < 8; ++k)
        dp.queue.enqueueReadBuffer(outputs[k], CL_FALSE, 0, seeds.size() * sizeof(float), result[k].data());
      dp.queue.finish();
    });
    for (std::size_t i = 0; i < seeds.size(); ++i) {
      out[i].place = result[0][i];
      out[i].normal = {result[1][i], result[2][i], result[3][i]};
      out[i].color = {result[4][i], result[5][i], result[6][i]};
      out[i].evaluations = static_cast<std::uint32_t>(result[7][i]);
    }
  }

 private:
  cl::Buffer input(std::vector<float>& plane) {
    return cl::Buffer(prepared_.program.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, plane.size() * sizeof(float),
                      plane.data());
  }

  void run(cl::Kernel& kernel, const Dispatch& dispatch) {
    throw_if_cancelled();
    prepared_.program.queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(dispatch.global_items),
                                                 cl::NDRange(dispatch.local_items));
  }

  PreparedProgram prepared_;
  std::optional<cl::Buffer> values_;
  cl::Kernel eval_, sample_, place_;
  cl_float4 origin_hi_{}, origin_lo_{};
};

}  // namespace

std::unique_ptr<MeshField> opencl_field(const Scene& scene, const OpenClOptions& options, const glm::dvec3& origin) {
  return std::make_unique<DeviceField>(scene, options, origin);
}

}  // namespace clmarch
