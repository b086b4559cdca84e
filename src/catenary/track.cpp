// Track alignment: straight pieces and circular arcs (see track.hpp).
#include "pcsim/catenary/track.hpp"

#include <cmath>

namespace pcsim::catenary {

TrackAlignment::TrackAlignment(std::vector<TrackPiece> pieces) : pieces_(std::move(pieces)) {
  PieceStart start;
  for (const auto& piece : pieces_) {
    starts_.push_back(start);
    const double a0 = start.heading;
    if (piece.radius == 0) {
      start.p += piece.length * Eigen::Vector2d(std::cos(a0), std::sin(a0));
    } else {
      straight_ = false;
      const double a1 = a0 + piece.length / piece.radius;
      // Arc about the centre c = p0 + R n(a0), n = (-sin a, cos a).
      start.p +=
          piece.radius * Eigen::Vector2d(std::sin(a1) - std::sin(a0), -std::cos(a1) + std::cos(a0));
      start.heading = a1;
    }
    start.s += piece.length;
  }
}

std::size_t TrackAlignment::piece_at(double s) const {
  std::size_t k = 0;
  while (k + 1 < starts_.size() && s >= starts_[k + 1].s) ++k;
  return k;
}

Eigen::Vector2d TrackAlignment::point(double s) const {
  if (straight_) return {s, 0.0};
  const std::size_t k = piece_at(s);
  const PieceStart& st = starts_[k];
  const double u = s - st.s, R = pieces_[k].radius, a0 = st.heading;
  if (R == 0) return st.p + u * Eigen::Vector2d(std::cos(a0), std::sin(a0));
  const double a = a0 + u / R;
  return st.p + R * Eigen::Vector2d(std::sin(a) - std::sin(a0), -std::cos(a) + std::cos(a0));
}

Eigen::Vector2d TrackAlignment::tangent(double s) const {
  if (straight_) return {1.0, 0.0};
  const std::size_t k = piece_at(s);
  const double R = pieces_[k].radius;
  const double a = starts_[k].heading + (R == 0 ? 0.0 : (s - starts_[k].s) / R);
  return {std::cos(a), std::sin(a)};
}

Eigen::Vector2d TrackAlignment::normal(double s) const {
  const Eigen::Vector2d t = tangent(s);
  return {-t.y(), t.x()};
}

double TrackAlignment::station_on(std::size_t k, const Eigen::Vector2d& p) const {
  const PieceStart& st = starts_[k];
  const double R = pieces_[k].radius, a0 = st.heading;
  if (R == 0) return st.s + Eigen::Vector2d(std::cos(a0), std::sin(a0)).dot(p - st.p);
  // Centre c = p0 + R n(a0); p - c = R (sin a, -cos a) on the circle.
  const Eigen::Vector2d c = st.p + R * Eigen::Vector2d(-std::sin(a0), std::cos(a0));
  const Eigen::Vector2d d = (p - c) / R;
  double da = std::atan2(d.x(), -d.y()) - a0;
  da = std::remainder(da, 2.0 * M_PI);  // in [-pi, pi]
  return st.s + R * da;
}

double TrackAlignment::station(const Eigen::Vector2d& p) const {
  if (straight_) return p.x();
  // The piece whose station range holds the local projection (the end
  // pieces also take what lies beyond them).
  const std::size_t n = pieces_.size();
  double s = station_on(0, p);
  for (std::size_t k = 0; k < n; ++k) {
    s = station_on(k, p);
    const double end = starts_[k].s + pieces_[k].length;
    if ((k == 0 || s >= starts_[k].s) && (k + 1 == n || s <= end)) return s;
  }
  return s;
}

}  // namespace pcsim::catenary
