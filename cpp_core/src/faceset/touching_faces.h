// Faces that touch along edges they do not share: faces of several objects,
// a STEP file's unsewn faces, faces copied out of their shell. Their common
// boundaries are separate edges (one per face), so a face set would see no
// shared edge and the two sides' nodes would not agree. Such faces are sewn
// (OCCT's BRepBuilderAPI_Sewing) so that those boundaries become one edge.
#pragma once

#include <TopoDS_Face.hxx>
#include <vector>

namespace tessella {

// Whether two of the faces have free boundary edges (bounding one face) that
// run along each other: both ends and the middle within `tolerance` (mm).
bool have_touching_free_edges(const std::vector<TopoDS_Face>& faces, double tolerance);

// The faces sewn within `tolerance` (mm), in the order given (faces[i]'s
// sewn copy at i; a face the sewing left alone is itself). Edges the faces
// already share stay shared.
std::vector<TopoDS_Face> sew_faces(const std::vector<TopoDS_Face>& faces, double tolerance);

}  // namespace tessella
