#pragma once
/// `revisit.ClosurePipeline`: the online API (pipeline/online.hpp) with numpy in and out. Without a pose,
/// a scan goes through revisit's own odometry first, as `revisit run` does.
#include <optional>
#include <vector>

#include "convert.hpp"
#include "pipeline/odometry_stages.hpp"
#include "pipeline/online.hpp"

namespace revisit::python {

class PyClosurePipeline {
  public:
    explicit PyClosurePipeline(const PipelineConfig& config);

    /// The closures this scan's map made that were accepted (the detector's and the proximity pass's).
    std::vector<ClosureRecord> AddScan(const py::array& points, const py::object& T_world_sensor, const py::object& stamp);
    /// Closes the last map and runs the final optimization; returns the closures accepted in the end.
    std::vector<ClosureRecord> Finish();
    /// Every accepted closure so far.
    std::vector<ClosureRecord> Closures() const;
    /// Every scan's pose re-anchored to its corrected map origin (N, 4, 4); scans after the last closed map
    /// follow its correction.
    py::array_t<double> CorrectedPoses() const;
    py::array_t<double> Poses() const { return ToNumpy(poses_); }
    const ClosurePipeline& pipeline() const { return pipeline_; }
    bool finished() const { return finished_; }

  private:
    PipelineConfig config_;
    ClosurePipeline pipeline_;
    std::optional<OdometryStages> odometry_;
    revisit::Poses poses_;  ///< T_world_sensor of every scan added
    bool finished_ = false;
    StageTimer add_scan_;  ///< the C++ calls to ClosurePipeline::AddScan, measured around them (the overhead's reference)
  public:
    const StageTimer& add_scan_timer() const { return add_scan_; }
};

/// The accepted records that may correct the trajectory.
std::vector<ClosureRecord> Accepted(const std::vector<ClosureRecord>& records);

void BindClosurePipeline(py::module_& m);

}  // namespace revisit::python
