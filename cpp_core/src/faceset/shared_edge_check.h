// The face set's promise checked on the joined result: along every edge two
// faces share, consecutive nodes are joined by one rod that is a side of one
// panel of each face. What the join could not keep (a T-junction, a gap) is
// counted and located, for the result's warning: a fabricator must know
// where two faces' parts will not fit, even where the join has a defect no
// test has met yet.
#pragma once

#include <array>
#include <vector>

#include "faceset/face_set_impl.h"
#include "tessella/panel_mesh.h"

namespace tessella {

struct SharedEdgeCheck {
  int segments = 0;                        // segments between consecutive nodes along shared edges
  int unmatched = 0;                       // of them, without a side of one panel of each face
  Vec3 first_at = Vec3::Zero();            // the first unmatched segment's middle
  std::array<int, 2> first_faces{-1, -1};  // its edge's faces (set order)
};

// `panel_face`: each panel's face in set order (parallel to mesh.panels).
SharedEdgeCheck check_shared_edges(const FaceSet::Impl& set, const PanelMesh& mesh,
                                   const std::vector<int>& panel_face);

}  // namespace tessella
