#include "frontend/stereo_depth.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace vio {
namespace {

// The matching pattern: kAlong samples on each side along the epipolar line
// and kAcross rows on each side of it, 1 px apart (5 x 3 = 15 samples).
constexpr int kAlong = 2, kAcross = 1;
constexpr int kSamples = (2 * kAlong + 1) * (2 * kAcross + 1);
using Pattern = std::array<double, kSamples>;
using Offsets = std::array<Eigen::Vector2d, kSamples>;
// Host pixels this close to the border are not searched [px].
constexpr double kHostBorder = 4.0;
// Matches closer than this to the best one do not count as rivals [px].
constexpr int kRivalDistance = 2;

// Bilinear value of a grid at (u, v); the caller keeps (u, v) at least 1 px
// inside. (The search reads ~1000 samples per pixel: bicubic there would
// cost four times as much for nothing, the parabola refines the match.)
double Bilinear(const ImageGrid& g, double u, double v) {
  const int u0 = static_cast<int>(u), v0 = static_cast<int>(v);
  const double fu = u - u0, fv = v - v0;
  const float* p = g.values().data() + v0 * g.width() + u0;
  const int w = g.width();
  return (1.0 - fv) * ((1.0 - fu) * p[0] + fu * p[1]) +
         fv * ((1.0 - fu) * p[w] + fu * p[w + 1]);
}

// Subtracts the mean and returns the remaining norm.
double ZeroMean(Pattern* x) {
  double mean = 0.0;
  for (double v : *x) mean += v;
  mean /= kSamples;
  double norm2 = 0.0;
  for (double& v : *x) {
    v -= mean;
    norm2 += v * v;
  }
  return std::sqrt(norm2);
}

// The epipolar geometry of one host pixel.
struct PixelLine {
  Eigen::Vector3d a;               // R f: the point at infinity, homogeneous
  Eigen::Vector2d e_host, n_host;  // line direction and normal in the host
  Eigen::Vector2d start, dir;      // segment x(s) = start + s dir, |dir| = 1
  double length = 0.0;             // [px]
  Offsets host_offsets, other_offsets;
};

class PairSearch {
 public:
  PairSearch(const PyramidLevel& host, const PyramidLevel& other,
             const Eigen::Isometry3d& T_o_h, int level,
             const StereoDepthOptions& options)
      : host_(host),
        other_(other),
        R_(T_o_h.linear()),
        t_(T_o_h.translation()),
        options_(options),
        rho_lo_(1.0 / options.max_depth_m),
        rho_hi_(1.0 / options.min_depth_m),
        sigma_line_px_(options.sigma_epipolar_px / std::pow(2.0, level)),
        sigma_intensity_(options.sigma_intensity / std::pow(2.0, level)) {
    // The other camera's centre in the host frame, for the host's epipole.
    centre_ = -R_.transpose() * t_;
  }

  // Searches one host pixel; returns false (counting why) or fills *point.
  bool Match(int u, int v, StereoDepthStats* stats, DepthPoint* point) const;

 private:
  bool MakeLine(const Eigen::Vector2d& p, PixelLine* line) const;
  double RhoAt(const PixelLine& line, const Eigen::Vector2d& x) const;

  const PyramidLevel& host_;
  const PyramidLevel& other_;
  Eigen::Matrix3d R_;
  Eigen::Vector3d t_, centre_;
  const StereoDepthOptions& options_;
  double rho_lo_, rho_hi_, sigma_line_px_;
  // A level averages 4^level pixels: its noise is sigma_I / 2^level.
  double sigma_intensity_;
};

bool PairSearch::MakeLine(const Eigen::Vector2d& p, PixelLine* line) const {
  const Pinhole& K = host_.camera;
  const Pinhole& Ko = other_.camera;
  // Host epipolar line through p: towards the epipole E = K c (homogeneous),
  // direction E.xy - E.z p (E.z = 0: the epipole is at infinity).
  const Eigen::Vector3d E(K.fx * centre_.x() + K.cx * centre_.z(),
                          K.fy * centre_.y() + K.cy * centre_.z(), centre_.z());
  const Eigen::Vector2d d = E.head<2>() - E.z() * p;
  if (!(d.norm() > 1e-9)) return false;
  line->e_host = d.normalized();
  line->n_host = Eigen::Vector2d(-line->e_host.y(), line->e_host.x());
  // The searched segment: rho from rho_lo (far) to rho_hi (near).
  line->a = R_ * K.Bearing(p);
  const Eigen::Vector3d h_lo = line->a + rho_lo_ * t_;
  const Eigen::Vector3d h_hi = line->a + rho_hi_ * t_;
  if (h_lo.z() < 1e-3 || h_hi.z() < 1e-3) return false;
  line->start = Ko.Project(h_lo);
  const Eigen::Vector2d span = Ko.Project(h_hi) - line->start;
  line->length = span.norm();
  if (!(line->length >= 2.0)) return false;
  line->dir = span / line->length;
  // Host pattern offsets and their images under the local affine warp
  // d x / d p = K_o pi'(h) R d f / d p at the middle inverse depth.
  const Eigen::Vector3d h_mid = line->a + std::sqrt(rho_lo_ * rho_hi_) * t_;
  Eigen::Matrix<double, 3, 2> d_f_d_p = Eigen::Matrix<double, 3, 2>::Zero();
  d_f_d_p(0, 0) = 1.0 / K.fx;
  d_f_d_p(1, 1) = 1.0 / K.fy;
  const Eigen::Matrix2d A = Ko.ProjectJacobian(h_mid) * R_ * d_f_d_p;
  int k = 0;
  for (int m = -kAcross; m <= kAcross; ++m) {
    for (int i = -kAlong; i <= kAlong; ++i, ++k) {
      line->host_offsets[k] = i * line->e_host + m * line->n_host;
      line->other_offsets[k] = A * line->host_offsets[k];
    }
  }
  return true;
}

double PairSearch::RhoAt(const PixelLine& line,
                         const Eigen::Vector2d& x) const {
  // x = K_o pi(a + rho t): with n = K_o^-1 x, (a_x + rho t_x) = n_x (a_z +
  // rho t_z), so rho = (n_x a_z - a_x) / (t_x - n_x t_z); likewise in y. Use
  // the better conditioned of the two.
  const Eigen::Vector3d n = other_.camera.Bearing(x);
  const double den_x = t_.x() - n.x() * t_.z();
  const double den_y = t_.y() - n.y() * t_.z();
  if (std::abs(den_x) >= std::abs(den_y)) {
    return (n.x() * line.a.z() - line.a.x()) / den_x;
  }
  return (n.y() * line.a.z() - line.a.y()) / den_y;
}

bool PairSearch::Match(int u, int v, StereoDepthStats* stats,
                       DepthPoint* point) const {
  const ImageGrid& H = *host_.image;
  const ImageGrid& O = *other_.image;
  const Eigen::Vector2d p(u, v);
  double I = 0.0;
  Eigen::Vector2d g;
  H.Evaluate(u, v, &I, &g.x(), &g.y());
  if (g.norm() < options_.min_gradient) return false;
  ++stats->candidates;
  PixelLine line;
  if (!MakeLine(p, &line)) {
    ++stats->out_of_view;
    return false;
  }
  const double g_along = g.dot(line.e_host);
  if (std::abs(g_along) < options_.min_line_cosine * g.norm()) {
    ++stats->along_edge;
    return false;
  }
  Pattern host;
  for (int k = 0; k < kSamples; ++k) {
    const Eigen::Vector2d q = p + line.host_offsets[k];
    host[k] = H.Value(q.x(), q.y());
  }
  const double host_norm = ZeroMean(&host);
  if (!(host_norm > 1e-6)) {
    ++stats->low_ncc;
    return false;
  }
  // Scores 1 - ncc along the segment (infinity where the pattern leaves O).
  double reach = 0.0;
  for (const auto& o : line.other_offsets) reach = std::max(reach, o.norm());
  const int n = static_cast<int>(line.length) + 1;
  std::vector<double> score(n, std::numeric_limits<double>::infinity());
  int best = -1;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d x = line.start + i * line.dir;
    if (!O.Inside(x.x(), x.y(), reach + kImageGridMargin)) continue;
    Pattern other;
    for (int k = 0; k < kSamples; ++k) {
      other[k] = Bilinear(O, x.x() + line.other_offsets[k].x(),
                          x.y() + line.other_offsets[k].y());
    }
    const double other_norm = ZeroMean(&other);
    if (!(other_norm > 1e-6)) continue;
    double dot = 0.0;
    for (int k = 0; k < kSamples; ++k) dot += host[k] * other[k];
    score[i] = 1.0 - dot / (host_norm * other_norm);
    if (best < 0 || score[i] < score[best]) best = i;
  }
  if (best < 0) {
    ++stats->out_of_view;
    return false;
  }
  if (1.0 - score[best] < options_.min_ncc) {
    ++stats->low_ncc;
    return false;
  }
  double rival = std::numeric_limits<double>::infinity();
  for (int i = 0; i < n; ++i) {
    if (std::abs(i - best) > kRivalDistance) rival = std::min(rival, score[i]);
  }
  if (best == 0 || best == n - 1 || !std::isfinite(score[best - 1]) ||
      !std::isfinite(score[best + 1]) ||
      rival < options_.uniqueness_ratio * score[best]) {
    ++stats->ambiguous;
    return false;
  }
  // Sub-pixel: the vertex of the parabola through the three scores.
  const double s_m = score[best - 1], s_0 = score[best], s_p = score[best + 1];
  const double curvature = s_m - 2.0 * s_0 + s_p;
  const double offset =
      curvature > 0.0 ? std::clamp(0.5 * (s_m - s_p) / curvature, -0.5, 0.5)
                      : 0.0;
  const Eigen::Vector2d x = line.start + (best + offset) * line.dir;
  const double rho = RhoAt(line, x);
  const double d_rho_d_s =
      RhoAt(line, x + 0.5 * line.dir) - RhoAt(line, x - 0.5 * line.dir);
  if (!(rho >= rho_lo_ && rho <= rho_hi_)) {
    ++stats->ambiguous;
    return false;
  }
  // The disparity error (header comment, step 4): the pattern's samples
  // each carry the noise of two images, so a shift s along the line is
  // known to 2 sigma_I^2 / sum_k (g_o(x_k) . l)^2 (the Gauss-Newton variance
  // of a least-squares 1-D alignment of the pattern).
  double info = 0.0;
  for (const Eigen::Vector2d& o : line.other_offsets) {
    double I_o = 0.0;
    Eigen::Vector2d g_o;
    O.Evaluate(x.x() + o.x(), x.y() + o.y(), &I_o, &g_o.x(), &g_o.y());
    info += std::pow(g_o.dot(line.dir), 2);
  }
  const double sigma_i = sigma_intensity_;
  const double photo = 2.0 * sigma_i * sigma_i / std::max(info, 1e-6);
  const double tangent = g.dot(line.n_host) / g_along;
  const double geo = sigma_line_px_ * sigma_line_px_ * tangent * tangent;
  point->uv = p;
  point->intensity = H.At(u, v);
  point->rho = rho;
  point->variance = d_rho_d_s * d_rho_d_s * (photo + geo);
  ++stats->accepted;
  return true;
}

}  // namespace

std::vector<DepthPoint> StereoInverseDepth(const PyramidLevel& host,
                                           const PyramidLevel& other,
                                           const Eigen::Isometry3d& T_o_h,
                                           int level,
                                           const StereoDepthOptions& options,
                                           StereoDepthStats* stats) {
  std::string message;
  if (!options.Validate(&message)) {
    throw std::invalid_argument("StereoDepthOptions: " + message);
  }
  StereoDepthStats counts;
  const PairSearch search(host, other, T_o_h, level, options);
  std::vector<DepthPoint> points;
  const int w = host.image->width(), h = host.image->height();
  const int border = static_cast<int>(kHostBorder);
  for (int v = border; v < h - border; ++v) {
    for (int u = border; u < w - border; ++u) {
      DepthPoint point;
      if (search.Match(u, v, &counts, &point)) points.push_back(point);
    }
  }
  if (stats != nullptr) *stats = counts;
  return points;
}

}  // namespace vio
