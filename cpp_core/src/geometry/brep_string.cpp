#include "geometry/brep_string.h"

#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <Standard_Failure.hxx>
#include <sstream>

#include "tessella/errors.h"

namespace tessella {

TopoDS_Shape shape_from_brep_string(const std::string& brep) {
  TopoDS_Shape shape;
  try {
    std::istringstream in(brep);
    BRep_Builder builder;
    BRepTools::Read(shape, in, builder);
  } catch (const Standard_Failure& e) {
    throw InvalidGeometry(std::string("cannot read the BRep string: ") + e.GetMessageString());
  }
  if (shape.IsNull()) throw InvalidGeometry("the BRep string holds no shape");
  return shape;
}

}  // namespace tessella
