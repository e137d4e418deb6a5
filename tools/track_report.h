#ifndef VIO_TOOLS_TRACK_REPORT_H_
#define VIO_TOOLS_TRACK_REPORT_H_

// The frontend's accuracy reports of vio_track: against the exact truth of
// a rendered sequence (eval/track_truth.h), and against ground-truth poses
// of any sequence (eval/epipolar_error.h); plus the track lengths.

#include <string>
#include <vector>

#include "config/euroc_sequence.h"
#include "dataset/trajectory.h"
#include "eval/epipolar_error.h"
#include "eval/track_truth.h"
#include "geometry/feature_observation.h"
#include "render/scene_file.h"

namespace vio {

// The truth report of tracks on a rendered sequence whose truth files
// (mav0/render/, render/scene_file.h) were read into `truth`.
TrackTruthReport TrackTruthOfRenderedSequence(
    const EurocSequence& sequence, const RenderTruth& truth,
    const std::vector<FeatureFrame>& frames);

// The epipolar report of the cam0 tracks against `ground_truth` (body
// poses, interpolated at the frame stamps).
EpipolarReport EpipolarErrorAgainst(const EurocSequence& sequence,
                                    const std::vector<FeatureFrame>& frames,
                                    const Trajectory& ground_truth,
                                    int max_gap);

std::string DescribePixelErrors(const PixelErrorStats& s);
std::string DescribeTrackLengths(const TrackLengthStats& s);
std::string DescribeTrackTruth(const TrackTruthReport& report);
std::string DescribeEpipolarError(const EpipolarReport& report);

}  // namespace vio

#endif  // VIO_TOOLS_TRACK_REPORT_H_
