// Reading a shape from a BRep string (BRepTools::Write format), the one way
// a face or a face set enters the core.
#pragma once

#include <TopoDS_Shape.hxx>
#include <string>

namespace tessella {

// The shape; throws InvalidGeometry when the text is no BRep or holds no shape.
TopoDS_Shape shape_from_brep_string(const std::string& brep);

}  // namespace tessella
