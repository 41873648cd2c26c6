#pragma once
// Where and which way a run is loaded, read from the spec its file holds (/spec json) and its
// scenario (the root's "scenario" attribute), for the arrows of the field pictures: the pulled and
// the held face of a dynamic-tension sample, an impact's driven regions, tractions and projectile,
// the piston that strikes a tank's or a column's water. A run of another scenario has none.
#include <array>
#include <string>
#include <vector>

#include "io/hdf5_file.hpp"

namespace rupture::render {

struct LoadingMark {
  enum class Kind {
    FaceArrow,  ///< arrows along the face (axis, side) of the drawn body, pointing along `direction`
    FaceHeld,   ///< the face (axis, side) is held: a hatched line
    BoxArrow,   ///< one arrow from the centre of [lo, hi] along `direction`
  };
  Kind kind = Kind::FaceArrow;
  int axis = 0;                         ///< FaceArrow, FaceHeld: 0 x, 1 y, 2 z
  int side = 1;                         ///< FaceArrow, FaceHeld: +1 the face at the largest coordinate
  std::array<double, 3> lo{}, hi{};     ///< BoxArrow: m
  std::array<double, 3> direction{};    ///< unit vector; zero for FaceHeld
  std::string label;                    ///< what loads there, for people: "pulled at 1e6 /s"
};

/// The run's loading marks; none when the file holds no spec or its scenario has no mark here.
/// `root` as in FieldImageRequest.
std::vector<LoadingMark> loadingMarks(const io::Hdf5File& file, const std::string& root);

}  // namespace rupture::render
