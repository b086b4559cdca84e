// Horizontal alignment of the track centre line (plan view): pieces of
// constant curvature joined tangentially, starting at the origin heading +x
// (no transition curves). The station s is the arc length along the centre
// line; the pantographs travel in stations and the contact point is where a
// wire crosses the vertical plane normal to the track at the pantograph's
// station. An alignment without curved pieces is the straight track along x
// (station = x, exactly).
#pragma once

#include <Eigen/Core>
#include <vector>

namespace pcsim::catenary {

struct TrackPiece {
  double length = 0;  // [m] > 0
  double radius = 0;  // [m]; 0: straight, > 0 curves to the left (+y), < 0 to the right
};

class TrackAlignment {
 public:
  TrackAlignment() = default;
  explicit TrackAlignment(std::vector<TrackPiece> pieces);

  bool straight() const { return straight_; }
  const std::vector<TrackPiece>& pieces() const { return pieces_; }

  // Centre line at station s (beyond the ends: the end pieces continued),
  // its unit tangent and its unit normal to the left of the tangent.
  Eigen::Vector2d point(double s) const;
  Eigen::Vector2d tangent(double s) const;
  Eigen::Vector2d normal(double s) const;
  // Station of the centre-line point whose normal passes through p.
  double station(const Eigen::Vector2d& p) const;

 private:
  struct PieceStart {
    double s = 0;
    Eigen::Vector2d p = Eigen::Vector2d::Zero();
    double heading = 0;  // [rad] from +x
  };
  std::size_t piece_at(double s) const;
  // Station of p on piece k (its local projection, not clamped).
  double station_on(std::size_t k, const Eigen::Vector2d& p) const;
  std::vector<TrackPiece> pieces_;
  std::vector<PieceStart> starts_;
  bool straight_ = true;
};

}  // namespace pcsim::catenary
