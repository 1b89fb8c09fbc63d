// The bed surface the particles move on, on the host: the data the particle kernels sample it from
// (kernels/particles/particle_common.cl, bed_gradient; kernels/particles/particle_walls.cl, face_rise
// and walled_bed_gradient) and the same functions in double, the CPU reference of those kernel
// functions (tests/kernels/test_particle_bed_surface.cpp) and the g_n of the particle records.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "core/Grid.hpp"

namespace talus::particles {

class ParticleBedSurface {
 public:
  /// `bed`, `mask`: the DEM and its domain cells; `slopeX`, `slopeY`: the limited (minmod) bed slopes
  /// per cell that the grid's solids reconstruct the bed with (flow::computeSlopeGravity); `edgeWalls`,
  /// `nodataWalls`: whether the raster edge and faces to nodata cells are walls (ParticleSettings).
  ParticleBedSurface(const Grid& grid, const std::vector<double>& bed, const std::vector<uint8_t>& mask,
                     const std::vector<double>& slopeX, const std::vector<double>& slopeY, bool edgeWalls,
                     bool nodataWalls);

  /// Per bilinear patch (indexed by its lower-left cell centre, rows of cells): the slopes of its two
  /// edges from that centre and its twist (bed_gradient). Nodata cells take the mean of their nearest
  /// domain cells, so the surface continues flat into a nodata hole.
  const std::vector<double>& patches() const { return patch_; }
  /// The DEM as the kernels read it for face_rise (0 in nodata cells, never read there).
  const std::vector<double>& cellBed() const { return bed_; }
  /// The limited slopes, x then y (rows of cells).
  const std::vector<double>& limitedSlopes() const { return slope_; }

  /// bed_gradient: the gradient of the bilinear surface at (x, y) [m/m].
  std::array<double, 2> gradient(double x, double y) const;
  /// face_rise: the jump of the reconstructed bed at the face from cell `here` to (a, b) along `axis`
  /// (d = +1 / -1) [m]; infinite across a wall boundary, 0 across an open one.
  double faceRise(int here, int a, int b, int axis, int d) const;
  /// walled_bed_gradient: the gradient at (x, y) of the bed a particle with column `column` [m] can
  /// reach, with the corners behind a wall replaced by its own cell's ghost elevation.
  std::array<double, 2> walledGradient(double x, double y, double column) const;
  /// walled_bed_offset: that bed's elevation at (x, y) less the bilinear surface's [m].
  double walledOffset(double x, double y, double column) const;
  /// The bilinear surface's elevation at (x, y) [m] (nodata cells filled as for patches()).
  double elevation(double x, double y) const;

 private:
  /// walled_patch (particle_walls.cl): the fractional position in the patch and each corner's change.
  struct WalledPatch {
    double u = 0, v = 0;
    double d[4] = {0, 0, 0, 0};
    bool walls = false;
  };
  WalledPatch walledPatch(double x, double y, double column) const;

  Grid grid_;
  std::vector<uint8_t> mask_;
  std::vector<double> bed_, slope_, patch_, z_;
  bool edgeWalls_, nodataWalls_;
};

}  // namespace talus::particles
