// Which OpenCL device each rank of a job renders on, and `clmarch devices` for every rank.
#pragma once

#include "cl/devices.hpp"

#include <optional>
#include <string>
#include <vector>

namespace clmarch {

/// The device index a rank takes by default: the node's GPUs shared out by local rank (the
/// local_rank-th GPU, round robin when the node has more ranks than GPUs), else nothing, which
/// leaves select_device's default (the first CPU).
std::optional<int> rank_default_device(const std::vector<DeviceEntry>& devices, int local_rank);

/// Every rank's text, in rank order, on rank 0 (empty elsewhere); the text itself when the world
/// is one process.
std::vector<std::string> gather_on_rank0(const std::string& text);

}  // namespace clmarch
