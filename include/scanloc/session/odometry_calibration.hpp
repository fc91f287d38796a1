#pragma once
// The odometry's calibration, learned online from the steps the session confirmed. A robot whose
// wheel radius or wheelbase is off by a few per cent reports every step a steady share too long,
// or every turn a steady share too sharp: errors that do not cancel from scan to scan, that the
// correction gate and the closures' odometry model take for noise, and that bent the sparse
// Radish logs' maps by metres (docs/BENCHMARKS.md, "A miscalibrated odometry"). Each confirmed
// scan gives one sample: the odometry's step since the last confirmed scan, and the step between
// the two confirmed postures. Two scales are fitted to them through the origin, robustly (Huber
// weights on a robust σ): the distance driven (matched ≈ s · odometry, along the odometry's
// direction) and the angle turned (matched ≈ k · odometry). A scale is significant while it
// stands apart from 1 by more than min_change and by more than `significance` standard errors:
// with perfect odometry the fits land within 0.5 % of 1 (the scans' own scale, or the
// reference's, differs by that much). The session reports the scales and warns of significant
// ones; with `apply` it also scales the odometry by them before anything uses it. Off by default:
// on the public logs, applied, they helped where the odometry was several per cent off and made
// the closures fewer where a noisier laser's scans fit worse (docs/BENCHMARKS.md, "A
// miscalibrated odometry").

#include <cstddef>
#include <deque>

#include "scanloc/geometry/pose2d.hpp"

namespace scanloc {

struct OdometryCalibrationOptions {
  bool enabled = true;  // learn and report the scales
  bool apply = false;   // ... and scale the odometry by the significant ones
  // Samples remembered (the most recent), and needed before a scale may be applied.
  int window = 3000;
  int min_samples = 30;
  // A scale is significant while |scale − 1| exceeds both of these: the change, and its standard
  // errors.
  double min_change = 0.01;
  double significance = 3.0;
  // A sample spans at least this much driving (m) or turning (rad): over shorter steps the
  // matcher's jitter and the odometry's timing weigh more than a scale (the Kümmerle logs localise
  // a scan every 5 cm).
  double min_step_m = 0.5;
  double min_step_rad = 0.25;
  // Scales are fitted again after this many new samples.
  int refit_every = 10;
  // Scales beyond [1 / max_scale, max_scale] are not believed: the fit keeps the last one.
  double max_scale = 2.0;
  // Throws std::invalid_argument naming the first option out of its domain.
  void Validate() const;
};

// One scale: the value in use (the last fit while it is significant and applied, else 1), the
// last fit and its standard error.
struct OdometryScale {
  double value = 1.0;
  double fitted = 1.0;
  double standard_error = 0.0;  // 0 until fitted
  std::size_t samples = 0;      // the samples the last fit weighed (those that moved)
  bool significant = false;
};

class OdometryCalibration {
 public:
  explicit OdometryCalibration(OdometryCalibrationOptions options = {});

  // One confirmed step: the odometry's (as the log gave it) and the session's between the same
  // two scans, each in the frame of the first. False, and nothing learned, when the odometry's
  // step is shorter than min_step_m and min_step_rad: the caller goes on to a later scan.
  bool Learn(const Pose2D& odometry_step, const Pose2D& matched_step);
  // An odometry step as the calibrated odometry reports it (the values in use).
  Pose2D Calibrated(const Pose2D& odometry_step) const;

  const OdometryScale& distance() const { return distance_; }
  const OdometryScale& turn() const { return turn_; }
  bool applies() const { return options_.apply; }
  std::size_t samples() const { return samples_.size(); }

 private:
  struct Sample {
    double odometry_m, matched_m;      // the distance, and the matched step along it
    double odometry_rad, matched_rad;  // the turns
  };
  void Refit();
  void Fit(double Sample::*odometry, double Sample::*matched, OdometryScale& scale) const;

  OdometryCalibrationOptions options_;
  std::deque<Sample> samples_;
  std::size_t since_fit_ = 0;
  OdometryScale distance_, turn_;
};

}  // namespace scanloc
