// The part of a set of Clipper polygons inside a box (or any clip polygon),
// collinear points kept: what the grid clippers cut the trim domain with, part
// by part, before they cut single cells.
#pragma once

#include <clipper.hpp>

namespace tessella {

// `fill`: how the subject's polygons count (the trim loops by parity; Clipper's
// own output, holes turning the other way, by winding).
inline ClipperLib::Paths clip_to_box(const ClipperLib::Paths& subject,
                                     ClipperLib::PolyFillType fill, const ClipperLib::Path& box) {
  ClipperLib::Clipper clipper(ClipperLib::ioPreserveCollinear);
  clipper.AddPaths(subject, ClipperLib::ptSubject, true);
  clipper.AddPath(box, ClipperLib::ptClip, true);
  ClipperLib::Paths piece;
  clipper.Execute(ClipperLib::ctIntersection, piece, fill, ClipperLib::pftNonZero);
  return piece;
}

}  // namespace tessella
